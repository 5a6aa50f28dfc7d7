"""Spherical shell inflated by a follower pressure p on its inner surface (facet tag 1):
compressible neo-Hookean (thesis Eq. 3.1), P2 tetrahedra.

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
G = ufl.Constant(mesh)
K = ufl.Constant(mesh)
p = ufl.Constant(mesh)  # cavity pressure

F = materials.deformation_gradient(u)
psi = materials.neo_hookean_compressible(F, G, K)
q = materials.quadrature_degree(degree)
dx = ufl.dx(metadata={"quadrature_degree": q})
ds = ufl.ds(metadata={"quadrature_degree": q})
v = ufl.TestFunction(V)
N = ufl.FacetNormal(mesh)
residual = (ufl.derivative(psi * dx, u, v)
            + p * ufl.det(F) * ufl.inner(ufl.inv(F).T * N, v) * ds(1))
tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
det_F = ufl.det(F)  # admissibility: det F > 0

forms = [residual, tangent]
expressions = [(det_F, materials.quadrature_points(cell, q))]
