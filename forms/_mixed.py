"""Builder shared by mixed_tet.py and mixed_hex.py: incompressible laws in mixed
displacement-pressure form on Taylor-Hood pairs (P2-P1 tetrahedra, Q2-Q1 hexahedra).

FFCx names coefficients and constants after the module-level variables that hold them, so each
form file assigns what build() returns to module-level names.
"""
import ufl
import materials


def build(cell):
    mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
    element = ufl.MixedElement([ufl.VectorElement("Lagrange", cell, 2),
                                ufl.FiniteElement("Lagrange", cell, 1)])
    W = ufl.FunctionSpace(mesh, element)
    w = ufl.Coefficient(W)  # (u, p): displacement and pressure (mean Cauchy stress)
    u, p = ufl.split(w)
    F = materials.deformation_gradient(u)
    c = {name: ufl.Constant(mesh) for name in ("G", "C10", "C01", "bulk_compliance")}
    dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(2)})
    laws = {"nh": materials.neo_hookean_incompressible(F, p, c["G"], c["bulk_compliance"]),
            "mr": materials.mooney_rivlin_incompressible(F, p, c["C10"], c["C01"],
                                                         c["bulk_compliance"])}
    out = {"w": w, **c}
    forms, expressions = [], []
    centroid = materials.centroid(cell)
    for name, lagrangian in laws.items():
        energy = materials.mixed_stored_energy(lagrangian, F, p, c["bulk_compliance"])
        residual = ufl.derivative(lagrangian * dx, w, ufl.TestFunction(W))
        tangent = ufl.derivative(residual, w, ufl.TrialFunction(W))
        out.update({f"residual_{name}": residual, f"tangent_{name}": tangent,
                    f"stress_{name}": materials.cauchy_stress(lagrangian, F),
                    f"psi_{name}": energy})
        forms += [residual, tangent]
        expressions += [(out[f"stress_{name}"], centroid), (energy, centroid)]
    out["det_F"] = ufl.det(F)
    expressions.append((out["det_F"],
                        materials.quadrature_points(cell, materials.quadrature_degree(2))))
    return out, forms, expressions
