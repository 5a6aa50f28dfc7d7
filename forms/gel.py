"""Flory-Rehner gel in a swollen reference state (thesis Eq. 4.28) on tetrahedra, P1 and P2.

Constants: n = N nu / V_m, phi0 (reference volume fraction), chi_A, chi_B and the temperature
T (chi = chi_A + chi_B T, T changed from load step to load step), nu (solvent molecule volume)
and length_scale (appendix B): the energy scale is kT/nu * length_scale. Exports per degree:
the Cauchy stress, the energy density, J and the admissibility J - phi0 (at quadrature points),
which the Newton line search keeps positive.
"""
import ufl
import materials

cell = "tetrahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
n = ufl.Constant(mesh)
phi0 = ufl.Constant(mesh)
chi_A = ufl.Constant(mesh)
chi_B = ufl.Constant(mesh)
T = ufl.Constant(mesh)
nu = ufl.Constant(mesh)
length_scale = ufl.Constant(mesh)


def gel(degree):
    V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, degree))
    u = ufl.Coefficient(V)
    F = materials.deformation_gradient(u)
    chi = materials.chi_linear(chi_A, chi_B, T)
    psi = materials.flory_rehner_gel(F, n, phi0, chi, materials.energy_scale(T, nu, length_scale))
    q = materials.quadrature_degree(degree)
    dx = ufl.dx(metadata={"quadrature_degree": q})
    residual = ufl.derivative(psi * dx, u, ufl.TestFunction(V))
    tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
    J = ufl.det(F)
    return u, residual, tangent, materials.cauchy_stress(psi, F), psi, J, J - phi0


u_p1, residual_p1, tangent_p1, stress_p1, psi_p1, J_p1, margin_p1 = gel(1)
u_p2, residual_p2, tangent_p2, stress_p2, psi_p2, J_p2, margin_p2 = gel(2)
forms = [residual_p1, tangent_p1, residual_p2, tangent_p2]
centroid = materials.centroid(cell)
expressions = [(stress_p1, centroid), (psi_p1, centroid), (J_p1, centroid),
               (margin_p1, materials.quadrature_points(cell, materials.quadrature_degree(1))),
               (stress_p2, centroid), (psi_p2, centroid), (J_p2, centroid),
               (margin_p2, materials.quadrature_points(cell, materials.quadrature_degree(2)))]
