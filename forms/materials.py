"""Material laws of gelx: strain-energy densities as UFL expressions of the deformation gradient.

Every scene's form file builds its residual and tangent from one of these energies with
`ufl.derivative`, and exports the Cauchy stress and the energy density for output, so a law is
written once, here, and nowhere else. Equation numbers refer to the thesis in shared/seed/.
"""
import basix
import ufl


def deformation_gradient(u):
    """F = I + Grad u, marked as a UFL variable so that stresses are ufl.diff(psi, F)."""
    d = len(u)
    return ufl.variable(ufl.Identity(d) + ufl.grad(u))


def neo_hookean_compressible(F, G, K):
    """Compressible neo-Hookean solid, thesis Eq. 3.1.

    U = G/2 (I1_bar - 3) + K/2 (J - 1)^2 with I1_bar = J^(-2/3) tr(F^T F):
    G is the initial shear modulus, K the bulk modulus.
    """
    J = ufl.det(F)
    I1_bar = J**(-2.0 / 3.0) * ufl.tr(F.T * F)
    return G / 2 * (I1_bar - 3) + K / 2 * (J - 1)**2


def neo_hookean_log(F, G, K):
    """Compressible neo-Hookean solid with a logarithmic volumetric term (the law of dolfinx's
    hyperelasticity demo),
        U = G/2 (tr C - 3) - G ln J + lambda/2 (ln J)^2,   lambda = K - 2G/3,
    G the shear and K the bulk modulus at small strain, as for neo_hookean_compressible; it
    differs from Eq. 3.1 at finite volume change (U grows without bound as J -> 0).
    """
    J = ufl.det(F)
    lame = K - 2 * G / 3
    return G / 2 * (ufl.tr(F.T * F) - 3) - G * ufl.ln(J) + lame / 2 * ufl.ln(J)**2


def first_piola(psi, F):
    """P = dpsi/dF."""
    return ufl.diff(psi, F)


def cauchy_stress(psi, F):
    """sigma = J^-1 P F^T."""
    return first_piola(psi, F) * F.T / ufl.det(F)


def quadrature_degree(displacement_degree):
    """Quadrature degree for hyperelastic residuals and tangents.

    The integrands are rational in Grad u, so no degree is exact; 2p (4 for P2) keeps the
    quadrature error below the discretisation error (the manufactured-solution test checks
    that the optimal rates survive it) at a fraction of FFCx's estimated degree.
    """
    return 2 * displacement_degree


def quadrature_points(cell, degree):
    """Points of the default Basix scheme of the given degree: the points FFCx integrates on,
    where the solver checks det F > 0 to reject inverted iterates."""
    points, _ = basix.make_quadrature(basix.cell.string_to_type(cell), degree)
    return points


def centroid(cell):
    """Reference-cell midpoint: the interpolation point of a DG0 field (cell-wise output)."""
    return {"tetrahedron": [[0.25, 0.25, 0.25]], "hexahedron": [[0.5, 0.5, 0.5]]}[cell]


# ---------------------------------------------------------------------------------------------
# The law library. Each function returns a strain-energy density per unit reference volume;
# a form file picks one, builds its residual and tangent with ufl.derivative and exports the
# Cauchy stress (cauchy_stress, or linear_elastic_stress) and the energy density for output.
# forms/README.md tables the laws, their parameters, units, thesis equations, elements and tests.
# ---------------------------------------------------------------------------------------------

BOLTZMANN = 1.38064852e-23  # J/K, the value of the thesis' UHYPER subroutine (appendix B)


def isochoric_invariants(F):
    """J = det F and the isochoric invariants I1_bar = J^(-2/3) I1, I2_bar = J^(-4/3) I2."""
    J = ufl.det(F)
    C = F.T * F
    I1 = ufl.tr(C)
    I2 = (I1**2 - ufl.tr(C * C)) / 2
    return J, J**(-2.0 / 3.0) * I1, J**(-4.0 / 3.0) * I2


