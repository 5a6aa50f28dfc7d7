#include <gelx/solvers/load_stepping.h>
#include <gelx/common/petsc_utils.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <sstream>

namespace gelx
{

void LoadSteppingOptions::bind(Parameters& p)
{
  auto in_unit_interval = [](double v) { return v > 0 && v <= 1 ? "" : "must be in (0, 1]"; };
  p.bind("load stepping", "dt", dt, "first load-factor step", in_unit_interval);
  p.bind("load stepping", "dt_min", dt_min, "smallest step", in_unit_interval);
  p.bind("load stepping", "dt_max", dt_max, "largest step", in_unit_interval);
  p.bind("load stepping", "dt_grow", grow, "growth factor after an easy step",
         [](double v) { return v >= 1 ? "" : "must be at least 1"; });
  p.bind("load stepping", "easy_iterations", easy_iterations,
         "Newton iterations up to which a step counts as easy", Parameters::at_least_one);
  p.bind("load stepping", "max_cutbacks", max_cutbacks,
         "step cut-backs allowed within one step (0 disables cut-back)",
         [](int v) { return v >= 0 ? "" : "must not be negative"; });
  p.bind("load stepping", "secant_predictor", secant_predictor,
         "start each step from the last two states extrapolated to its load (a secant "
         "predictor) instead of from the last one");
}

void LoadSteppingOptions::check() const
{
  if (dt_min > dt || dt > dt_max)
    throw InputError("load stepping needs dt_min <= dt <= dt_max");
}

LoadStepper::LoadStepper(NonlinearSystem& system, NewtonSolver& newton,
                         LoadSteppingOptions options, std::function<void(double)> apply_load)
    : _system(system), _newton(newton), _options(options), _apply_load(std::move(apply_load))
{
}

void LoadStepper::run(const StepObserver& observer)
{
  PathState state;
  run(state, observer ? std::vector<StepObserver>{observer} : std::vector<StepObserver>{});
}

void LoadStepper::run(PathState& state, const std::vector<StepObserver>& observers)
{
  const bool root = dolfinx::MPI::rank(PetscObjectComm((PetscObject)_newton.snes())) == 0;
  CompletedPoint saved(_system); // the last completed step, restored after a failure
  // The step completed before it and its load, for the secant predictor (none yet: -1)
  OwnedVec before(_system.create_vector()), guess(_system.create_vector());
  double before_load = -1;
  double dt = state.step_size > 0 ? state.step_size : _options.dt;
  int cutbacks = 0;
  // A continued path (a restart) starts with the loads of its last point, which a new run's
  // scene has not applied
  if (state.step > 0)
    _apply_load(state.load);
  auto start = std::chrono::steady_clock::now();
  // The end point is reached exactly, whatever the step sizes on the way.
  constexpr double t_end = 1.0, t_eps = 1e-12;
  while (state.load < t_end - t_eps)
  {
    const double t = state.load;
    // Stretch the last step a little rather than leave a sliver of load for an extra step
    if (t + 1.25 * dt >= t_end)
      dt = t_end - t;
    saved.save();
    _apply_load(t + dt);
    if (_options.secant_predictor && before_load >= 0)
    {
      // guess = saved + dt (saved - before) / (t - before_load)
      GELX_PETSC(VecWAXPY(guess.get(), -1.0, before.get(), saved.unknowns()));
      GELX_PETSC(VecAYPX(guess.get(), dt / (t - before_load), saved.unknowns()));
      _system.set_state(guess.get());
    }
    NewtonReport report = _newton.solve(_system);
    if (!report.converged)
    {
      saved.restore();
      if (cutbacks == _options.max_cutbacks
          || dt * _options.cut < _options.dt_min * (1 - 1e-12))
      {
        _apply_load(t); // leave loads consistent with the last completed state
        std::ostringstream msg;
        msg << "load step from t = " << t << " to " << t + dt << " failed (" << report.reason
            << ") after " << cutbacks << " cut-backs, and no further one was tried: ";
        if (cutbacks == _options.max_cutbacks)
          msg << "max_cutbacks = " << _options.max_cutbacks << " reached";
        else
          msg << "the next step, " << dt * _options.cut << ", would be below dt_min = "
              << _options.dt_min;
        throw ConvergenceError(msg.str());
      }
      if (root)
        std::printf("  step failed (%s): cutting dt to %.4g\n", report.reason.c_str(),
                    dt * _options.cut);
      dt *= _options.cut;
      ++cutbacks;
      ++state.cutbacks;
      continue;
    }
    GELX_PETSC(VecCopy(saved.unknowns(), before.get()));
    before_load = t;
    state.load = t + dt;
    ++state.step;
    if (report.iterations <= _options.easy_iterations)
      dt = std::min(dt * _options.grow, _options.dt_max);
    state.step_size = dt;
    const auto now = std::chrono::steady_clock::now();
    StepRecord record;
    record.step = state.step;
    record.load = state.load;
    record.step_size = state.load - t;
    record.newton = report;
    record.cutbacks = cutbacks;
    record.wall_time = std::chrono::duration<double>(now - start).count();
    for (const auto& observe : observers)
      observe(record, state);
    start = std::chrono::steady_clock::now();
    cutbacks = 0;
  }
}

} // namespace gelx
