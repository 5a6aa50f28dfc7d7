#pragma once
/// @file swelling.h
/// The homogeneous states a swelling gel passes through (demos/swelling, forms/swelling.py):
/// from its reference state, swollen freely to the polymer fraction phi0 and stress-free at the
/// chemical potential mu0, to its equilibrium with a solvent at mu >= mu0. Two families: the
/// layer bonded to a rigid substrate (held laterally at the reference state, stretched by l
/// through its thickness; also the skin of a free body early on, held by its dry core), and the
/// free gel swelling isotropically to the polymer fraction phi. chi may be linear in phi.
/// Units as in flory_rehner.h: mu in kT, moduli in kT/nu.

#include <cmath>

namespace gelx::theory
{

/// chi(phi) = chi + dchi_dphi phi: the form fitted to gels with a volume phase transition
/// (PNIPAM: Afroze, Nies and Berghmans 2000), with the values that take chi's place where it
/// depends on phi
struct LinearChi
{
  double chi = 0;       ///< chi at phi = 0
  double dchi_dphi = 0; ///< its slope

  double at(double phi) const { return chi + dchi_dphi * phi; }
  /// In the osmotic pressure: Eq. 4.20's chi_bar = chi(phi) - (1 - phi) dchi/dphi (peo.h)
  double osmotic(double phi) const;
  /// In the drained moduli: chi_bar + (phi / 2) dchi_bar/dphi = chi + dchi_dphi (3 phi - 1),
  /// since the mixing part of mu is ln(1 - phi) + phi + chi_bar phi^2
  double stiffness(double phi) const { return chi + dchi_dphi * (3 * phi - 1); }
};

/// The free gel at polymer fraction phi: the chemical potential that holds it there,
/// phi^2 (chi_bar(phi) - chi_free(phi, n)) (Eq. 4.7 with chi_bar), the reference's mu0 at phi0
double free_gel_mu(double phi, const LinearChi& chi, double n);

/// The held layer stretched by l through its thickness from the reference state phi0:
/// mu = dU/dl of U(l) = n/2 phi0 (phi0^(-2/3) (2 + l^2) - 3 - ln(l/phi0))
///     + (l - phi0) ln(1 - phi) + chi(phi) phi0 (1 - phi),   phi = phi0 / l,
/// the energy per reference volume of thesis Eq. 4.28 (the traction-free surface makes mu the
/// stress through the thickness); held_layer_mu(1) = free_gel_mu(phi0)
double held_layer_mu(double l, double phi0, const LinearChi& chi, double n);
/// Its slope dmu/dl, the layer's drained modulus through the thickness (per reference volume)
double held_layer_modulus(double l, double phi0, const LinearChi& chi, double n);

/// Where the way from phi0 to the equilibrium at mu first enters the spinodal: the polymer
/// fraction of the first state whose drained modulus is not positive, or NaN if there is none.
/// The held layer's states (mu rising with l until it reaches mu) and, for a free body, the
/// free gel's as well (drained_uniaxial_modulus with chi.stiffness). Scanned in steps of 5e-4
/// of the stretch: the moduli are smooth, so a spinodal narrower than that is not a concern
/// of this model's resolution either.
double spinodal_on_swelling(double phi0, const LinearChi& chi, double n, double mu,
                            bool free_body);

} // namespace gelx::theory
