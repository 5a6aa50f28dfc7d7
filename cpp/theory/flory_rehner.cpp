#include "theory/flory_rehner.h"

#include "theory/roots.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gelx::theory
{
namespace
{
// Below this phi the series of h and h' are used: at phi = 0.1 the closed forms lose about
// two digits to cancellation, and 20 series terms reach 0.1^20/22 < 1e-21.
constexpr double series_limit = 0.1;
constexpr int series_terms = 20;

/// Root of an increasing function g on (0, 1) with g(0+) < 0 < g(1-): expand a bracket
/// outwards from `guess`, then Newton with bisection safeguard.
double increasing_root(const ValueAndSlope& g, double guess, const char* what)
{
  if (!(guess > 0.0 && guess < 1.0))
    guess = 0.5;
  double lo = guess, hi = guess;
  double glo = g(lo).first;
  if (glo == 0.0)
    return lo;
  if (glo > 0.0)
  {
    // Root below the guess: shrink lo geometrically towards 0 (phi^-2 overflows below 1e-150).
    do
    {
      hi = lo;
      lo *= 0.25;
      if (lo < 1e-150)
        throw std::runtime_error(std::string(what) + ": no root in (0, 1)");
    } while (g(lo).first > 0.0);
  }
  else
  {
    // Root above the guess: move hi towards 1 by quartering the distance 1 - hi.
    do
    {
      lo = hi;
      hi = 1.0 - 0.25 * (1.0 - hi);
      if (1.0 - hi < 1e-16)
        throw std::runtime_error(std::string(what) + ": no root in (0, 1)");
    } while (g(hi).first < 0.0);
  }
  // Absolute step tolerance relative to the root's size keeps small roots accurate.
  const double xtol = 4e-16 * std::min(lo + hi, 1.0);
  return safeguarded_newton(g, lo, hi, guess > lo && guess < hi ? guess : 0.5 * (lo + hi),
                            xtol);
}
} // namespace

double mixing_h(double phi)
{
  if (phi < series_limit)
  {
    double s = 0.0, p = 1.0;
    for (int k = 0; k < series_terms; ++k, p *= phi)
      s += p / (k + 2);
    return s;
  }
  return -std::log1p(-phi) / (phi * phi) - 1.0 / phi;
}

double mixing_dh(double phi)
{
  if (phi < series_limit)
  {
    double s = 0.0, p = 1.0;
    for (int k = 1; k < series_terms; ++k, p *= phi)
      s += k * p / (k + 2);
    return s;
  }
  // d/dphi [-ln(1-phi)/phi^2 - 1/phi]
  return 1.0 / (phi * phi * (1.0 - phi)) + 2.0 * std::log1p(-phi) / (phi * phi * phi)
         + 1.0 / (phi * phi);
}

double chi_free(double phi, double n)
{
  return 0.5 * n * (1.0 / phi - 2.0 * std::pow(phi, -5.0 / 3.0)) + mixing_h(phi);
}

double dchi_free(double phi, double n)
{
  return 0.5 * n * (-1.0 / (phi * phi) + (10.0 / 3.0) * std::pow(phi, -8.0 / 3.0))
         + mixing_dh(phi);
}

double chi_constrained(double phi, double lambda_par, double n)
{
  return 0.5 * n * (1.0 / phi - 2.0 / (phi * phi * lambda_par)) + mixing_h(phi);
}

double dchi_constrained(double phi, double lambda_par, double n)
{
  return 0.5 * n * (-1.0 / (phi * phi) + 4.0 / (phi * phi * phi * lambda_par))
         + mixing_dh(phi);
}

double chi_difference(double phi, double lambda_par, double n)
{
  return n / (phi * phi) * (1.0 / lambda_par - std::cbrt(phi));
}

double drained_uniaxial_modulus(double phi, double chi, double n)
{
  return phi * phi * (1.0 / (1.0 - phi) - 2.0 * chi) + n * (std::cbrt(phi) + phi / 2.0);
}

double lambda_monotone_bound(double n)
{
  if (n <= 0.0)
    return INFINITY; // chi' = -h is then increasing for every lambda
  // phi_m: positive root of phi^2 + 2 phi^3 = n/2 (increasing in phi, so bisection is safe).
  double a = 0.0, b = 1.0;
  if (b * b + 2 * b * b * b < 0.5 * n)
    return INFINITY; // minimum outside (0,1): quartic increasing on (0,1), positive everywhere
  for (int i = 0; i < 200 && b - a > 1e-16; ++i)
  {
    const double m = 0.5 * (a + b);
    (m * m + 2 * m * m * m < 0.5 * n ? a : b) = m;
  }
  const double pm = 0.5 * (a + b);
  const double deficit = 0.5 * n * pm - pm * pm * pm / 3.0 - 0.5 * pm * pm * pm * pm;
  if (deficit <= 0.0)
    return INFINITY;
  // 2n/lambda > deficit; a 1e-9 relative margin absorbs the rounding of pm.
  return 2.0 * n / deficit * (1.0 - 1e-9);
}

double phi_free(double chi, double n, double guess)
{
  auto g = [chi, n](double phi) { return std::pair{chi_free(phi, n) - chi, dchi_free(phi, n)}; };
  return increasing_root(g, guess, "phi_free (Eq. 4.7)");
}

std::vector<double> phi_constrained_all(double chi, double lambda_par, double n)
{
  auto g = [chi, lambda_par, n](double phi)
  {
    return std::pair{chi_constrained(phi, lambda_par, n) - chi,
                     dchi_constrained(phi, lambda_par, n)};
  };
  // 400 logit-spaced samples resolve features down to ~0.2 in log(phi/(1-phi)).
  return all_roots(g, 0.0, 1.0, 400, Spacing::logit);
}

double phi_constrained(double chi, double lambda_par, double n, double guess)
{
  auto g = [chi, lambda_par, n](double phi)
  {
    return std::pair{chi_constrained(phi, lambda_par, n) - chi,
                     dchi_constrained(phi, lambda_par, n)};
  };
  if (lambda_par < lambda_monotone_bound(n))
    return increasing_root(g, guess, "phi_constrained (Eq. 4.10)");
  return unique_root(g, 0.0, 1.0, 400, Spacing::logit, "phi_constrained (Eq. 4.10)");
}

double sigma3(double phi, double lambda_par, double n)
{
  const double phi_c = 1.0 / (lambda_par * lambda_par * lambda_par);
  return n * phi / lambda_par * (1.0 / phi_c - 1.0 / phi);
}

double prestrain(double lambda_par, double chi, double n)
{
  return lambda_par * std::cbrt(phi_free(chi, n)) - 1.0;
}

double alpha0(double phi_i, double phi_f) { return std::cbrt(phi_i / phi_f); }

double alpha_parallel(double lambda_par_i, double lambda_par_f)
{
  return lambda_par_f / lambda_par_i;
}

double alpha_perpendicular(double phi_i, double lambda_par_i, double phi_f,
                           double lambda_par_f)
{
  // lambda_perp = (phi lambda_par)^-1/2
  return std::sqrt((phi_i * lambda_par_i) / (phi_f * lambda_par_f));
}

double anisotropy(double phi_i, double lambda_par_i, double phi_f, double lambda_par_f)
{
  return alpha_parallel(lambda_par_i, lambda_par_f)
         / alpha_perpendicular(phi_i, lambda_par_i, phi_f, lambda_par_f);
}

Contraction contract(double n, double a0, double phi_i, double eps_par)
{
  Contraction c{};
  c.phi_i = phi_i;
  c.phi_f = phi_i / (a0 * a0 * a0);
  if (!(phi_i > 0.0) || !(c.phi_f < 1.0))
    throw std::invalid_argument("contract: need 0 < phi_i and phi_f = phi_i/alpha0^3 < 1");
  c.chi_i = chi_free(c.phi_i, n);
  c.chi_f = chi_free(c.phi_f, n);
  c.lambda_par = (1.0 + eps_par) / std::cbrt(phi_i);
  c.phi_c = 1.0 / (c.lambda_par * c.lambda_par * c.lambda_par);
  c.phi_prime_i = phi_constrained(c.chi_i, c.lambda_par, n, std::min(c.phi_c, 0.99));
  c.phi_prime_f = phi_constrained(c.chi_f, c.lambda_par, n, c.phi_prime_i);
  c.alpha_perp = alpha_perpendicular(c.phi_prime_i, c.lambda_par, c.phi_prime_f, c.lambda_par);
  c.A_max = 1.0 / c.alpha_perp;
  c.sigma3_i = sigma3(c.phi_prime_i, c.lambda_par, n);
  c.sigma3_f = sigma3(c.phi_prime_f, c.lambda_par, n);
  return c;
}

} // namespace gelx::theory
