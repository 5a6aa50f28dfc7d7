"""Builder shared by swelling.py (hexahedra) and fiber_film.py (tetrahedra): a gel that swells
in time, solvent diffusion coupled to large deformation (Hong, Zhao, Zhou & Suo, JMPS 56, 2008;
the mixed (u, mu) form of Bouklas, Landis & Huang, JMPS 2015), on Taylor-Hood pairs (Q2-Q1,
P2-P1: mu acts like a pressure as t -> 0+, when the gel deforms at fixed volume, and these
pairs are inf-sup stable) or equal order (Q1-Q1, which is not: to show what that does).

Unknowns w = (u, mu): the displacement from a pre-swollen, stress-free reference state (the
mesh; polymer volume fraction phi0 = lambda0^-3) and the solvent's chemical potential mu in
units of kT. With the molecular incompressibility of polymer and solvent, the solvent volume
per reference volume is J - phi0, and the free energy per reference volume, the Flory-Rehner
gel of thesis Eq. 4.28 Legendre-transformed to mu (energies in kT_nu = kT / nu; chi may be
linear in the polymer fraction, chi + dchi_dphi phi: materials.mixing),

    W(F, mu) = U(F) - kT_nu mu (J - phi0),

is stress-free at F = I for mu = mu0(phi0) (cpp/theory: FreeSwelling). The solvent is
conserved, with Fick's flux in the current state pulled back to the reference,

    d/dt (J - phi0) + Div j = 0,   j = -D (J - phi0) C^-1 Grad mu,

(current flux -D phi_s grad mu of solvent volume, phi_s = (J - phi0)/J the solvent fraction;
D the solvent's diffusivity, mm^2/s) and no flux where mu is not prescribed. The transient
residual holds the rate w_dot of w; its tangent dR/dw + shift dR/dw_dot is the Jacobian that
PETSc TS asks for (shift its constant). The conservation row is scaled by -kT_nu so that the
coupling blocks are each other's transposes at shift 1.

The fieldsplit linear solver's Schur complement in mu, S = -(L + shift G^T K^-1 G) (L the
mobility's Laplacian, G the coupling kT_nu J F^-T : Grad v mu, K the displacement block at
fixed mu), is preconditioned by the same operator with K^-1 replaced by the inverse of the
gel's drained stiffness to volume change, as the fixed-stress splitting of poroelasticity does
(Mikelic and Wheeler, Comput. Geosci. 2013): G^T K^-1 G ~ kT_nu J^2 / m(J) times the mass of
mu, m = J^2 f''(J) + 4/3 G_n with f the mixing energy per reference volume and G_n = n
phi0^(1/3) the network's shear modulus, in units of kT/nu. Unlike selfp's diag(K)^-1, it
does not depend on the mesh size.

build(cell, elements) returns, per element (suffix: its name), residual, tangent,
schur_preconditioner (its mu block, on the mixed space), volume (int J dX: the solvent taken
up, V - V0), the Cauchy stress and J (the local swelling ratio) at the cell midpoints and
J - phi0 at the quadrature points (admissibility); coefficients w_*, w_dot_*; and the
constants. FFCx names coefficients and constants after
the module-level variables that hold them, so each form file puts them into its namespace.
"""
import ufl
import materials


def build(cell, elements):
    """elements: {suffix: displacement degree} (mu is of degree 1)."""
    mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
    c = {"n": ufl.Constant(mesh),  # N nu: the network's stiffness in units of kT/nu
         "phi0": ufl.Constant(mesh),  # polymer volume fraction of the reference state
         "chi": ufl.Constant(mesh),  # Flory's interaction parameter at phi = 0
         "dchi_dphi": ufl.Constant(mesh),  # its slope in phi: chi(phi) = chi + dchi_dphi phi
         "kT_nu": ufl.Constant(mesh),  # energy scale kT/nu (MPa)
         "D": ufl.Constant(mesh),  # solvent diffusivity (length^2/s)
         "shift": ufl.Constant(mesh)}  # TS's shift: d(w_dot)/dw of the implicit scheme
    out, forms, expressions = dict(c), [], []
    for suffix, degree in elements.items():
        W = ufl.FunctionSpace(mesh, ufl.MixedElement(
            [ufl.VectorElement("Lagrange", cell, degree), ufl.FiniteElement("Lagrange", cell, 1)]))
        w, w_dot = ufl.Coefficient(W), ufl.Coefficient(W)  # (u, mu), its rate
        names = ["residual", "tangent", "schur_preconditioner", "volume", "stress",
                 "swelling_ratio", "margin"]
        kernels = dict(zip(names, gel(w, w_dot, degree, **c)))
        out.update({f"W_{suffix}": W, f"w_{suffix}": w, f"w_dot_{suffix}": w_dot})
        out.update({f"{name}_{suffix}": kernels[name] for name in names})
        forms += [kernels[name] for name in names[:4]]
        points = materials.quadrature_points(cell, materials.quadrature_degree(degree))
        expressions += [(kernels["stress"], materials.centroid(cell)), (kernels["margin"], points),
                        (kernels["swelling_ratio"], materials.centroid(cell))]
    return out, forms, expressions


def gel(w, w_dot, degree, n, phi0, chi, dchi_dphi, kT_nu, D, shift):
    u, mu = ufl.split(w)
    u_dot, _ = ufl.split(w_dot)
    W = w.ufl_function_space()
    v, q = ufl.TestFunctions(W)
    F = materials.deformation_gradient(u)
    J = ufl.det(F)
    psi = (materials.flory_rehner_gel(F, n, phi0, chi, kT_nu, dchi_dphi)
           - kT_nu * mu * (J - phi0))
    quadrature = materials.quadrature_degree(degree)
    dx = ufl.dx(metadata={"quadrature_degree": quadrature})
    J_dot = J * ufl.inner(ufl.inv(F).T, ufl.grad(u_dot))
    flux = -D * (J - phi0) * ufl.inv(F.T * F) * ufl.grad(mu)
    residual = (ufl.inner(materials.first_piola(psi, F), ufl.grad(v)) * dx
                - kT_nu * (J_dot * q - ufl.inner(flux, ufl.grad(q))) * dx)
    dw = ufl.TrialFunction(W)
    tangent = ufl.derivative(residual, w, dw) + shift * ufl.derivative(residual, w_dot, dw)
    _, dmu = ufl.split(dw)
    volume_change = ufl.variable(J)
    mixing = materials.mixing(volume_change, phi0, chi, dchi_dphi)
    drained = (J**2 * ufl.diff(ufl.diff(mixing, volume_change), volume_change)
               + 4.0 / 3.0 * n * phi0**(1.0 / 3.0))
    schur_preconditioner = -kT_nu * (
        D * (J - phi0) * ufl.inner(ufl.inv(F.T * F) * ufl.grad(dmu), ufl.grad(q))
        + shift * J**2 / drained * dmu * q) * dx
    return (residual, tangent, schur_preconditioner, J * dx, materials.cauchy_stress(psi, F), J,
            J - phi0)

