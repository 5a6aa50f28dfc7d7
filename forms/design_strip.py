"""Inverse design of a prestretched strip (thesis §5.2.1; demos/design): the compressible
neo-Hookean law of thesis Eq. 3.1 with a prestretch F = Fe F0 whose axial stretch is the design
field, and an objective of the equilibrium it settles into, on Q2 hexahedra.

The design is a DG0 field `stretch`, s per cell: F0 = diag(s, s^-1/2, s^-1/2), the isochoric
uniaxial stretch along x of the cell's stress-free state relative to the mesh (s < 1: the cell
wants to be shorter along x, as strip A of the bistrip, stretched by 1/s before bonding, does).
The objective is a UFL functional of u and s: here the distance of the equilibrium to a target
displacement field plus a Tikhonov term that keeps s near a prior,

    J(u, s) = 1/2 int |u - u_target|^2 dX + regularisation/2 int (s - stretch_prior)^2 dX;

a user writes another in its place (keeping the names), and FFCx derives what the adjoint needs
(gelx::AdjointGradient, cpp/gelx/solvers/adjoint.h):
  residual, tangent           R(u; s) and dR/du, the equilibrium
  residual_d_stretch          dR/ds: rows the displacement, columns the design (a bilinear form)
  objective                   J
  objective_d_state           dJ/du (a linear form on the displacement space)
  objective_d_stretch         dJ/ds (a linear form on the design space)
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
designs = ufl.FunctionSpace(mesh, ufl.FiniteElement("DG", cell, 0))
V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 2))
u = ufl.Coefficient(V)
u_target = ufl.Coefficient(V)
stretch = ufl.Coefficient(designs)

F = materials.deformation_gradient(u)
F0 = ufl.diag(ufl.as_vector([stretch, stretch**-0.5, stretch**-0.5]))
psi = materials.prestretched(lambda Fe: materials.neo_hookean_compressible(Fe, G, K), F, F0)
dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(2)})
residual = ufl.derivative(psi * dx, u, ufl.TestFunction(V))
tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
residual_d_stretch = ufl.derivative(residual, stretch, ufl.TrialFunction(designs))

objective = (ufl.inner(u - u_target, u - u_target) / 2
             + regularisation / 2 * (stretch - stretch_prior)**2) * dx
objective_d_state = ufl.derivative(objective, u, ufl.TestFunction(V))
objective_d_stretch = ufl.derivative(objective, stretch, ufl.TestFunction(designs))

stress = materials.cauchy_stress(psi, F)
det_F = ufl.det(F)
forms = [residual, tangent, residual_d_stretch, objective, objective_d_state, objective_d_stretch]
expressions = [(stress, materials.centroid(cell)), (psi, materials.centroid(cell)),
               (det_F, materials.quadrature_points(cell, materials.quadrature_degree(2)))]
