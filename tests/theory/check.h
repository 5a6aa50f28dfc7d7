#pragma once
// Minimal assertion helpers for the theory tests: every check prints the measured value, the
// expected value and the tolerance, and the test returns non-zero if any check failed.

#include <cmath>
#include <cstdio>
#include <string>

namespace check
{
inline int failures = 0;
inline int passes = 0;

/// |measured - expected| <= tol
inline void near(const std::string& what, double measured, double expected, double tol)
{
  const bool ok = std::abs(measured - expected) <= tol;
  std::printf("%-4s %-58s measured %.12g expected %.12g tol %.3g\n", ok ? "ok" : "FAIL",
              what.c_str(), measured, expected, tol);
  failures += !ok;
  passes += ok;
}

/// condition, with the numbers that decide it printed by the caller
inline void that(const std::string& what, bool ok)
{
  std::printf("%-4s %s\n", ok ? "ok" : "FAIL", what.c_str());
  failures += !ok;
  passes += ok;
}

inline int result()
{
  std::printf("%d passed, %d failed\n", passes, failures);
  return failures ? 1 : 0;
}
} // namespace check
