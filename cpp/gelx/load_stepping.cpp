#include "load_stepping.h"
#include "petsc_utils.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <sstream>

namespace gelx
{

void LoadSteppingOptions::declare(Parameters& p) { declare(p, LoadSteppingOptions{}); }

void LoadSteppingOptions::declare(Parameters& p, const LoadSteppingOptions& d)
{
  auto in_unit_interval = [](double v) { return v > 0 && v <= 1 ? "" : "must be in (0, 1]"; };
  p.add("load stepping", "dt", d.dt, "first load-factor step", in_unit_interval);
  p.add("load stepping", "dt_min", d.dt_min, "smallest step", in_unit_interval);
  p.add("load stepping", "dt_max", d.dt_max, "largest step", in_unit_interval);
  p.add("load stepping", "dt_grow", d.grow, "growth factor after an easy step",
        [](double v) { return v >= 1 ? "" : "must be at least 1"; });
  p.add("load stepping", "easy_iterations", d.easy_iterations,
        "Newton iterations up to which a step counts as easy", Parameters::at_least_one);
  p.add("load stepping", "max_cutbacks", d.max_cutbacks,
        "step cut-backs allowed within one step (0 disables cut-back)",
        [](int v) { return v >= 0 ? "" : "must not be negative"; });
}

LoadSteppingOptions LoadSteppingOptions::from(const Parameters& p)
{
  LoadSteppingOptions o;
  o.dt = p.real("dt");
  o.dt_min = p.real("dt_min");
  o.dt_max = p.real("dt_max");
  o.grow = p.real("dt_grow");
  o.easy_iterations = p.integer("easy_iterations");
  o.max_cutbacks = p.integer("max_cutbacks");
  if (o.dt_min > o.dt || o.dt > o.dt_max)
    throw InputError("load stepping needs dt_min <= dt <= dt_max");
  return o;
}

LoadStepper::LoadStepper(NonlinearSystem& system, NewtonSolver& newton,
                         LoadSteppingOptions options, std::function<void(double)> apply_load)
    : _system(system), _newton(newton), _options(options), _apply_load(std::move(apply_load))
{
}

void LoadStepper::run(const std::function<void(const StepRecord&)>& on_step)
{
  const bool root = dolfinx::MPI::rank(PetscObjectComm((PetscObject)_newton.ksp())) == 0;
  // The last converged state, restored after a failed attempt
  struct SavedState
  {
    Vec v;
    ~SavedState() { VecDestroy(&v); }
  } saved{_system.create_vector()};
  double t = 0, dt = _options.dt;
  int step = 0, cutbacks = 0;
  auto start = std::chrono::steady_clock::now();
  // The end point is reached exactly, whatever the step sizes on the way.
  constexpr double t_end = 1.0, t_eps = 1e-12;
  while (t < t_end - t_eps)
  {
    // Stretch the last step a little rather than leave a sliver of load for an extra step
    if (t + 1.25 * dt >= t_end)
      dt = t_end - t;
    GELX_PETSC(VecCopy(_system.unknowns(), saved.v));
    if (root)
      std::printf("  step %d: t = %.6g (dt = %.4g)\n", step + 1, t + dt, dt);
    _apply_load(t + dt);
    NewtonReport report = _newton.solve(_system);
    if (!report.converged)
    {
      GELX_PETSC(VecCopy(saved.v, _system.unknowns()));
      _system.unknowns_changed();
      if (cutbacks == _options.max_cutbacks
          || dt * _options.cut < _options.dt_min * (1 - 1e-12))
      {
        _apply_load(t); // leave loads consistent with the last converged state
        std::ostringstream msg;
        msg << "load step from t = " << t << " to " << t + dt << " failed (" << report.reason
            << ") after " << cutbacks << " cut-backs (max_cutbacks = " << _options.max_cutbacks
            << ", dt_min = " << _options.dt_min << ")";
        throw ConvergenceError(msg.str());
      }
      if (root)
        std::printf("  step failed (%s): cutting dt to %.4g\n", report.reason.c_str(),
                    dt * _options.cut);
      dt *= _options.cut;
      ++cutbacks;
      ++_total_cutbacks;
      continue;
    }
    t += dt;
    ++step;
    auto now = std::chrono::steady_clock::now();
    StepRecord record{step, t, dt, report, cutbacks,
                      std::chrono::duration<double>(now - start).count()};
    on_step(record);
    start = std::chrono::steady_clock::now();
    cutbacks = 0;
    if (report.iterations <= _options.easy_iterations)
      dt = std::min(dt * _options.grow, _options.dt_max);
  }
}

} // namespace gelx
