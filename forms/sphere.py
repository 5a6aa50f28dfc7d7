"""Spherical shell inflated by a follower pressure p on its inner surface (facet tag 1):
compressible Mooney-Rivlin (C01 = 0: the neo-Hookean solid of thesis Eq. 3.1 with G = 2 C10),
P2 tetrahedra.

The pressure acts on the current inner surface: its virtual work is -p J F^-T N . v dA, with N
the reference outward normal of the solid (pointing into the cavity).
"""
import ufl
import materials

cell = "tetrahedron"
degree = 2
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, degree))

u = ufl.Coefficient(V)
C10 = ufl.Constant(mesh)
C01 = ufl.Constant(mesh)
K = ufl.Constant(mesh)
p = ufl.Constant(mesh)  # cavity pressure
rho = ufl.Constant(mesh)  # mass density (damped dynamics)

F = materials.deformation_gradient(u)
psi = materials.mooney_rivlin_compressible(F, C10, C01, K)
q = materials.quadrature_degree(degree)
dx = ufl.dx(metadata={"quadrature_degree": q})
ds = ufl.ds(metadata={"quadrature_degree": q})
v = ufl.TestFunction(V)
N = ufl.FacetNormal(mesh)
residual = (ufl.derivative(psi * dx, u, v)
            + p * ufl.det(F) * ufl.inner(ufl.inv(F).T * N, v) * ds(1))
tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
# Damped dynamics (gelx::DampedDynamics): the consistent mass and the stored (strain) energy
mass = rho * ufl.inner(ufl.TrialFunction(V), v) * dx
strain_energy = psi * dx
det_F = ufl.det(F)  # admissibility: det F > 0
stress = materials.cauchy_stress(psi, F)

forms = [residual, tangent, mass, strain_energy]
# The admissibility check at the quadrature points; stress and energy density per cell (output)
centroid = materials.centroid(cell)
expressions = [(det_F, materials.quadrature_points(cell, q)), (stress, centroid),
               (psi, centroid)]
