#include "theory/swelling.h"

#include "theory/flory_rehner.h"
#include "theory/peo.h"

#include <limits>

namespace gelx::theory
{

double LinearChi::osmotic(double phi) const { return chi_bar(at(phi), dchi_dphi, phi); }

double free_gel_mu(double phi, const LinearChi& chi, double n)
{
  return phi * phi * (chi.osmotic(phi) - chi_free(phi, n));
}

double held_layer_mu(double l, double phi0, const LinearChi& chi, double n)
{
  const double phi = phi0 / l;
  return n * std::cbrt(phi0) * l - n * phi0 / (2 * l) + std::log1p(-phi) + phi
         + chi.osmotic(phi) * phi * phi;
}

double held_layer_modulus(double l, double phi0, const LinearChi& chi, double n)
{
  const double phi = phi0 / l;
  return n * std::cbrt(phi0) + n * phi0 / (2 * l * l)
         + phi * phi * phi / phi0 * (1 / (1 - phi) - 2 * chi.stiffness(phi));
}

double spinodal_on_swelling(double phi0, const LinearChi& chi, double n, double mu,
                            bool free_body)
{
  // mu rises without bound along either family (the network's term grows with the stretch),
  // so each scan ends; the cap only guards against a mu no finite stretch reaches
  // (the reference state itself is checked whatever mu is)
  constexpr double step = 1 + 5e-4, largest = 1e4;
  for (double l = 1;; l *= step)
  {
    if (held_layer_modulus(l, phi0, chi, n) <= 0)
      return phi0 / l;
    if (l > largest || held_layer_mu(l, phi0, chi, n) >= mu)
      break;
  }
  for (double J = 1; free_body; J *= step)
  {
    const double phi = phi0 / J;
    if (drained_uniaxial_modulus(phi, chi.stiffness(phi), n) <= 0)
      return phi;
    if (J > largest || free_gel_mu(phi, chi, n) >= mu)
      break;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

} // namespace gelx::theory