def neo_hookean_incompressible(F, p, G, bulk_compliance):
    """Incompressible neo-Hookean solid, thesis Eq. 1.10, in mixed displacement-pressure form.

    The analogue of ABAQUS hybrid elements: the pressure p is an independent field and
        L(F, p) = G/2 (I1_bar - 3) + p (J - 1) - bulk_compliance p^2 / 2.
    Stationarity in p gives J - 1 = bulk_compliance p: bulk_compliance = 1/K = 0 enforces
    J = 1 exactly, where I1_bar = I1 and the deviatoric part is Eq. 1.10; bulk_compliance = 1/K > 0
    gives back Eq. 3.1 with p = K (J - 1), without the locking of a pure displacement form.
    p is the mean Cauchy stress (tension positive): sigma = G J^(-5/3) dev(B) + p I; the
    thesis' Lagrange multiplier of Eq. 1.11 is -p + G I1/3.
    """
    J, I1_bar, _ = isochoric_invariants(F)
    return G / 2 * (I1_bar - 3) + p * (J - 1) - bulk_compliance * p**2 / 2


def mixed_stored_energy(lagrangian, volume_change, p, bulk_compliance):
    """Stored energy of a mixed law L = W_iso + p c - bulk_compliance p^2 / 2, with the volume
    change c = J - 1 (tr eps for the small-strain law), at a solution: W_iso plus the
    volumetric energy bulk_compliance p^2 / 2 (= K/2 c^2 there, since c = bulk_compliance p);
    the energy-density output field."""
    return lagrangian - p * volume_change + bulk_compliance * p**2


def mooney_rivlin_compressible(F, C10, C01, K):
    """Compressible Mooney-Rivlin solid (constitutive comparison of chapter 2),
        U = C10 (I1_bar - 3) + C01 (I2_bar - 3) + K/2 (J - 1)^2,
    initial shear modulus G = 2 (C10 + C01); C01 = 0 is Eq. 3.1 with G = 2 C10.
    """
    J, I1_bar, I2_bar = isochoric_invariants(F)
    return C10 * (I1_bar - 3) + C01 * (I2_bar - 3) + K / 2 * (J - 1)**2


def mooney_rivlin_incompressible(F, p, C10, C01, bulk_compliance):
    """Incompressible Mooney-Rivlin solid in mixed form (see neo_hookean_incompressible):
        L(F, p) = C10 (I1_bar - 3) + C01 (I2_bar - 3) + p (J - 1) - bulk_compliance p^2 / 2.
    """
    J, I1_bar, I2_bar = isochoric_invariants(F)
    return (C10 * (I1_bar - 3) + C01 * (I2_bar - 3) + p * (J - 1)
            - bulk_compliance * p**2 / 2)


def small_strain(F):
    """eps = sym(F) - I = sym(Grad u)."""
    d = F.ufl_shape[0]
    return ufl.sym(F) - ufl.Identity(d)


def linear_elastic(F, G, K):
    """Small-strain isotropic linear elasticity (chapter 2's reference model),
        U = G dev(eps):dev(eps) + K/2 tr(eps)^2,   eps = sym(Grad u),
    G the shear and K the bulk modulus (E = 9KG/(3K+G), nu = (3K-2G)/(2(3K+G))).
    Its stress is linear_elastic_stress (dU/dF = sigma; no J^-1 F^T push-forward).
    """
    eps = small_strain(F)
    return G * ufl.inner(ufl.dev(eps), ufl.dev(eps)) + K / 2 * ufl.tr(eps)**2


def linear_elastic_incompressible(F, p, G, bulk_compliance):
    """Small-strain linear elasticity in mixed displacement-pressure form (chapter 2's
    linear-elastic variant of the incompressible pyramid),
        L(F, p) = G dev(eps):dev(eps) + p tr(eps) - bulk_compliance p^2 / 2,
    bulk_compliance = 0 enforcing tr(eps) = 0; its stress is linear_elastic_stress
    (2 G dev(eps) + p I). Unlike the hyperelastic laws it is not frame-indifferent: use it for
    the law's small-strain response on a large-deformation geometry (the contact still sees the
    current position X + u)."""
    eps = small_strain(F)
    return (G * ufl.inner(ufl.dev(eps), ufl.dev(eps)) + p * ufl.tr(eps)
            - bulk_compliance * p**2 / 2)


