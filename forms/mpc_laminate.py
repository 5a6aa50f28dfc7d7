"""Two-phase laminate cell of tests/mpc_laminate.cpp: compressible neo-Hookean (Eq. 3.1) and
small-strain linear elasticity with cell-wise moduli, P1 tetrahedra.

G and K are DG0 coefficients (one value per cell, one per phase in the test) instead of the
constants of compressible.py, so one form holds both phases:
  residual_nh, tangent_nh   neo-Hookean
  residual_le, tangent_le   linear elasticity
"""
import ufl
import materials

cell = "tetrahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 1))
Q = ufl.FunctionSpace(mesh, ufl.FiniteElement("DG", cell, 0))
u = ufl.Coefficient(V)
G = ufl.Coefficient(Q)  # shear modulus per cell
K = ufl.Coefficient(Q)  # bulk modulus per cell


def problem(energy):
    psi = energy(materials.deformation_gradient(u), G, K)
    dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(1)})
    residual = ufl.derivative(psi * dx, u, ufl.TestFunction(V))
    return residual, ufl.derivative(residual, u, ufl.TrialFunction(V))


residual_nh, tangent_nh = problem(materials.neo_hookean_compressible)
residual_le, tangent_le = problem(materials.linear_elastic)

forms = [residual_nh, tangent_nh, residual_le, tangent_le]
