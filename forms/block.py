"""Block under stretch and twist on tetrahedra: a compressible law of materials.py, chosen by
the scene's --law, with P1 or P2 displacements (--degree).

One displacement coefficient per degree (u_p1, u_p2) shared by the laws; forms and expressions
are suffixed law_degree:
  nh_p1, nh_p2          neo-Hookean, thesis Eq. 3.1 (constants G, K)
  nh_log_p1, nh_log_p2  neo-Hookean with a ln J volumetric term, dolfinx's hyperelasticity
                        demo (G, K)
  mr_p1, mr_p2          Mooney-Rivlin, C10 = (1 - s) G/2, C01 = s G/2 (G, K, s = mooney_share)
  le_p1, le_p2          small-strain linear elasticity (G, K)
Each exports residual, tangent and energy forms, stress and psi at the cell midpoints; det_F_p1,
det_F_p2 (quadrature points) are the admissibility expressions.
"""
import ufl
import materials

cell = "tetrahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
G = ufl.Constant(mesh)  # shear modulus
K = ufl.Constant(mesh)  # bulk modulus
mooney_share = ufl.Constant(mesh)  # C01 / (C10 + C01), law mr
u_p1 = ufl.Coefficient(ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 1)))
u_p2 = ufl.Coefficient(ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 2)))

laws = {"nh": lambda F: materials.neo_hookean_compressible(F, G, K),
        "nh_log": lambda F: materials.neo_hookean_log(F, G, K),
        "mr": lambda F: materials.mooney_rivlin_compressible(F, (1 - mooney_share) * G / 2,
                                                             mooney_share * G / 2, K),
        "le": lambda F: materials.linear_elastic(F, G, K)}


def block(u, degree, law):
    V = u.ufl_function_space()
    F = materials.deformation_gradient(u)
    psi = laws[law](F)
    dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(degree)})
    residual = ufl.derivative(psi * dx, u, ufl.TestFunction(V))
    tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
    stress = (materials.linear_elastic_stress if law == "le" else materials.cauchy_stress)
    return residual, tangent, psi * dx, stress(psi, F), psi


# Module-level names name the generated forms and expressions (FFCx)
forms, expressions = [], []
centroid = materials.centroid(cell)
for _law in laws:
    for _degree, _u in ((1, u_p1), (2, u_p2)):
        _names = [f"{kind}_{_law}_p{_degree}"
                  for kind in ("residual", "tangent", "energy", "stress", "psi")]
        _objects = block(_u, _degree, _law)
        globals().update(zip(_names, _objects))
        forms += _objects[:3]
        expressions += [(e, centroid) for e in _objects[3:]]
del _law, _degree, _u, _names, _objects  # (FFCx names a coefficient by its variable: u_p1, u_p2)
det_F_p1 = ufl.det(materials.deformation_gradient(u_p1))
det_F_p2 = ufl.det(materials.deformation_gradient(u_p2))
expressions += [(det_F_p1, materials.quadrature_points(cell, materials.quadrature_degree(1))),
                (det_F_p2, materials.quadrature_points(cell, materials.quadrature_degree(2)))]
