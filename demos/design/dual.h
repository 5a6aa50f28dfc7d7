#pragma once
/// @file dual.h
/// A forward-mode dual number, value + slope eps with eps^2 = 0: evaluated through a function,
/// its slope is the function's derivative along the seeded direction, exact to round-off. The
/// centreline objective (strip.h) is differentiated with it through the helix detector's
/// rates (demos/bistrip/centreline.h), written once as a template: a finite difference would
/// leave a truncation error that the adjoint's Taylor test (tests/design_gradient.cpp) sees.

#include <cmath>

namespace gelx::scenes
{

struct Dual
{
  double value = 0, slope = 0;
  Dual(double v = 0, double s = 0) : value(v), slope(s) {}
};

inline Dual operator+(const Dual& a, const Dual& b) { return {a.value + b.value, a.slope + b.slope}; }
inline Dual operator-(const Dual& a, const Dual& b) { return {a.value - b.value, a.slope - b.slope}; }
inline Dual operator*(const Dual& a, const Dual& b)
{
  return {a.value * b.value, a.slope * b.value + a.value * b.slope};
}
inline Dual operator/(const Dual& a, const Dual& b)
{
  return {a.value / b.value, (a.slope * b.value - a.value * b.slope) / (b.value * b.value)};
}
inline Dual sqrt(const Dual& a)
{
  const double r = std::sqrt(a.value);
  return {r, a.slope / (2 * r)};
}

} // namespace gelx::scenes
