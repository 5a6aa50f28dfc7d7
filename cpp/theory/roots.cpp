#include "theory/roots.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace gelx::theory
{

double safeguarded_newton(const ValueAndSlope& f, double lo, double hi, double x0, double xtol,
                          int max_iterations)
{
  auto [flo, dlo] = f(lo);
  auto [fhi, dhi] = f(hi);
  if (flo == 0.0)
    return lo;
  if (fhi == 0.0)
    return hi;
  if ((flo > 0.0) == (fhi > 0.0))
    throw std::invalid_argument("safeguarded_newton: [lo, hi] does not bracket a root");
  // Orient the bracket so that f(a) < 0 < f(b); a may be larger than b.
  double a = flo < 0.0 ? lo : hi;
  double b = flo < 0.0 ? hi : lo;
  double x = (x0 > std::min(lo, hi) && x0 < std::max(lo, hi)) ? x0 : 0.5 * (lo + hi);
  double dx_old = std::abs(hi - lo);
  for (int it = 0; it < max_iterations; ++it)
  {
    auto [fx, dfx] = f(x);
    if (fx == 0.0)
      return x;
    if (fx < 0.0)
      a = x;
    else
      b = x;
    // Newton if it lands strictly inside the bracket and halves the step at least every other
    // iteration (the rtsafe criterion); otherwise bisect.
    double xn = x - fx / dfx;
    double dx;
    const bool inside = std::isfinite(xn) && (xn - a) * (xn - b) < 0.0;
    if (inside && std::abs(2.0 * fx) < std::abs(dx_old * dfx))
    {
      dx = xn - x;
      x = xn;
    }
    else
    {
      xn = 0.5 * (a + b);
      dx = xn - x;
      x = xn;
    }
    dx_old = dx;
    if (std::abs(dx) <= xtol || std::abs(a - b) <= xtol)
      return x;
  }
  return x; // bracket width after max_iterations bisections is below any useful tolerance
}

std::vector<double> all_roots(const ValueAndSlope& f, double lo, double hi, int samples,
                              Spacing spacing, double xtol)
{
  auto point = [&](int i)
  {
    const double t = (i + 1.0) / (samples + 1.0); // interior points only: ends may be singular
    if (spacing == Spacing::uniform)
      return lo + t * (hi - lo);
    // logit spacing on (lo, hi): s in [-L, L] mapped through the logistic function.
    const double L = 36.0; // 1/(1+e^36) ~ 2e-16: reaches the ends to machine precision
    const double s = -L + 2.0 * L * t;
    return lo + (hi - lo) / (1.0 + std::exp(-s));
  };
  std::vector<double> roots;
  double x_prev = point(0);
  double f_prev = f(x_prev).first;
  if (f_prev == 0.0)
    roots.push_back(x_prev);
  for (int i = 1; i < samples; ++i)
  {
    const double x = point(i);
    const double fx = f(x).first;
    if (fx == 0.0)
      roots.push_back(x);
    else if (f_prev != 0.0 && (f_prev > 0.0) != (fx > 0.0))
      roots.push_back(safeguarded_newton(f, x_prev, x, 0.5 * (x_prev + x), xtol));
    x_prev = x;
    f_prev = fx;
  }
  return roots;
}

double unique_root(const ValueAndSlope& f, double lo, double hi, int samples, Spacing spacing,
                   const std::string& what)
{
  std::vector<double> r = all_roots(f, lo, hi, samples, spacing);
  if (r.empty())
    throw std::runtime_error(what + ": no root on (" + std::to_string(lo) + ", "
                             + std::to_string(hi) + ")");
  if (r.size() > 1)
  {
    std::ostringstream s;
    s.precision(10);
    s << what << ": " << r.size() << " roots:";
    for (double x : r)
      s << " " << x;
    throw NonUniqueRoot(s.str(), r);
  }
  return r[0];
}

} // namespace gelx::theory
