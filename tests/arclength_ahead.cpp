// The arc-length path does not step back (gelx::ArcLength keeps only corrector points ahead of
// the last point).
//
// The sphere |x - x0|^2 + psi^2 (lambda - l0)^2 = ds^2 meets the path ahead of the last point
// and behind it. Newton from the predictor reaches the point ahead unless it wanders into the
// other's basin: on the crease's 40 x 20 mesh (demos/crease/README.md), next to a nearly
// singular tangent at the fold's turn (where an attempt's first Newton step takes |R| from
// 8e-10 to 4e-3), the corrector of step 31 converged in 14 iterations to step 29's point; every
// later predictor was oriented along that step back, and the path retraced itself to
// chi = 1.8, far below the reference state's swelling (measured 2026-12-07).
//
// Here the path is the unit circle R(x, lambda) = x^2 + lambda^2 - 1 = 0 (one unknown; psi = 1,
// so a step of arc length ds turns the point by 2 asin(ds / 2)), followed from (1, 0) with
// lambda increasing, in steps of at most 0.1. The first corrector attempt of step 4 is sent
// astray as the crease's was: its residual is, until the iterate comes within ds / 2 of
// the circle's point B behind the last point at the attempt's arc length, the distance to B
// along the circle's tangent there; from that basin Newton on the true residual converges to B,
// a point of the path. Checks: every step turns the point forward by 2 asin(ds / 2) of its own
// ds (1e-8: a residual within the corrector's tolerance, |R| <= 1e-9 |dR/dlambda| <= 2e-9,
// moves a point on its sphere by less than 1e-9), and the lured step was cut back and
// completed at half the arc length. With the check of ArcLength::run
// removed, step 4 turns by -0.1 and every step after it as well (the path retraces: seen).

#include "scalar_path.h"
#include "support.h"

#include <gelx/common/petsc_utils.h>
#include <gelx/solvers/arclength.h>

#include <array>
#include <cmath>
#include <cstdio>

namespace
{
/// The unit circle as a path of one unknown x and the load lambda, whose residual lures one
/// corrector attempt to the point behind (lure()).
class Circle : public gelx::test::ScalarPath
{
public:
  explicit Circle(MPI_Comm comm) : ScalarPath(comm, 1.0) {}

  /// The next residual is the first of a corrector attempt, from the last point at angle
  /// theta0: from it on, lure the iterate towards the point behind
  void lure(double theta0)
  {
    _lured_from = theta0;
    _behind_known = false;
  }
  bool luring() const { return !std::isnan(_lured_from); }

  double value(double x, double lambda) override
  {
    if (luring())
    {
      if (!_behind_known)
      {
        // The attempt's predictor: its distance from the last point is the arc length ds
        const double ds = std::hypot(x - std::cos(_lured_from), lambda - std::sin(_lured_from));
        const double theta_b = _lured_from - 2 * std::asin(ds / 2);
        _b = {std::cos(theta_b), std::sin(theta_b)};
        _tangent_b = {-std::sin(theta_b), std::cos(theta_b)};
        _basin = ds / 2;
        _behind_known = true;
      }
      if (std::hypot(x - _b[0], lambda - _b[1]) < _basin)
        _lured_from = NAN; // in B's basin: the true residual from here on
      else
        return _tangent_b[0] * (x - _b[0]) + _tangent_b[1] * (lambda - _b[1]);
    }
    return x * x + lambda * lambda - 1;
  }
  double derivative(double x, double) override { return luring() ? _tangent_b[0] : 2 * x; }

private:
  double _lured_from = NAN, _basin = 0;
  bool _behind_known = false;
  std::array<double, 2> _b{}, _tangent_b{};
};
} // namespace

int main(int argc, char* argv[])
{
  return gelx::test::run_checks(
      argc, argv,
      [](MPI_Comm comm, gelx::test::Checks& checks)
      {
        constexpr int lured_step = 4;
        constexpr double ds = 0.1;
        gelx::set_default_options("circle_", {{"ds", std::to_string(ds)},
                                              {"ds_max", std::to_string(ds)},
                                              {"psi", "1"}});
        Circle circle(comm);
        gelx::ArcLength continuation(comm, circle,
                                     [&](double lambda) { circle.set_load(lambda); }, "circle_");
        gelx::PathState path;
        double theta = 0; // the last point's angle
        continuation.run(
            path, 10,
            {[&](const gelx::StepRecord& pt, gelx::PathState&)
             {
               const double x = circle.x(), angle = std::atan2(pt.load, x);
               const double turn = angle - theta, expected = 2 * std::asin(pt.step_size / 2);
               const double residual = std::abs(x * x + pt.load * pt.load - 1);
               char text[64];
               std::snprintf(text, sizeof text, "|R| = %.1e", residual);
               checks.require("step " + std::to_string(pt.step) + ": on the circle, " + text,
                              residual <= 1e-8);
               checks.relative("step " + std::to_string(pt.step) + ": turned by 2 asin(ds/2) "
                                   "of its ds = " + std::to_string(pt.step_size),
                               turn, expected, 1e-8);
               if (pt.step == lured_step)
                 checks.require("the lured step " + std::to_string(pt.step) + " was cut back ("
                                    + std::to_string(pt.cutbacks) + " cut-backs, ds "
                                    + std::to_string(pt.step_size) + ")",
                                pt.cutbacks == 1 && pt.step_size == ds / 2);
               if (pt.step == lured_step - 1)
                 circle.lure(angle);
               theta = angle;
             }},
            [&](const gelx::StepRecord& pt) { return pt.step >= 8; });
        checks.require("the lured attempt reached the basin of the point behind",
                       !circle.luring());
      });
}
