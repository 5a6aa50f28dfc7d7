"""Block under stretch and twist: compressible neo-Hookean (thesis Eq. 3.1) on tetrahedra.

Forms for P1 and P2 displacements (suffix _p1, _p2), chosen by the scene's --degree.
"""
import ufl
import materials

cell = "tetrahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
G = ufl.Constant(mesh)  # shear modulus
K = ufl.Constant(mesh)  # bulk modulus


def block(degree):
    V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, degree))
    u = ufl.Coefficient(V)  # displacement
    F = materials.deformation_gradient(u)
    psi = materials.neo_hookean_compressible(F, G, K)
    q = materials.quadrature_degree(degree)
    dx = ufl.dx(metadata={"quadrature_degree": q})
    residual = ufl.derivative(psi * dx, u, ufl.TestFunction(V))
    tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
    return u, residual, tangent, psi * dx, materials.cauchy_stress(psi, F), psi, ufl.det(F)


# Module-level names name the generated forms, expressions and coefficients
u_p1, residual_p1, tangent_p1, energy_p1, stress_p1, psi_p1, det_F_p1 = block(1)
u_p2, residual_p2, tangent_p2, energy_p2, stress_p2, psi_p2, det_F_p2 = block(2)

forms = [residual_p1, tangent_p1, energy_p1, residual_p2, tangent_p2, energy_p2]
# Cell-wise output at the centroid, and the solver's admissibility check det F > 0 at the
# quadrature points
centroid = materials.centroid(cell)
expressions = [(stress_p1, centroid), (psi_p1, centroid),
               (det_F_p1, materials.quadrature_points(cell, materials.quadrature_degree(1))),
               (stress_p2, centroid), (psi_p2, centroid),
               (det_F_p2, materials.quadrature_points(cell, materials.quadrature_degree(2)))]
