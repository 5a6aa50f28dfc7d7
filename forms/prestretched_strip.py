"""The prestretched bistrip of chapter 3: a compressible law of materials.py, chosen by the
scene's --law, with a per-cell prestretch F0 (strip A stretched before bonding, F = Fe F0;
F0 = I in strip B), on hexahedra. The laws:
  nh   neo-Hookean, thesis Eq. 3.1, the law of the thesis' ABAQUS runs (constants G, K)
  mr   Mooney-Rivlin, C10 = (1 - s) G/2, C01 = s G/2 (G, K, s = mooney_share)

Cells tagged 1 are the prestretched strips (A), 2 the stress-free ones (B): demos/bistrip/
section.h. Two displacement elements, for the work-precision study of demos/bistrip/bench.py:
Q2 (suffix q2, the scene's default) and Q1 (q1, which locks in bending under full
integration). Per law and element (suffix law_q1,
law_q2):
  residual_*, tangent_*           the equilibrium
  energy_A_*, energy_B_*          the stored energy of each strip (their sum: the strain energy)
  cell_energy_*                   the stored energy of every cell (a DG0 vector)
  stress_*, psi_*                 Cauchy stress and energy density at the cell midpoints
  psi_section_*                   energy density on a 5 x 5 grid of each cell's mid-section
                                  z = const (cross-section maps, thesis Fig. 3.6)
and per element alone (suffix q1, q2):
  mass_*                          the dynamic methods (gelx::DampedDynamics, inertia)
  det_F_*                         admissibility, at the quadrature points
"""
import ufl
import materials

cell = "hexahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
G = ufl.Constant(mesh)
K = ufl.Constant(mesh)
mooney_share = ufl.Constant(mesh)  # C01 / (C10 + C01), law mr
rho = ufl.Constant(mesh)  # mass density (the dynamic methods)
F0 = ufl.Coefficient(ufl.FunctionSpace(mesh, ufl.TensorElement("DG", cell, 0)))
cells = ufl.FunctionSpace(mesh, ufl.FiniteElement("DG", cell, 0))
V1 = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 1))
V2 = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 2))
u_q1 = ufl.Coefficient(V1)
u_q2 = ufl.Coefficient(V2)
# The 5 x 5 grid of the mid-section of the reference cell, x fastest
section_points = [[(i + 0.5) / 5, (j + 0.5) / 5, 0.5] for j in range(5) for i in range(5)]


laws = {"nh": lambda F: materials.neo_hookean_compressible(F, G, K),
        "mr": lambda F: materials.mooney_rivlin_compressible(F, (1 - mooney_share) * G / 2,
                                                             mooney_share * G / 2, K)}


def strip(u, degree, law):
    V = u.ufl_function_space()
    F = materials.deformation_gradient(u)
    psi = materials.prestretched(laws[law], F, F0)
    dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(degree)})
    residual = ufl.derivative(psi * dx, u, ufl.TestFunction(V))
    # psi_section: a one-component vector, so that FFCx does not merge it with psi (same
    # expression, other points) under one symbol
    return (residual, ufl.derivative(residual, u, ufl.TrialFunction(V)), psi * dx(1),
            psi * dx(2), psi * ufl.TestFunction(cells) * dx, materials.cauchy_stress(psi, F), psi,
            ufl.as_vector([psi]))


def mass(u, degree):
    V = u.ufl_function_space()
    dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(degree)})
    return rho * ufl.inner(ufl.TrialFunction(V), ufl.TestFunction(V)) * dx


# Module-level names name the generated forms and expressions (FFCx)
mass_q1, mass_q2 = mass(u_q1, 1), mass(u_q2, 2)
det_F_q1 = ufl.det(materials.deformation_gradient(u_q1))
det_F_q2 = ufl.det(materials.deformation_gradient(u_q2))
forms = [mass_q1, mass_q2]
expressions = [(det_F_q1, materials.quadrature_points(cell, materials.quadrature_degree(1))),
               (det_F_q2, materials.quadrature_points(cell, materials.quadrature_degree(2)))]
centroid = materials.centroid(cell)
for _law in laws:
    for _degree, _u in ((1, u_q1), (2, u_q2)):
        _names = [f"{kind}_{_law}_q{_degree}" for kind in
                  ("residual", "tangent", "energy_A", "energy_B", "cell_energy", "stress", "psi",
                   "psi_section")]
        _objects = strip(_u, _degree, _law)
        globals().update(zip(_names, _objects))
        forms += _objects[:5]
        expressions += [(_objects[5], centroid), (_objects[6], centroid),
                        (_objects[7], section_points)]
del _law, _degree, _u, _names, _objects  # (FFCx names a coefficient by its variable: u_q1, u_q2)
