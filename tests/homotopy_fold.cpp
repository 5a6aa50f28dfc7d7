// From one equilibrium to another across the folds of the way between them
// (gelx::follow_homotopy: load steps, then arc length once they fail, then a landing at t = 1).
//
// The path is the cubic R(x, t) = x^3 - 3 x - (6 t - 3) = 0, from its one root at t = 0 to its
// one root at t = 1 (Cardano: x = -+(cbrt(3/2 + sqrt(5/4)) + cbrt(3/2 - sqrt(5/4))), -+2.1038).
// Along the way t(x) = (x^3 - 3 x + 3) / 6 rises to the fold t = 5/6 at x = -1, falls to the
// fold t = 1/6 at x = 1 and rises again: a state carried by slowly increasing t snaps at
// t = 5/6 from x = -1 to the far branch, whose root at t = 1 it then reaches. Load steps stop at
// the first fold (Newton near x = -1 with a line search stalls at |R|'s local minimum there);
// with them alone the test throws. (Without the secant predictor: its extrapolation carries
// the scalar state over the fold, from where Newton on a cubic finds the far root, a jump
// that the design strip's Newton did not survive; demos/design/README.md.)
// Checks: every step's residual is |R| <= 1e-8; the end is the far root (relative 1e-10:
// Newton's residual test, |R| <= 1e-10 with dR/dx = 10 there); the path passed both folds,
// in that order: t turned back and forward again at points no further than 1e-9 beyond the
// folds (every point solves R = 0 to ~1e-10, and t's error is R's / 6) and within 0.05 of
// them (the point where t turns is within one step of the fold, |dx| <= ds_max = 0.2 psi =
// 0.26 with psi = 1.32, and t is 5/6 - (x + 1)^2 / 2 there: 0.034 at most).

#include "scalar_path.h"
#include "support.h"

#include <gelx/common/petsc_utils.h>
#include <gelx/solvers/homotopy.h>

#include <cmath>

namespace
{
class Cubic : public gelx::test::ScalarPath
{
public:
  using ScalarPath::ScalarPath;
  double value(double x, double t) override { return x * x * x - 3 * x - (6 * t - 3); }
  double derivative(double x, double) override { return 3 * x * x - 3; }
};
} // namespace

int main(int argc, char* argv[])
{
  return gelx::test::run_checks(
      argc, argv,
      [](MPI_Comm comm, gelx::test::Checks& checks)
      {
        const double root = std::cbrt(1.5 + std::sqrt(1.25)) + std::cbrt(1.5 - std::sqrt(1.25));
        gelx::set_default_options("cubic_", {{"snes_rtol", "0"}, {"snes_atol", "1e-10"}});
        gelx::set_default_options("cubic_arclength_", {{"snes_atol", "1e-10"}});
        Cubic cubic(comm, -root);
        gelx::NewtonSolver newton(comm, "cubic_");
        // Where t turned back (a fold) and then forward again
        int turns = 0;
        double last_load = 0, direction = 1, turned_down_at = NAN, turned_up_at = NAN;
        gelx::follow_homotopy(
            cubic, newton, {},
            [&](double t) { cubic.set_load(t); },
            [&](const gelx::StepRecord& pt, gelx::PathState&)
            {
              const double residual = std::abs(cubic.value(cubic.x(), pt.load));
              checks.require("step " + std::to_string(pt.step) + " at t = "
                                 + std::to_string(pt.load) + ": |R| = "
                                 + std::to_string(residual),
                             residual <= 1e-8);
              // (the landing at t = 1 comes back from the point past it: not a turn of the path)
              if (last_load < 1 && (pt.load - last_load) * direction < 0)
              {
                (++turns == 1 ? turned_down_at : turned_up_at) = last_load;
                direction = -direction;
              }
              last_load = pt.load;
            },
            "cubic_arclength_");
        checks.relative("the end: the root on the far branch", cubic.x(), root, 1e-10);
        checks.require("t turned back, then forward again (" + std::to_string(turns)
                           + " turns)",
                       turns == 2);
        checks.require("t turned back at " + std::to_string(turned_down_at)
                           + ", within 0.05 below the fold 5/6",
                       turned_down_at <= 5.0 / 6 + 1e-9 && turned_down_at >= 5.0 / 6 - 0.05);
        checks.require("t turned forward at " + std::to_string(turned_up_at)
                           + ", within 0.05 above the fold 1/6",
                       turned_up_at >= 1.0 / 6 - 1e-9 && turned_up_at <= 1.0 / 6 + 0.05);
      });
}
