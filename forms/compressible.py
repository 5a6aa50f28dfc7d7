"""Compressible laws on tetrahedra, displacement-only: neo-Hookean (Eq. 3.1) with a per-cell
prestretch F0 (F = Fe F0; F0 = I where nothing is prestretched), compressible Mooney-Rivlin and
small-strain linear elasticity, for the constitutive comparison of chapter 2.

One displacement coefficient per degree (u_p1, u_p2) shared by the laws; forms and expressions
are suffixed law_degree:
  nh_p1, nh_p2   neo-Hookean with prestretch; constants G, K; coefficient F0 (DG0 3x3 tensor)
  mr_p2          Mooney-Rivlin; constants C10, C01, K
  le_p2          linear elasticity; constants G, K
Each law exports stress_* and psi_* at the cell midpoints; det_F_p1, det_F_p2 (quadrature
points) are the admissibility expressions.
"""
import ufl
import materials

cell = "tetrahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
G = ufl.Constant(mesh)
K = ufl.Constant(mesh)
C10 = ufl.Constant(mesh)
C01 = ufl.Constant(mesh)
F0 = ufl.Coefficient(ufl.FunctionSpace(mesh, ufl.TensorElement("DG", cell, 0)))
V1 = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 1))
V2 = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 2))
u_p1 = ufl.Coefficient(V1)
u_p2 = ufl.Coefficient(V2)


def problem(u, degree, energy, stress):
    V = u.ufl_function_space()
    F = materials.deformation_gradient(u)
    psi = energy(F)
    dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(degree)})
    residual = ufl.derivative(psi * dx, u, ufl.TestFunction(V))
    tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
    return residual, tangent, stress(psi, F), psi


def nh(F):
    return materials.prestretched(materials.neo_hookean_compressible, F, F0, G, K)


def mr(F):
    return materials.mooney_rivlin_compressible(F, C10, C01, K)


def le(F):
    return materials.linear_elastic(F, G, K)


residual_nh_p1, tangent_nh_p1, stress_nh_p1, psi_nh_p1 = problem(u_p1, 1, nh,
                                                                 materials.cauchy_stress)
residual_nh_p2, tangent_nh_p2, stress_nh_p2, psi_nh_p2 = problem(u_p2, 2, nh,
                                                                 materials.cauchy_stress)
residual_mr_p2, tangent_mr_p2, stress_mr_p2, psi_mr_p2 = problem(u_p2, 2, mr,
                                                                 materials.cauchy_stress)
residual_le_p2, tangent_le_p2, stress_le_p2, psi_le_p2 = problem(u_p2, 2, le,
                                                                 materials.linear_elastic_stress)
det_F_p1 = ufl.det(materials.deformation_gradient(u_p1))
det_F_p2 = ufl.det(materials.deformation_gradient(u_p2))

forms = [residual_nh_p1, tangent_nh_p1, residual_nh_p2, tangent_nh_p2,
         residual_mr_p2, tangent_mr_p2, residual_le_p2, tangent_le_p2]
centroid = materials.centroid(cell)
expressions = [(e, centroid) for e in (stress_nh_p1, psi_nh_p1, stress_nh_p2, psi_nh_p2,
                                       stress_mr_p2, psi_mr_p2, stress_le_p2, psi_le_p2)]
expressions += [(det_F_p1, materials.quadrature_points(cell, materials.quadrature_degree(1))),
                (det_F_p2, materials.quadrature_points(cell, materials.quadrature_degree(2)))]
