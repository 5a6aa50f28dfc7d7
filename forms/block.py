"""Block under stretch and twist: compressible neo-Hookean (thesis Eq. 3.1), P2 tetrahedra."""
import ufl
import materials

cell = "tetrahedron"
degree = 2
coordinate_element = ufl.VectorElement("Lagrange", cell, 1)
mesh = ufl.Mesh(coordinate_element)
V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, degree))

u = ufl.Coefficient(V)  # displacement
v = ufl.TestFunction(V)
du = ufl.TrialFunction(V)
G = ufl.Constant(mesh)  # shear modulus
K = ufl.Constant(mesh)  # bulk modulus

F = materials.deformation_gradient(u)
psi = materials.neo_hookean_compressible(F, G, K)
dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(degree)})

residual = ufl.derivative(psi * dx, u, v)
tangent = ufl.derivative(residual, u, du)
energy = psi * dx

# Cell-wise output and the admissibility check of the solver
stress = materials.cauchy_stress(psi, F)
det_F = ufl.det(F)

forms = [residual, tangent, energy]
expressions = [(stress, materials.centroid(cell)),
               (psi, materials.centroid(cell)),
               (det_F, materials.quadrature_points(cell, materials.quadrature_degree(degree)))]
