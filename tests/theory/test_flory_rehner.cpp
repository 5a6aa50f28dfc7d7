// Flory-Rehner closed forms and their inverses (thesis Eq. 4.7, 4.10, 4.11, 4.18) and the root
// finder's detection of non-unique roots.

#include "check.h"
#include "theory/amax_map.h"
#include "theory/flory_rehner.h"
#include "theory/roots.h"

#include <algorithm>

using namespace gelx::theory;

int main()
{
  // 1. chi -> phi -> chi round trips. phi is found to ~1e-16 relative; chi(phi) then carries
  //    |dchi/dphi| phi 1e-16 plus rounding of terms as large as n phi^-5/3 (~2e3 at phi = 0.005),
  //    so the tolerance is 1e-12 relative to max(1, |chi|, that largest term).
  double worst_free = 0.0, worst_con = 0.0;
  for (double n : {0.1, 0.01, 0.001, 0.0})
    for (double phi : linspace(0.005, 0.995, 199))
    {
      const double chi = chi_free(phi, n);
      const double scale = std::max({1.0, std::abs(chi), n * std::pow(phi, -5.0 / 3.0)});
      worst_free = std::max(worst_free, std::abs(chi_free(phi_free(chi, n), n) - chi) / scale);
      for (double lambda : {1.0, 1.5, 3.0, 8.0})
      {
        const double c = chi_constrained(phi, lambda, n);
        const double s = std::max({1.0, std::abs(c), n / (phi * phi)});
        worst_con = std::max(
            worst_con, std::abs(chi_constrained(phi_constrained(c, lambda, n), lambda, n) - c) / s);
      }
    }
  check::near("chi->phi->chi, free gel (Eq. 4.7), worst relative", worst_free, 0.0, 1e-12);
  check::near("chi->phi->chi, constrained gel (Eq. 4.10), worst relative", worst_con, 0.0, 1e-12);

  // 2. phi -> chi -> phi: the inverse recovers phi itself (Newton converges to ~4 ulp; 1e-12
  //    allows for the conditioning dphi = dchi / chi'(phi) near phi -> 0).
  double worst_phi = 0.0;
  for (double phi : linspace(0.01, 0.99, 99))
    worst_phi = std::max(worst_phi, std::abs(phi_free(chi_free(phi, 0.01), 0.01) - phi) / phi);
  check::near("phi->chi->phi, free gel, worst relative", worst_phi, 0.0, 1e-12);

  // 3. Eq. 4.18 (closed form) against the difference of Eq. 4.7 and 4.10; both sides are O(n
  //    phi^-2) and the subtraction loses digits in proportion, hence 1e-12 relative to that.
  double worst_418 = 0.0;
  for (double n : {0.1, 0.01, 0.002})
    for (double lambda : {0.9, 1.3, 2.0, 5.0})
      for (double phi : linspace(0.01, 0.99, 99))
        worst_418 = std::max(worst_418, std::abs(chi_free(phi, n) - chi_constrained(phi, lambda, n)
                                                 - chi_difference(phi, lambda, n))
                                            / (n / (phi * phi)));
  check::near("Eq. 4.18 identity, worst relative to n/phi^2", worst_418, 0.0, 1e-12);
  // Sign statement of section 4.3.1: chi < chi' for phi > phi_c and vice versa.
  const double lam = 2.0, pc = 1.0 / 8.0;
  check::that("chi < chi' at phi = 0.2 > phi_c = 0.125",
              chi_free(0.2, 0.01) < chi_constrained(0.2, lam, 0.01));
  check::that("chi > chi' at phi = 0.1 < phi_c", chi_free(0.1, 0.01) > chi_constrained(0.1, lam, 0.01));
  check::near("chi = chi' at phi_c", chi_free(pc, 0.01) - chi_constrained(pc, lam, 0.01), 0.0, 1e-13);

  // 4. Eq. 4.11: sigma3 vanishes at phi_c, is tensile above it and compressive below.
  check::near("sigma3(phi_c) = 0", sigma3(pc, lam, 0.01), 0.0, 1e-15);
  check::that("sigma3 > 0 for phi > phi_c", sigma3(0.2, lam, 0.01) > 0.0);
  check::that("sigma3 < 0 for phi < phi_c", sigma3(0.1, lam, 0.01) < 0.0);
  // Eq. 4.12: a constrained gel with lambda = lambda_free (1 + eps) has prestrain eps.
  const double chi = chi_free(0.2, 0.01);
  check::near("prestrain (Eq. 4.12) recovers eps = 0.3",
              prestrain(1.3 / std::cbrt(0.2), chi, 0.01), 0.3, 1e-14);

  // 5. Eq. 4.13-4.16: A = (phi'_f/phi'_i)^1/2 (lambda_f/lambda_i)^3/2 for any alpha_par.
  const double a = anisotropy(0.2, 2.0, 0.3, 1.8);
  check::near("Eq. 4.16 identity with alpha_par = 0.9", a,
              std::sqrt(0.3 / 0.2) * std::pow(0.9, 1.5), 1e-15);
  check::near("alpha0 (Eq. 4.13) of phi 0.2 -> 0.390625", alpha0(0.2, 0.390625), 0.8, 1e-15);

  // 6. The monotonicity certificate: chi' really increases on (0, 1) just below the bound.
  for (double n : {0.1, 0.01, 0.001})
  {
    const double lb = lambda_monotone_bound(n);
    double min_slope = INFINITY;
    for (double phi : linspace(1e-4, 0.9999, 20000))
      min_slope = std::min(min_slope, dchi_constrained(phi, 0.999 * lb, n));
    std::printf("     n = %g: lambda bound %.4f, min dchi'/dphi %.4g\n", n, lb, min_slope);
    check::that("chi' increasing below lambda_monotone_bound, n = " + std::to_string(n),
                min_slope > 0.0);
  }

  // 7. The drained uniaxial modulus against a central difference of the energy of Eq. 4.28
  //    per reference volume under F = diag(lambda, 1, 1) at fixed mu (the mu (J - phi) term is
  //    linear in lambda and drops out). Step 1e-4: truncation h^2/12 |W^(4)| and rounding
  //    4 eps |W| / h^2 ~ 1e-8 for |W| ~ 1, so 1e-6 absolute (|W^(4)| < 100 for phi <= 0.6).
  //    It changes sign at the chi of the spinodal, phi^2 (1/(1-phi) - 2 chi) = -n (phi^(1/3)
  //    + phi/2): at phi = 0.3, n = 0.01 that is chi = 0.7598 (fiber_film refuses the thesis'
  //    alpha0 = 0.8 step to chi_f = 0.846 with it).
  {
    double worst = 0.0;
    for (double n : {0.1, 0.01, 0.001})
      for (double phi : {0.05, 0.2, 0.3, 0.6})
        for (double chi : {0.2, 0.5, 0.846})
        {
          const auto energy = [&](double lambda)
          {
            return n / 2 * phi * (std::pow(phi, -2.0 / 3.0) * (lambda * lambda + 2) - 3
                                  - std::log(lambda / phi))
                   + (lambda - phi) * std::log(1 - phi / lambda)
                   + chi * phi * (1 - phi / lambda);
          };
          const double h = 1e-4;
          const double difference = (energy(1 + h) - 2 * energy(1) + energy(1 - h)) / (h * h);
          worst = std::max(worst, std::abs(drained_uniaxial_modulus(phi, chi, n) - difference));
        }
    check::near("drained uniaxial modulus against d2W/dlambda2, worst", worst, 0.0, 1e-6);
    // The grid holds both signs (chi = 0.846 at phi = 0.3 or 0.6 is inside the spinodal)
    check::that("the modulus is negative inside the spinodal",
                drained_uniaxial_modulus(0.3, 0.846, 0.01) < 0
                    && drained_uniaxial_modulus(0.3, 0.5, 0.01) > 0);
  }

  // 8. Non-unique roots are reported, not silently picked.
  ValueAndSlope cubic = [](double x)
  {
    return std::pair{(x - 0.2) * (x - 0.5) * (x - 0.8),
                     (x - 0.5) * (x - 0.8) + (x - 0.2) * (x - 0.8) + (x - 0.2) * (x - 0.5)};
  };
  try
  {
    unique_root(cubic, 0.0, 1.0, 100, Spacing::uniform, "cubic");
    check::that("three roots raise NonUniqueRoot", false);
  }
  catch (const NonUniqueRoot& e)
  {
    check::that("three roots raise NonUniqueRoot", e.roots.size() == 3);
    check::near("middle root", e.roots[1], 0.5, 1e-14);
  }
  return check::result();
}
