"""Manufactured solution for the compressible neo-Hookean solid (thesis Eq. 3.1), P1 and P2.

The displacement u_exact below is smooth, fully three-dimensional and large enough (|Grad u| up
to ~0.3) to exercise the nonlinearity. The body force b = -Div P(u_exact) is derived by UFL from
the same energy the solver uses, so the discrete solution converges to u_exact at the rates of
the element: L2 error O(h^(p+1)), H1 error O(h^p).
"""
import ufl
import materials

cell = "tetrahedron"
coordinate_element = ufl.VectorElement("Lagrange", cell, 1)
mesh = ufl.Mesh(coordinate_element)
x = ufl.SpatialCoordinate(mesh)
G = ufl.Constant(mesh)
K = ufl.Constant(mesh)

u_exact = 0.1 * ufl.as_vector([ufl.sin(ufl.pi * x[1]) * (1 + x[2]),
                               ufl.sin(ufl.pi * x[2]) * (1 + x[0]),
                               ufl.sin(ufl.pi * x[0]) * (1 + x[1])])
F_exact = materials.deformation_gradient(u_exact)
body_force = -ufl.div(materials.first_piola(materials.neo_hookean_compressible(F_exact, G, K),
                                            F_exact))
# The errors are integrated well beyond the discretisation order, so they measure the solution.
dx_error = ufl.dx(metadata={"quadrature_degree": 8})


def problem(degree):
    V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, degree))
    u, v, du = ufl.Coefficient(V), ufl.TestFunction(V), ufl.TrialFunction(V)
    F = materials.deformation_gradient(u)
    psi = materials.neo_hookean_compressible(F, G, K)
    dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(degree) + 2})
    residual = ufl.derivative(psi * dx, u, v) - ufl.inner(body_force, v) * dx
    tangent = ufl.derivative(residual, u, du)
    e = u - u_exact
    return (u, residual, tangent, ufl.inner(e, e) * dx_error,
            ufl.inner(ufl.grad(e), ufl.grad(e)) * dx_error)


# Module-level names become the names of the generated forms and coefficients (u_p1, u_p2)
u_p1, residual_p1, tangent_p1, error_l2_p1, error_h1_p1 = problem(1)
u_p2, residual_p2, tangent_p2, error_l2_p2, error_h1_p2 = problem(2)
forms = [residual_p1, tangent_p1, error_l2_p1, error_h1_p1,
         residual_p2, tangent_p2, error_l2_p2, error_h1_p2]
