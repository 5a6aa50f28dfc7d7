#pragma once
/// @file roots.h
/// Bracketed scalar root finding for the 0-D models: a bisection-safeguarded Newton method and a
/// sign-change scan that finds every root on an interval, so callers can tell when an inverse
/// such as phi(chi) is not unique.

#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace gelx::theory
{

/// A root was asked to be unique but the scan found several; `roots` holds all of them.
class NonUniqueRoot : public std::runtime_error
{
public:
  NonUniqueRoot(const std::string& what, std::vector<double> roots)
      : std::runtime_error(what), roots(std::move(roots))
  {
  }
  std::vector<double> roots;
};

/// f(x) and f'(x) evaluated together (they share the expensive logarithms).
using ValueAndSlope = std::function<std::pair<double, double>(double)>;

/// Root of f in the bracket [lo, hi] (f(lo) and f(hi) of opposite sign, or one of them zero),
/// started from x0. Newton steps are taken while they stay inside the current bracket and shrink
/// it fast enough; otherwise the step is a bisection, so convergence is guaranteed and is
/// quadratic near a simple root. Stops when the step is below `xtol` (absolute) or f is zero.
/// Throws std::invalid_argument when [lo, hi] is not a bracket.
double safeguarded_newton(const ValueAndSlope& f, double lo, double hi, double x0,
                          double xtol = 1e-15, int max_iterations = 200);

/// Every root of f on (lo, hi): f is sampled at `samples` points spaced uniformly in
/// `transform`-space (see below), each sign change is refined with safeguarded_newton. Roots
/// closer together than the sample spacing can be missed; the callers in this library know
/// f's limits at the ends of the interval and choose the sampling accordingly.
/// `logit` spaces the samples uniformly in log(x/(1-x)), which resolves both ends of (0, 1).
enum class Spacing
{
  uniform,
  logit
};
std::vector<double> all_roots(const ValueAndSlope& f, double lo, double hi, int samples,
                              Spacing spacing = Spacing::uniform, double xtol = 1e-15);

/// The root of f on (lo, hi) when there is exactly one; throws NonUniqueRoot (several roots) or
/// std::runtime_error (none). `what` names the equation in the message.
double unique_root(const ValueAndSlope& f, double lo, double hi, int samples, Spacing spacing,
                   const std::string& what);

} // namespace gelx::theory
