"""Inverse design of a prestretched strip (thesis §5.2.1; demos/design): the compressible
neo-Hookean law of thesis Eq. 3.1 with a prestretch F = Fe F0 that is the design field, and an
objective of the equilibrium it settles into, on Q2 hexahedra.

The design is a DG0 field `prestretch` of two components per cell, the stretch s and its
direction's angle a (radians, about z from x):

    F0 = Q(a) diag(s, s^-1/2, s^-1/2) Q(a)^T,

the isochoric uniaxial stretch of the cell's stress-free state relative to the mesh along the
in-plane direction (cos a, sin a, 0) (s < 1: the cell wants to be shorter along it, as strip A
of the bistrip, stretched by 1/s before bonding, does; a != 0 makes a bilayer twist as it
curls: a helix). The objective is a UFL functional of u and the design: here the distance of
the equilibrium to a target displacement field, its elastic energy, and a Tikhonov term that
keeps s near a prior,

    J = placement_weight/2 int |u - u_target|^2 dX + energy_weight int psi dX
        + regularisation/2 int (s - stretch_prior)^2 dX;

`distance` is the first integral alone, the distance reported whatever J is (a scene can set
placement_weight to 0 and add a term UFL cannot write, gelx::Objective's sampled part: the
design scene's `--objective centreline`, the helix detector's curvature and twist);

a user writes another in its place (keeping the names), and FFCx derives what the adjoint needs
(gelx::AdjointGradient, cpp/gelx/solvers/adjoint.h):
  residual, tangent           R(u; d) and dR/du, the equilibrium
  residual_d_prestretch       dR/dd: rows the displacement, columns the design (a bilinear form)
  objective                   J
  distance                    its placement term, unweighted
  objective_d_state           dJ/du (a linear form on the displacement space)
  objective_d_prestretch      dJ/dd (a linear form on the design space)
  stress, psi                 Cauchy stress and energy density at the cell midpoints
  det_F                       admissibility, at the quadrature points
"""
import ufl
import materials

cell = "hexahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
G = ufl.Constant(mesh)
K = ufl.Constant(mesh)
regularisation = ufl.Constant(mesh)  # weight of the Tikhonov term (length^2 / stretch^2)
stretch_prior = ufl.Constant(mesh)
placement_weight = ufl.Constant(mesh)
energy_weight = ufl.Constant(mesh)  # 1/MPa: J in length^5 as the placement term's
designs = ufl.FunctionSpace(mesh, ufl.VectorElement("DG", cell, 0, dim=2))
V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 2))
u = ufl.Coefficient(V)
u_target = ufl.Coefficient(V)
prestretch = ufl.Coefficient(designs)

stretch, angle = prestretch[0], prestretch[1]
Q = ufl.as_matrix([[ufl.cos(angle), -ufl.sin(angle), 0], [ufl.sin(angle), ufl.cos(angle), 0],
                   [0, 0, 1]])
F0 = Q * ufl.diag(ufl.as_vector([stretch, stretch**-0.5, stretch**-0.5])) * Q.T
F = materials.deformation_gradient(u)
psi = materials.prestretched(lambda Fe: materials.neo_hookean_compressible(Fe, G, K), F, F0)
dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(2)})
residual = ufl.derivative(psi * dx, u, ufl.TestFunction(V))
tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
residual_d_prestretch = ufl.derivative(residual, prestretch, ufl.TrialFunction(designs))

distance = ufl.inner(u - u_target, u - u_target) / 2 * dx
objective = (placement_weight * ufl.inner(u - u_target, u - u_target) / 2 + energy_weight * psi
             + regularisation / 2 * (stretch - stretch_prior)**2) * dx
objective_d_state = ufl.derivative(objective, u, ufl.TestFunction(V))
objective_d_prestretch = ufl.derivative(objective, prestretch, ufl.TestFunction(designs))

stress = materials.cauchy_stress(psi, F)
det_F = ufl.det(F)
forms = [residual, tangent, residual_d_prestretch, objective, objective_d_state,
         objective_d_prestretch, distance]
expressions = [(stress, materials.centroid(cell)), (psi, materials.centroid(cell)),
               (det_F, materials.quadrature_points(cell, materials.quadrature_degree(2)))]
