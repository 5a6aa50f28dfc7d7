"""A gel that swells in time: solvent diffusion coupled to large deformation (Hong, Zhao, Zhou
& Suo, JMPS 56, 2008; the mixed (u, mu) form of Bouklas, Landis & Huang, JMPS 2015), on Q2-Q1
Taylor-Hood hexahedra (mu acts like a pressure as t -> 0+, when the gel deforms at fixed
volume).

Unknowns w = (u, mu): the displacement from a pre-swollen, stress-free reference state (the
mesh; polymer volume fraction phi0 = lambda0^-3) and the solvent's chemical potential mu in
units of kT. With the molecular incompressibility of polymer and solvent, the solvent volume
per reference volume is J - phi0, and the free energy per reference volume, the Flory-Rehner
gel of thesis Eq. 4.28 Legendre-transformed to mu (energies in kT_nu = kT / nu),

    W(F, mu) = U(F) - kT_nu mu (J - phi0),

is stress-free at F = I for mu = mu0(phi0) (cpp/theory: FreeSwelling). The solvent is
conserved, with Fick's flux in the current state pulled back to the reference,

    d/dt (J - phi0) + Div j = 0,   j = -D (J - phi0) C^-1 Grad mu,

(current flux -D phi_s grad mu of solvent volume, phi_s = (J - phi0)/J the solvent fraction;
D the solvent's diffusivity, mm^2/s) and no flux where mu is not prescribed. The transient
residual holds the rate w_dot of w; its tangent dR/dw + shift dR/dw_dot is the Jacobian that
PETSc TS asks for (shift its constant). The conservation row is scaled by -kT_nu so that the
coupling blocks are each other's transposes at shift 1.

Exports: residual, tangent; volume (int J dX) and solvent (int (J - phi0) dX); the Cauchy
stress and J at the cell midpoints; J - phi0 at the quadrature points (admissibility).
"""
import ufl
import materials

cell = "hexahedron"
mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
element = ufl.MixedElement([ufl.VectorElement("Lagrange", cell, 2),
                            ufl.FiniteElement("Lagrange", cell, 1)])
W = ufl.FunctionSpace(mesh, element)
w = ufl.Coefficient(W)  # (u, mu)
w_dot = ufl.Coefficient(W)  # its rate
n = ufl.Constant(mesh)  # N nu: the network's stiffness in units of kT/nu
phi0 = ufl.Constant(mesh)  # polymer volume fraction of the reference state
chi = ufl.Constant(mesh)  # Flory's interaction parameter
kT_nu = ufl.Constant(mesh)  # energy scale kT/nu (MPa)
D = ufl.Constant(mesh)  # solvent diffusivity (mm^2/s)
shift = ufl.Constant(mesh)  # TS's shift: d(w_dot)/dw of the implicit scheme

u, mu = ufl.split(w)
u_dot, _ = ufl.split(w_dot)
v, q = ufl.TestFunctions(W)
F = materials.deformation_gradient(u)
J = ufl.det(F)
psi = materials.flory_rehner_gel(F, n, phi0, chi, kT_nu) - kT_nu * mu * (J - phi0)
dx = ufl.dx(metadata={"quadrature_degree": materials.quadrature_degree(2)})

J_dot = J * ufl.inner(ufl.inv(F).T, ufl.grad(u_dot))
flux = -D * (J - phi0) * ufl.inv(F.T * F) * ufl.grad(mu)
residual = (ufl.inner(materials.first_piola(psi, F), ufl.grad(v)) * dx
            - kT_nu * (J_dot * q - ufl.inner(flux, ufl.grad(q))) * dx)
dw = ufl.TrialFunction(W)
tangent = ufl.derivative(residual, w, dw) + shift * ufl.derivative(residual, w_dot, dw)

volume = J * dx
solvent = (J - phi0) * dx
stress = materials.cauchy_stress(psi, F)
margin = J - phi0
forms = [residual, tangent, volume, solvent]
expressions = [(stress, materials.centroid(cell)), (J, materials.centroid(cell)),
               (margin, materials.quadrature_points(cell, materials.quadrature_degree(2)))]
