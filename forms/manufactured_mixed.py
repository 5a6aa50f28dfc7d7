"""Manufactured solution for the nearly incompressible mixed neo-Hookean law (thesis Eq. 1.10
in the u-p form of materials.neo_hookean_incompressible) on the three mixed elements of the
project: P2-P1 tetrahedra, Q2-Q1 and Q1-P0 hexahedra.

The residual and tangent are those of forms/_mixed.py, the kernels the scenes run, plus the
source terms that make (u_exact, p_exact) the exact solution:
  - u_exact is the composition of three shears (each adds a function of the other two
    coordinates to one coordinate), so det F = 1 exactly: a smooth, three-dimensional,
    volume-preserving deformation with |Grad u| up to 0.32 (amplitude a = 0.05; at a = 0.1,
    |Grad u| up to 0.67, Newton failed on the finer P2-P1 and Q2-Q1 meshes even from the
    interpolant of the exact solution, with near-singular tangents);
  - p_exact is an independent smooth field, |p_exact| <= 0.25 G;
  - the body force b = -Div P(u_exact, p_exact), with P = dL/dF of the same Lagrangian;
  - the traction t = P(u_exact, p_exact) N on the boundary: it acts on the faces without
    Dirichlet conditions (on the others the residual rows are replaced by the conditions), so
    that the mean pressure is set by the tractions as in the scenes, not by 1/K times the
    volume error of the interpolated boundary data;
  - the volumetric source s = J(u_exact) - 1 - bulk_compliance p_exact of the pressure
    equation (dL/dp = s).
"""
import ufl
import _mixed
import materials


def u_exact_of(x):
    """x -> x + u: shears along z (by x, y), then x (by y, z), then y (by x, z)."""
    a = 0.05
    y = x + ufl.as_vector([0, 0, a * ufl.sin(ufl.pi * x[0]) * (1 + x[1])])
    y = y + ufl.as_vector([a * ufl.sin(ufl.pi * y[1]) * (1 + y[2]), 0, 0])
    y = y + ufl.as_vector([0, a * ufl.sin(ufl.pi * y[2]) * (1 + y[0]), 0])
    return y - x


def p_exact_of(x):
    return 0.1 * ufl.cos(ufl.pi * x[0]) * ufl.sin(ufl.pi * x[1]) * (1 + x[2]) + 0.05


def problem(cell, displacement_degree):
    """The mixed problem with sources; returns the names FFCx should see."""
    out, _, _ = _mixed.build(cell, displacement_degree)
    w, G, bulk_compliance = out["w"], out["G"], out["bulk_compliance"]
    W = w.ufl_function_space()
    mesh = W.ufl_domain()
    x = ufl.SpatialCoordinate(mesh)
    u_exact, p_exact = u_exact_of(x), p_exact_of(x)
    F_exact = materials.deformation_gradient(u_exact)
    P_exact = materials.first_piola(
        materials.neo_hookean_incompressible(F_exact, p_exact, G, bulk_compliance), F_exact)
    body_force = -ufl.div(P_exact)
    traction = P_exact * ufl.FacetNormal(mesh)
    volume_source = ufl.det(F_exact) - 1 - bulk_compliance * p_exact
    v, q = ufl.split(ufl.TestFunction(W))
    # The sources are smooth: two orders above the element's own quadrature keep their
    # quadrature error far below the discretisation error
    metadata = {"quadrature_degree": materials.quadrature_degree(displacement_degree) + 2}
    dx, ds = ufl.dx(metadata=metadata), ufl.ds(metadata=metadata)
    residual = (out["residual_nh"] - ufl.inner(body_force, v) * dx
                - ufl.inner(traction, v) * ds - volume_source * q * dx)
    u, p = ufl.split(w)
    # The errors are integrated well beyond the discretisation order, so they measure the
    # solution
    dx_error = ufl.dx(metadata={"quadrature_degree": 8})
    e_u, e_p = u - u_exact, p - p_exact
    return {"w": w, "G": G, "bulk_compliance": bulk_compliance, "residual": residual,
            "tangent": out["tangent_nh"],  # the sources do not depend on w
            "error_u_l2": ufl.inner(e_u, e_u) * dx_error,
            "error_u_h1": ufl.inner(ufl.grad(e_u), ufl.grad(e_u)) * dx_error,
            "error_p_l2": e_p**2 * dx_error, "det_F": out["det_F"]}


forms, expressions = [], []
# Module-level names become the names of the generated forms, coefficients and constants
# (residual_p2p1, w_p2p1, G_p2p1, ...): one set per element, each on its own UFL mesh
for _element, _cell, _degree in (("p2p1", "tetrahedron", 2), ("q2q1", "hexahedron", 2),
                                 ("q1p0", "hexahedron", 1)):
    _names = problem(_cell, _degree)
    globals().update({f"{name}_{_element}": value for name, value in _names.items()})
    forms += [_names[name] for name in ("residual", "tangent", "error_u_l2", "error_u_h1",
                                        "error_p_l2")]
    # det F at the quadrature points, where the solver rejects inverted iterates
    expressions.append((_names["det_F"], materials.quadrature_points(
        _cell, materials.quadrature_degree(_degree))))
