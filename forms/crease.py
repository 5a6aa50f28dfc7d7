"""The crease scene's gel (demos/crease): the Flory-Rehner gel of thesis Eq. 4.28 in pure solvent
at equilibrium, displacement only, on Q2 hexahedra.

In the drained limit the solvent's chemical potential is the bath's, mu = 0, at every point
and every chi, so forms/swelling.py's mixed (u, mu) form has no work for its mu field: its
displacement rows at mu = 0 are this form's (W(F, 0) = U(F), forms/_swelling.py), and its mu
rows would only be held by boundary conditions. Constants: n = N nu, phi0 (the reference
state's polymer volume fraction), chi and kT_nu (kT / nu, MPa). Exports the Cauchy stress and
J (the local swelling ratio) at the cell midpoints, and J - phi0 at the quadrature points (the
admissibility the Newton line search keeps positive).
"""
import ufl
import materials

cell = "hexahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
n = ufl.Constant(mesh)
phi0 = ufl.Constant(mesh)
chi = ufl.Constant(mesh)
kT_nu = ufl.Constant(mesh)
V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, 2))
u = ufl.Coefficient(V)

F = materials.deformation_gradient(u)
psi = materials.flory_rehner_gel(F, n, phi0, chi, kT_nu)
dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(2)})
residual = ufl.derivative(psi * dx, u, ufl.TestFunction(V))
tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
stress = materials.cauchy_stress(psi, F)
swelling_ratio = ufl.det(F)
margin = swelling_ratio - phi0

forms = [residual, tangent]
expressions = [(stress, materials.centroid(cell)), (swelling_ratio, materials.centroid(cell)),
               (margin, materials.quadrature_points(cell, materials.quadrature_degree(2)))]
