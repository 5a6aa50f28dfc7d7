#pragma once
/// @file load_stepping.h
/// Adaptive load stepping: the load factor t goes from 0 to 1 in steps that grow after easy
/// Newton solves and are cut back after failed ones.

#include <gelx/io/parameters.h>
#include <gelx/solvers/path.h>

namespace gelx
{

struct LoadSteppingOptions
{
  double dt = 0.1;         ///< first step
  double dt_min = 1e-4;    ///< smallest step before giving up
  double dt_max = 0.25;    ///< largest step
  double grow = 1.5;       ///< step growth after an easy step
  double cut = 0.5;        ///< step reduction after a failed step
  int easy_iterations = 5; ///< a step that converged in at most this many iterations is easy
  int max_cutbacks = 12;   ///< cut-backs allowed within one step (0 disables cut-back)
  /// Start each step's Newton solve from the last two completed states extrapolated to its
  /// load (a secant predictor) instead of from the last one. Off by default: a closer start
  /// is not always an easier one, and it can carry a state across a contact plane or past a
  /// bifurcation that the last state would not. Measured: the design strip's solve from rest
  /// (demos/design) 47 -> 29 s; the block twisted 18 degrees a step, 59 Newton iterations
  /// against 25 although each step's first residual was a quarter (tests/secant_predictor.py).
  bool secant_predictor = false;

  /// Bind the options to scene parameters (section "load stepping"), the current values as
  /// their defaults.
  void bind(Parameters& p);
  /// Throws InputError unless dt_min <= dt <= dt_max.
  void check() const;
};

/// Follows the load path t: 0 -> 1 with Newton solves at each step.
class LoadStepper
{
public:
  /// `apply_load(t)` sets every load to its value at t (Dirichlet values, pressures, ...).
  LoadStepper(NonlinearSystem& system, NewtonSolver& newton, LoadSteppingOptions options,
              std::function<void(double)> apply_load);

  /// Run from `state` (a new path: PathState{}; a continued one: its loads are applied first)
  /// to t = 1, calling every observer after every completed step. Throws ConvergenceError when a step fails with no cut-back left or when
  /// cutting would take the step below dt_min; the state then holds the last completed step.
  void run(PathState& state, const std::vector<StepObserver>& observers);
  /// Run a new path with one observer, or none.
  void run(const StepObserver& observer = nullptr);

private:
  NonlinearSystem& _system;
  NewtonSolver& _newton;
  LoadSteppingOptions _options;
  std::function<void(double)> _apply_load;
};

} // namespace gelx
