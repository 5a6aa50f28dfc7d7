#include "arclength.h"
#include "load_stepping.h"
#include "petsc_utils.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <sstream>

namespace gelx
{

ArcLength::ArcLength(MPI_Comm comm, NonlinearProblem& problem,
                     std::function<void(double)> set_load_factor, const std::string& prefix)
    : _comm(comm), _problem(problem), _set_load(std::move(set_load_factor)), _prefix(prefix)
{
  _ksp = create_linear_solver(comm, prefix);
  _K = problem.create_matrix();
  for (Vec* v : {&_R, &_f, &_a, &_b, &_du, &_du_prev, &_u0, &_tmp, &_branch})
    *v = problem.create_vector();
}

ArcLength::~ArcLength()
{
  KSPDestroy(&_ksp);
  MatDestroy(&_K);
  for (Vec* v : {&_R, &_f, &_a, &_b, &_du, &_du_prev, &_u0, &_tmp, &_branch})
    VecDestroy(v);
}

void ArcLength::load_derivative(double lambda, Vec f)
{
  const double h = 1e-4 * std::max(1.0, std::abs(lambda));
  _set_load(lambda + h);
  _problem.residual(f);
  _set_load(lambda - h);
  _problem.residual(_tmp);
  _set_load(lambda);
  GELX_PETSC(VecAXPY(f, -1.0, _tmp));
  GELX_PETSC(VecScale(f, 1.0 / (2 * h)));
}

double ArcLength::switch_branch()
{
  _problem.tangent(_K);
  const BucklingMode mode = lowest_tangent_eigenpair(_comm, _K, _problem.u()->function_space());
  // The mode's owned entries, in the layout of the unknowns' vector
  PetscInt n;
  PetscScalar* direction;
  GELX_PETSC(VecGetLocalSize(_branch, &n));
  GELX_PETSC(VecGetArray(_branch, &direction));
  std::copy_n(mode.shape->x()->array().begin(), n, direction);
  GELX_PETSC(VecRestoreArray(_branch, &direction));
  PetscReal norm;
  GELX_PETSC(VecNormalize(_branch, &norm));
  _switch_branch = true;
  return mode.load_factor;
}

std::pair<double, double> parabola_vertex(const double s[3], const double l[3])
{
  // lambda(s) = c0 + c1 s + c2 s^2 through the three points (divided differences)
  const double d01 = (l[1] - l[0]) / (s[1] - s[0]), d12 = (l[2] - l[1]) / (s[2] - s[1]);
  const double c2 = (d12 - d01) / (s[2] - s[0]);
  const double c1 = d01 - c2 * (s[0] + s[1]);
  const double c0 = l[0] - c1 * s[0] - c2 * s[0] * s[0];
  const double sv = -c1 / (2 * c2);
  return {sv, c0 + c1 * sv + c2 * sv * sv};
}

void ArcLength::run(double lambda0, int max_steps,
                    const std::function<void(const PathPoint&)>& on_point,
                    const std::function<bool(const PathPoint&)>& stop)
{
  double ds = real_option(_prefix, "ds", 0.05);
  const double ds_max = real_option(_prefix, "ds_max", 10 * ds);
  const double ds_min = real_option(_prefix, "ds_min", 1e-6 * ds);
  const double psi = real_option(_prefix, "psi", 0.0);
  const int max_it = int_option(_prefix, "max_it", 15);
  const int target_it = int_option(_prefix, "target_it", 5);
  const double rtol = real_option(_prefix, "rtol", 1e-9);
  const bool monitor = int_option(_prefix, "monitor", 1) && dolfinx::MPI::rank(_comm) == 0;
  const bool track_stability = int_option(_prefix, "stability", 0) != 0;

  Vec u = _problem.unknowns();
  double lambda = lambda0, s = 0, dlambda_prev = 0;
  bool have_direction = false;
  PathPoint point;
  point.load_factor = lambda;
  auto dot = [](Vec x, Vec y)
  {
    PetscScalar d;
    GELX_PETSC(VecDot(x, y, &d));
    return static_cast<double>(d);
  };
  auto solve = [&](Vec rhs, Vec x)
  {
    GELX_PETSC(KSPSolve(_ksp, rhs, x));
    KSPConvergedReason reason;
    GELX_PETSC(KSPGetConvergedReason(_ksp, &reason));
    return reason >= 0;
  };

  for (int step = 1; step <= max_steps; ++step)
  {
    GELX_PETSC(VecCopy(u, _u0));
    int cutbacks = 0;
    while (true)
    {
      // Predictor along the tangent, K du_t = -dR/dlambda, or along the branch's mode
      _set_load(lambda);
      _problem.tangent(_K);
      GELX_PETSC(KSPSetOperators(_ksp, _K, _K));
      load_derivative(lambda, _f);
      const double f_norm = std::sqrt(dot(_f, _f));
      bool ok = true;
      double Dl = 0;
      if (_switch_branch)
      {
        GELX_PETSC(VecCopy(_branch, _du));
        GELX_PETSC(VecScale(_du, ds));
      }
      else
      {
        GELX_PETSC(VecScale(_f, -1.0));
        ok = solve(_f, _b);
        GELX_PETSC(VecScale(_f, -1.0));
        double dl = ds / std::sqrt(dot(_b, _b) + psi * psi);
        if (have_direction && dot(_b, _du_prev) + psi * psi * dlambda_prev < 0)
          dl = -dl; // keep going the way the path went: through a limit point, lambda decreases
        GELX_PETSC(VecCopy(_b, _du));
        GELX_PETSC(VecScale(_du, dl));
        Dl = dl;
      }

      int it = 0;
      bool converged = false;
      for (; ok && it < max_it; ++it)
      {
        GELX_PETSC(VecWAXPY(u, 1.0, _du, _u0));
        _problem.unknowns_changed();
        _set_load(lambda + Dl);
        if (!_problem.admissible())
          break;
        _problem.residual(_R);
        const double r_norm = std::sqrt(dot(_R, _R));
        if (monitor)
          std::printf("    %3d  |R| = %.4e  lambda = %.10g\n", it, r_norm, lambda + Dl);
        if (!std::isfinite(r_norm))
          break;
        if (r_norm <= rtol * f_norm)
        {
          converged = true;
          break;
        }
        _problem.tangent(_K);
        GELX_PETSC(KSPSetOperators(_ksp, _K, _K));
        load_derivative(lambda + Dl, _f);
        GELX_PETSC(VecScale(_R, -1.0));
        GELX_PETSC(VecScale(_f, -1.0));
        ok = solve(_R, _a) && solve(_f, _b);
        // |du + a + d b|^2 + psi^2 (Dl + d)^2 = ds^2
        GELX_PETSC(VecAXPY(_a, 1.0, _du)); // a <- du + a
        const double A = dot(_b, _b) + psi * psi;
        const double B = 2 * (dot(_a, _b) + psi * psi * Dl);
        const double C = dot(_a, _a) + psi * psi * Dl * Dl - ds * ds;
        const double disc = B * B - 4 * A * C;
        if (disc < 0)
        {
          ok = false;
          break;
        }
        const double roots[2] = {(-B + std::sqrt(disc)) / (2 * A), (-B - std::sqrt(disc)) / (2 * A)};
        // the root whose increment points most along the current one
        double best = roots[0], best_cos = -INFINITY;
        for (double d : roots)
        {
          const double c = dot(_a, _du) + d * dot(_b, _du) + psi * psi * (Dl + d) * Dl;
          if (c > best_cos)
          {
            best_cos = c;
            best = d;
          }
        }
        GELX_PETSC(VecWAXPY(_du, best, _b, _a));
        Dl += best;
      }
      if (converged)
      {
        const double previous = dlambda_prev;
        lambda += Dl;
        s += ds;
        GELX_PETSC(VecCopy(_du, _du_prev));
        dlambda_prev = Dl;
        have_direction = true;
        _switch_branch = false;
        const double previous_stability = point.stability;
        point = {step, lambda, s, it, cutbacks, previous * Dl < 0};
        if (track_stability)
        {
          _problem.tangent(_K);
          point.stability
              = lowest_tangent_eigenpair(_comm, _K, _problem.u()->function_space()).load_factor;
          point.bifurcation = !point.limit_point && previous_stability * point.stability < 0;
        }
        if (monitor)
          std::printf("  arc-length step %d: lambda = %.10g, s = %.6g, %d iterations%s%s\n",
                      step, lambda, s, it, point.limit_point ? " (limit point passed)" : "",
                      point.bifurcation ? " (bifurcation passed)" : "");
        on_point(point);
        ds = std::min(ds_max, ds * std::clamp(std::sqrt(double(target_it) / std::max(it, 1)),
                                              0.5, 2.0));
        break;
      }
      // Failed: back to the last point with half the arc length
      GELX_PETSC(VecCopy(_u0, u));
      _problem.unknowns_changed();
      _set_load(lambda);
      ds *= 0.5;
      ++cutbacks;
      if (ds < ds_min)
      {
        std::ostringstream msg;
        msg << "arc-length step " << step << " failed at lambda = " << lambda
            << " with the arc length below ds_min = " << ds_min;
        throw ConvergenceError(msg.str());
      }
    }
    if (stop(point))
      return;
  }
}

} // namespace gelx
