"""The prestretched bistrip of chapter 3: compressible neo-Hookean (Eq. 3.1) with a per-cell
prestretch F0 (strip A stretched before bonding, F = Fe F0; F0 = I in strip B), on hexahedra.

Cells tagged 1 are the prestretched strips (A), 2 the stress-free ones (B): demos/bistrip/
section.h. Two displacement elements, for the work-precision study of demos/bistrip/bench.py: Q2 (suffix q2, the scene's default) and Q1
(q1, which locks in bending under full integration). Per element:
  residual_*, tangent_*           the equilibrium
  mass_*                          damped dynamics (gelx::DampedDynamics)
  energy_A_*, energy_B_*          the stored energy of each strip (their sum: the strain energy)
  cell_energy_*                   the stored energy of every cell (a DG0 vector)
  stress_*, psi_*                 Cauchy stress and energy density at the cell midpoints
  psi_section_*                   energy density on a 5 x 5 grid of each cell's mid-section
                                  z = const (cross-section maps, thesis Fig. 3.6)
  det_F_*                         admissibility, at the quadrature points
"""
import ufl
import materials

cell = "hexahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
G = ufl.Constant(mesh)
K = ufl.Constant(mesh)
rho = ufl.Constant(mesh)  # mass density (damped dynamics)
F0 = ufl.Coefficient(ufl.FunctionSpace(mesh, ufl.TensorElement("DG", cell, 0)))
cells = ufl.FunctionSpace(mesh, ufl.FiniteElement("DG", cell, 0))
V1 = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 1))
V2 = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 2))
u_q1 = ufl.Coefficient(V1)
u_q2 = ufl.Coefficient(V2)
# The 5 x 5 grid of the mid-section of the reference cell, x fastest
section_points = [[(i + 0.5) / 5, (j + 0.5) / 5, 0.5] for j in range(5) for i in range(5)]


def strip(u, degree):
    V = u.ufl_function_space()
    F = materials.deformation_gradient(u)
    psi = materials.prestretched(materials.neo_hookean_compressible, F, F0, G, K)
    dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(degree)})
    v = ufl.TestFunction(V)
    residual = ufl.derivative(psi * dx, u, v)
    return (residual, ufl.derivative(residual, u, ufl.TrialFunction(V)),
            rho * ufl.inner(ufl.TrialFunction(V), v) * dx, psi * dx(1), psi * dx(2),
            psi * ufl.TestFunction(cells) * dx, materials.cauchy_stress(psi, F), psi, ufl.det(F))


(residual_q1, tangent_q1, mass_q1, energy_A_q1, energy_B_q1, cell_energy_q1, stress_q1, psi_q1,
 det_F_q1) = strip(u_q1, 1)
(residual_q2, tangent_q2, mass_q2, energy_A_q2, energy_B_q2, cell_energy_q2, stress_q2, psi_q2,
 det_F_q2) = strip(u_q2, 2)
# A one-component vector, so that FFCx does not merge it with psi_* (same expression, other
# points) under one symbol
psi_section_q1 = ufl.as_vector([psi_q1])
psi_section_q2 = ufl.as_vector([psi_q2])

forms = [residual_q1, tangent_q1, mass_q1, energy_A_q1, energy_B_q1, cell_energy_q1,
         residual_q2, tangent_q2, mass_q2, energy_A_q2, energy_B_q2, cell_energy_q2]
centroid = materials.centroid(cell)
expressions = [(stress_q1, centroid), (psi_q1, centroid), (psi_section_q1, section_points),
               (det_F_q1, materials.quadrature_points(cell, materials.quadrature_degree(1))),
               (stress_q2, centroid), (psi_q2, centroid), (psi_section_q2, section_points),
               (det_F_q2, materials.quadrature_points(cell, materials.quadrature_degree(2)))]
