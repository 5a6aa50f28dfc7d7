// The swelling gel's homogeneous states (cpp/theory/swelling.h) against the energy they come
// from, written here: thesis Eq. 4.28 per reference volume with chi linear in phi, for the
// layer held laterally and stretched by l through its thickness and for the free gel swelling
// by J in volume; and the spinodal scan on cases whose answer is known.

#include "check.h"
#include "theory/flory_rehner.h"
#include "theory/swelling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace gelx::theory;

namespace
{
double mixing(double J, double phi0, const LinearChi& chi)
{
  const double phi = phi0 / J;
  return (J - phi0) * std::log1p(-phi) + chi.at(phi) * phi0 * (1 - phi);
}
double held_layer_energy(double l, double phi0, const LinearChi& chi, double n)
{
  return n / 2 * phi0 * (std::pow(phi0, -2.0 / 3.0) * (2 + l * l) - 3 - std::log(l / phi0))
         + mixing(l, phi0, chi);
}
double free_gel_energy(double J, double phi0, const LinearChi& chi, double n)
{
  return n / 2 * phi0 * (3 * std::pow(phi0, -2.0 / 3.0) * std::cbrt(J * J) - 3 - std::log(J / phi0))
         + mixing(J, phi0, chi);
}
/// f'(x) by the fourth-order central difference of step h
template <typename F>
double slope(F f, double x, double h)
{
  return (f(x - 2 * h) - 8 * f(x - h) + 8 * f(x + h) - f(x + 2 * h)) / (12 * h);
}
} // namespace

int main()
{
  // 1. mu and the modulus against the energy's derivatives (fourth-order differences, step
  //    3e-4: truncation ~3e-16 f^(5), round-off ~1e-12 of the energy, relative to the
  //    quantity's scale, at least 1e-3; measured up to 1.8e-10, and 1e-8 leaves room for the
  //    larger derivatives near phi0 = 0.58)
  double worst_mu = 0, worst_modulus = 0, worst_free = 0, worst_reference = 0;
  const double h = 3e-4;
  for (const LinearChi chi : {LinearChi{0.4, 0}, LinearChi{0.3, 0.6}, LinearChi{0.75, 0.5},
                              LinearChi{0.2, -0.4}})
    for (double lambda0 : {1.2, 1.5, 2.0})
      for (double n : {1e-3, 1e-2})
      {
        const double phi0 = std::pow(lambda0, -3.0);
        for (double l : {1.0, 1.3, 2.0, 4.0})
        {
          const auto U = [&](double x) { return held_layer_energy(x, phi0, chi, n); };
          const auto mu = [&](double x) { return held_layer_mu(x, phi0, chi, n); };
          const auto G = [&](double x) { return free_gel_energy(x, phi0, chi, n); };
          const double scale = std::max(1e-3, std::abs(mu(l)));
          worst_mu = std::max(worst_mu, std::abs(mu(l) - slope(U, l, h)) / scale);
          const double m = held_layer_modulus(l, phi0, chi, n);
          worst_modulus = std::max(worst_modulus,
                                   std::abs(m - slope(mu, l, h)) / std::max(1e-3, std::abs(m)));
          const double free_mu = free_gel_mu(phi0 / l, chi, n);
          worst_free = std::max(worst_free, std::abs(free_mu - slope(G, l, h))
                                                / std::max(1e-3, std::abs(free_mu)));
        }
        // 2. The reference state is the free gel at phi0: the held layer there is the same
        //    state, and its modulus through the thickness is the free gel's uniaxial one
        worst_reference = std::max(
            {worst_reference,
             std::abs(held_layer_mu(1, phi0, chi, n) - free_gel_mu(phi0, chi, n)),
             std::abs(held_layer_modulus(1, phi0, chi, n)
                      - drained_uniaxial_modulus(phi0, chi.stiffness(phi0), n))});
      }
  check::near("held layer: mu against dU/dl, worst relative", worst_mu, 0, 1e-8);
  check::near("held layer: modulus against dmu/dl, worst relative", worst_modulus, 0, 1e-8);
  check::near("free gel: mu against dU/dJ, worst relative", worst_free, 0, 1e-8);
  check::near("reference: layer and free gel agree, worst absolute", worst_reference, 0, 1e-14);

  // 3. The spinodal scan. chi = 0.4 at lambda0 = 1.5 swells to mu = 0 with every modulus
  //    positive: none. chi = 0.85 + phi: the reference itself is inside (its modulus < 0),
  //    found at phi0. lambda0 = 1.2, chi = 0.75 + 0.5 phi: the reference is outside, and the
  //    held layer's modulus turns negative on the way: the scan stops at the first step where
  //    it is not positive (one step before, it was)
  const double phi15 = std::pow(1.5, -3.0), phi12 = std::pow(1.2, -3.0);
  check::that("chi = 0.4: no spinodal on the way to mu = 0",
              std::isnan(spinodal_on_swelling(phi15, {0.4, 0}, 1e-3, 0, true)));
  const LinearChi inside{0.85, 1.0};
  check::that("chi = 0.85 + phi: the reference's modulus is negative",
              held_layer_modulus(1, phi15, inside, 1e-3) < 0);
  check::near("chi = 0.85 + phi: the spinodal at phi0",
              spinodal_on_swelling(phi15, inside, 1e-3, 0, false), phi15, 0);
  const LinearChi crossing{0.75, 0.5};
  const double phi = spinodal_on_swelling(phi12, crossing, 1e-3, 0, false);
  const double l = phi12 / phi;
  std::printf("     lambda0 = 1.2, chi = 0.75 + 0.5 phi: spinodal at phi = %.6f (l = %.6f), mu "
              "there %.4g\n", phi, l, held_layer_mu(l, phi12, crossing, 1e-3));
  check::that("the reference's modulus is positive",
              held_layer_modulus(1, phi12, crossing, 1e-3) > 0);
  check::that("the modulus at the spinodal found is not positive, one step before it is",
              held_layer_modulus(l, phi12, crossing, 1e-3) <= 0
                  && held_layer_modulus(l / (1 + 5e-4), phi12, crossing, 1e-3) > 0);
  check::that("the spinodal lies before the equilibrium (mu there below 0)",
              held_layer_mu(l, phi12, crossing, 1e-3) < 0);
  return check::result();
}
