"""Cantilever under a dead end traction, for the volumetric-locking benchmark
(tests/materials/locking.cpp): the same compressible neo-Hookean solid (Eq. 3.1) discretised two
ways on tetrahedra.

  *_p1     displacement-only P1 with neo_hookean_compressible; coefficient u_p1, constants G, K
  *_mixed  mixed u-p P2-P1 with neo_hookean_incompressible, bulk_compliance = 1/K; coefficient
           w = (u, p), constants G, bulk_compliance. Eliminating p = K (J - 1) gives back the
           energy of *_p1, so both discretise one continuum problem.

The constant vector `traction` is a dead load per reference area on the facets tagged 2.
load_work_* = int traction . u ds(2) is the work of that load; divided by the resultant
|traction| area it is the mean deflection of the loaded face along the load.
"""
import ufl
import materials

cell = "tetrahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
G = ufl.Constant(mesh)
K = ufl.Constant(mesh)
bulk_compliance = ufl.Constant(mesh)
traction = ufl.Constant(mesh, shape=(3,))  # dead load per reference area on ds(2)


def measures(degree):
    q = materials.quadrature_degree(degree)
    return ufl.dx(metadata={"quadrature_degree": q}), ufl.ds(metadata={"quadrature_degree": q})


def displacement_p1():
    V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 1))
    u = ufl.Coefficient(V)
    v = ufl.TestFunction(V)
    dx, ds = measures(1)
    psi = materials.neo_hookean_compressible(materials.deformation_gradient(u), G, K)
    residual = ufl.derivative(psi * dx, u, v) - ufl.dot(traction, v) * ds(2)
    tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
    return u, residual, tangent, ufl.dot(traction, u) * ds(2)


def mixed_p2_p1():
    W = ufl.FunctionSpace(mesh, ufl.MixedElement([ufl.VectorElement("Lagrange", cell, 2),
                                                  ufl.FiniteElement("Lagrange", cell, 1)]))
    w = ufl.Coefficient(W)
    dw = ufl.TestFunction(W)
    u, p = ufl.split(w)
    v, _ = ufl.split(dw)
    dx, ds = measures(2)
    lagrangian = materials.neo_hookean_incompressible(materials.deformation_gradient(u), p, G,
                                                      bulk_compliance)
    residual = ufl.derivative(lagrangian * dx, w, dw) - ufl.dot(traction, v) * ds(2)
    tangent = ufl.derivative(residual, w, ufl.TrialFunction(W))
    return w, residual, tangent, ufl.dot(traction, u) * ds(2)


# Module-level names name the generated forms and coefficients
u_p1, residual_p1, tangent_p1, load_work_p1 = displacement_p1()
w, residual_mixed, tangent_mixed, load_work_mixed = mixed_p2_p1()

forms = [residual_p1, tangent_p1, load_work_p1, residual_mixed, tangent_mixed, load_work_mixed]
