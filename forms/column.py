"""Slender column under a dead axial load: compressible neo-Hookean (Eq. 3.1), P2 tetrahedra.

The load is a dead traction -q e_z on the facets tagged 2 (the top end). The functionals
measure the symmetry of a buckling mode v about the column's mid-length z = L/2.
"""
import ufl
import materials

cell = "tetrahedron"
degree = 2
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, degree))
x = ufl.SpatialCoordinate(mesh)

u = ufl.Coefficient(V)
G = ufl.Constant(mesh)
K = ufl.Constant(mesh)
q = ufl.Constant(mesh)  # axial traction on the top end (compressive when positive)
rho = ufl.Constant(mesh)  # mass density (damped dynamics)

F = materials.deformation_gradient(u)
psi = materials.neo_hookean_compressible(F, G, K)
dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(degree)})
ds = ufl.ds(metadata={"quadrature_degree": materials.quadrature_degree(degree)})
v = ufl.TestFunction(V)
residual = ufl.derivative(psi * dx, u, v) + q * v[2] * ds(2)
# The same column of small-strain linear elasticity (ColumnParameters::law): a linear problem,
# whose vibration the trapezoidal rule follows with its energy exactly conserved
psi_linear = materials.linear_elastic(F, G, K)
residual_linear = ufl.derivative(psi_linear * dx, u, v) + q * v[2] * ds(2)
tangent_linear = ufl.derivative(residual_linear, u, ufl.TrialFunction(V))
strain_energy_linear = psi_linear * dx
potential_energy = psi * dx + q * u[2] * ds(2)  # the residual is its derivative
tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
# Damped dynamics (gelx::DampedDynamics): the consistent mass and the stored (strain) energy
mass = rho * ufl.inner(ufl.TrialFunction(V), v) * dx
strain_energy = psi * dx

# Symmetry of the lateral deflection v_x of a mode about z = L/2
mode = ufl.Coefficient(V)
half_length = ufl.Constant(mesh)
mode_odd_part = mode[0] * (x[2] - half_length) * dx
mode_odd_scale = abs(mode[0] * (x[2] - half_length)) * dx
mode_even_part = mode[0] * dx
mode_even_scale = abs(mode[0]) * dx

det_F = ufl.det(F)  # admissibility: det F > 0
stress = materials.cauchy_stress(psi, F)

forms = [residual, tangent, potential_energy, mass, strain_energy, mode_odd_part, mode_odd_scale,
         mode_even_part, mode_even_scale, residual_linear, tangent_linear, strain_energy_linear]
# The admissibility check at the quadrature points; stress and energy density per cell (output)
centroid = materials.centroid(cell)
expressions = [(det_F, materials.quadrature_points(cell, materials.quadrature_degree(degree))),
               (stress, centroid), (psi, centroid)]