def linear_elastic_stress(psi, F):
    """sigma = dU/d(Grad u) of linear_elastic (symmetric by construction)."""
    return ufl.diff(psi, F)


def chi_linear(A, B, T):
    """Flory-Huggins parameter chi = A + B T (thesis section 4.4, step (2)); T is a runtime
    constant that the program changes from load step to load step."""
    return A + B * T


def energy_scale(T, nu, length_scale):
    """kT/nu of Eq. 4.28 with the length-scale option of the UHYPER subroutine (appendix B):
    kT_v = k T / nu * scale. With nu in m^3 and scale = 1 the stress unit is Pa; scale = 1e-6
    gives MPa (lengths in mm, forces in N), as in the thesis' ABAQUS models."""
    return BOLTZMANN * T / nu * length_scale


def flory_rehner_gel(F, n, phi0, chi, kT_nu, dchi_dphi=0):
    """Flory-Rehner gel in a swollen reference state, thesis Eq. 4.28 (per reference volume):

        U = kT/nu [ n/2 phi0 (phi0^(-2/3) I1' - 3 - ln(J'/phi0)) + mixing(J') ]

    with n = N nu / V_m the network stiffness, phi0 = lambda0^-3 the polymer volume fraction of
    the reference (mesh) state, I1' = tr(F^T F), J' = det F measured from it, so that the
    polymer volume fraction is phi = phi0 / J', and the mixing energy of mixing() (chi may
    depend on phi: dchi_dphi). Defined for J' > phi0 only (the log of 1 - phi0/J'): export
    J' - phi0 as the admissibility expression. Homogeneous equilibria reproduce Eq. 4.7 (free
    swelling) and Eq. 4.10-4.11 (uniaxial constraint), with chi_bar of Eq. 4.20 in place of
    chi when dchi_dphi is not 0.
    """
    J = ufl.det(F)
    I1 = ufl.tr(F.T * F)
    return kT_nu * (n / 2 * phi0 * (phi0**(-2.0 / 3.0) * I1 - 3 - ufl.ln(J / phi0))
                    + mixing(J, phi0, chi, dchi_dphi))


def mixing(J, phi0, chi, dchi_dphi=0):
    """Flory-Huggins mixing energy per reference volume in units of kT/nu, J the volume ratio
    to the reference state and phi = phi0 / J the polymer fraction:

        (J - phi0) ln(1 - phi) + chi(phi) phi0 (1 - phi),   chi(phi) = chi + dchi_dphi phi,

    J times the mixing energy per current volume (1 - phi) ln(1 - phi) + chi phi (1 - phi).
    A chi linear in phi is the form fitted to gels with a volume phase transition (PNIPAM,
    Afroze, Nies and Berghmans 2000; Cai and Suo, JMPS 2011); with it the osmotic pressure
    holds chi_bar = chi(phi) - (1 - phi) dchi_dphi in place of chi (thesis section 4.3.3;
    cpp/theory chi_bar).
    """
    phi = phi0 / J
    return (J - phi0) * ufl.ln(1 - phi) + (chi + dchi_dphi * phi) * phi0 * (1 - phi)


def prestretched(law, F, F0, *args):
    """Energy per reference volume of a law with the multiplicative split F = Fe F0:

        U(F) = det(F0) law(F F0^-1, *args).

    F0 maps the reference (mesh) configuration to the stress-free one of a sub-domain (a strip
    stretched before gluing in the bistrip of chapter 3, a prestretched gel); law is an energy
    per stress-free volume, hence det F0. F must be the ufl.variable F so that the stress
    ufl.diff(U, F) includes the chain rule through F0^-1; F = F0 is stress free.
    """
    return ufl.det(F0) * law(F * ufl.inv(F0), *args)
