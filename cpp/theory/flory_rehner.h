#pragma once
/// @file flory_rehner.h
/// Flory-Rehner theory of a neutral gel with a phi-independent Flory-Huggins parameter chi:
/// the free-swelling gel (thesis Eq. 4.5-4.7), the uniaxially constrained gel (Eq. 4.8-4.11),
/// the prestrain (Eq. 4.12) and the contraction ratios and anisotropy (Eq. 4.13-4.16).
///
/// Notation (thesis section 4.2): phi = V_m/V is the polymer volume fraction, n = N nu / V_m the
/// dimensionless network stiffness (N chains, solvent molecule volume nu, dry volume V_m),
/// lambda_par the fixed longitudinal stretch of the constrained gel, measured from the dry
/// (molten) state, and phi_c = lambda_par^-3 the volume fraction at which the constrained gel is
/// stress free. Everything here is dimensionless; stresses are given in units of kT/nu.

#include <vector>

namespace gelx::theory
{

/// Mixing part of both equilibrium conditions,
/// \f$ h(\phi) = -\ln(1-\phi)/\phi^2 - 1/\phi = \sum_{k\ge0} \phi^k/(k+2) \f$.
/// The series is used for small phi, where the closed form cancels catastrophically
/// (h -> 1/2 while each of its two terms grows like 1/phi).
double mixing_h(double phi);
/// \f$ h'(\phi) \f$; every series coefficient is positive, so h' >= 1/3 + phi/2 on (0, 1).
double mixing_dh(double phi);

/// Eq. 4.7: chi of a free-swelling gel in equilibrium at volume fraction phi,
/// \f$ \chi = \tfrac12 n (\phi^{-1} - 2\phi^{-5/3}) - \phi^{-2}\ln(1-\phi) - \phi^{-1}
///        = \tfrac12 n (\phi^{-1} - 2\phi^{-5/3}) + h(\phi) \f$.
/// Strictly increasing on (0, 1) for every n >= 0 (the elastic slope
/// n phi^-2 (5/3 phi^-2/3 - 1/2) is positive), so its inverse is unique.
double chi_free(double phi, double n);
double dchi_free(double phi, double n);

/// Eq. 4.10: chi of the uniaxially constrained gel (transverse stresses zero, Eq. 4.9) at
/// volume fraction phi and fixed longitudinal stretch lambda_par,
/// \f$ \chi' = \tfrac12 n (\phi^{-1} - 2\phi^{-2}\lambda_\parallel^{-1}) - \phi^{-2}\ln(1-\phi)
///     - \phi^{-1} = \tfrac12 n (\phi^{-1} - 2\phi^{-2}\lambda_\parallel^{-1}) + h(\phi) \f$.
double chi_constrained(double phi, double lambda_par, double n);
double dchi_constrained(double phi, double lambda_par, double n);

/// Eq. 4.18 in closed form: \f$ \chi - \chi' = n\phi^{-2}(\lambda_\parallel^{-1} - \phi^{1/3}) \f$.
double chi_difference(double phi, double lambda_par, double n);

/// The drained modulus of uniaxial strain, d^2 W / d lambda^2 at F = I for W(diag(lambda, 1, 1))
/// at fixed solvent potential, of a gel whose reference state holds volume fraction phi, in
/// units of kT/nu per reference volume: the mixing energy's
/// \f$ \phi^2 (1/(1-\phi) - 2\chi) \f$ plus the network's \f$ n (\phi^{1/3} + \phi/2) \f$
/// (Eq. 4.2's (n/2)(I_1 - 3 - ln J) per dry volume). The longitudinal entry of the acoustic
/// tensor, the first to lose positivity: where it is negative the homogeneous gel is inside
/// its spinodal and separates into a collapsed and a swollen phase (the skin of a gel
/// heated faster than it drains, which holds phi while chi rises).
double drained_uniaxial_modulus(double phi, double chi, double n);

/// Largest lambda_par for which chi_constrained is provably strictly increasing on (0, 1).
/// dchi'/dphi = n phi^-2 (2/(lambda phi) - 1/2) + h'(phi) > 0 follows from h' >= 1/3 + phi/2 when
/// the quartic phi^3/3 + phi^4/2 - n phi/2 + 2n/lambda is positive on (0, 1); its minimum is at
/// the unique positive root of phi^2 + 2 phi^3 = n/2, which gives the bound. Beyond it the
/// inverse may still be unique, but it is checked by a scan instead.
double lambda_monotone_bound(double n);

/// Inverse of Eq. 4.7: the unique phi in (0, 1) with chi_free(phi) = chi. `guess` (optional,
/// in (0, 1)) warm-starts the bracketed Newton iteration. Throws std::runtime_error when no
/// root exists (only possible for n = 0 and chi <= 1/2).
double phi_free(double chi, double n, double guess = 0.5);

/// Every phi in (0, 1) with chi_constrained(phi, lambda_par) = chi, by a sign-change scan.
std::vector<double> phi_constrained_all(double chi, double lambda_par, double n);

/// Inverse of Eq. 4.10. When lambda_par < lambda_monotone_bound(n) the root is unique and found
/// by a warm-started bracketed Newton iteration; otherwise a scan finds all roots and
/// NonUniqueRoot is thrown when there is more than one.
double phi_constrained(double chi, double lambda_par, double n, double guess = 0.5);

/// Eq. 4.11: longitudinal true stress of the constrained gel in units of kT/nu,
/// \f$ \sigma_3 \nu/kT = n (\phi/\lambda_\parallel)(\phi_c^{-1} - \phi^{-1}) \f$ with
/// phi_c = lambda_par^-3 (chi already eliminated with Eq. 4.10).
double sigma3(double phi, double lambda_par, double n);

/// Eq. 4.12: prestrain of a constrained gel with stretch lambda_par at a given chi,
/// \f$ \epsilon_\parallel = (\lambda_\parallel - \lambda)/\lambda \f$ with
/// lambda = phi_free(chi)^-1/3 the stretch of the free gel at the same chi.
double prestrain(double lambda_par, double chi, double n);

/// Eq. 4.13: isotropic contraction ratio of the free gel, (phi_i/phi_f)^(1/3).
double alpha0(double phi_i, double phi_f);
/// Eq. 4.14, with lambda_perp = (phi lambda_par)^-1/2 from phi = 1/(lambda_perp^2 lambda_par).
double alpha_parallel(double lambda_par_i, double lambda_par_f);
double alpha_perpendicular(double phi_i, double lambda_par_i, double phi_f,
                           double lambda_par_f);
/// Eq. 4.15-4.16: A = alpha_par / alpha_perp
///   = (phi'_f/phi'_i)^(1/2) (lambda_par_f/lambda_par_i)^(3/2).
double anisotropy(double phi_i, double lambda_par_i, double phi_f, double lambda_par_f);

/// One contraction experiment of section 4.3.2. The free gel goes from phi_i to
/// phi_f = phi_i / alpha0^3 (chi_i -> chi_f by Eq. 4.7). The constrained gel is prestrained at
/// chi_i to lambda_par = (1 + eps) phi_i^(-1/3) (Eq. 4.12), which fixes phi'_i by Eq. 4.10, and
/// then contracts at constant lambda_par (alpha_par = 1, the case that attains the bound of
/// Eq. 4.16) to phi'_f at chi_f. A_max = (phi'_f / phi'_i)^(1/2).
struct Contraction
{
  double phi_i, phi_f, chi_i, chi_f;   ///< free gel
  double lambda_par, phi_c;            ///< constraint, phi_c = lambda_par^-3
  double phi_prime_i, phi_prime_f;     ///< constrained gel
  double alpha_perp, A_max;            ///< alpha_par = 1
  double sigma3_i, sigma3_f;           ///< Eq. 4.11 before and after, units kT/nu
};
/// Throws std::invalid_argument when phi_f >= 1 (the specified alpha0 cannot be reached) and
/// NonUniqueRoot when Eq. 4.10 has several roots.
Contraction contract(double n, double alpha0, double phi_i, double eps_par);

} // namespace gelx::theory
