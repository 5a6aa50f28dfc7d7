#pragma once
/// @file load_stepping.h
/// Adaptive load stepping: the load factor t goes from 0 to 1 in steps that grow after easy
/// Newton solves and are cut back after failed ones.

#include "newton.h"
#include "parameters.h"
#include <functional>
#include <stdexcept>

namespace gelx
{

/// The load path could not be followed: a step failed at the smallest allowed size.
class ConvergenceError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

struct LoadSteppingOptions
{
  double dt = 0.1;         ///< first step
  double dt_min = 1e-4;    ///< smallest step before giving up
  double dt_max = 0.25;    ///< largest step
  double grow = 1.5;       ///< step growth after an easy step
  double cut = 0.5;        ///< step reduction after a failed step
  int easy_iterations = 5; ///< a step that converged in at most this many iterations is easy
  int max_cutbacks = 12;   ///< cut-backs allowed within one step (0 disables cut-back)

  /// Declare the options as scene parameters (section "load stepping"), with a scene's own
  /// defaults.
  static void declare(Parameters& p, const LoadSteppingOptions& defaults);
  static void declare(Parameters& p);
  static LoadSteppingOptions from(const Parameters& p);
};

/// One converged step.
struct StepRecord
{
  int step = 0;
  double t = 0;             ///< load factor reached
  double dt = 0;            ///< step taken
  NewtonReport newton;      ///< the converged solve
  int cutbacks = 0;         ///< failed attempts before this step converged
  double wall_time = 0;     ///< seconds spent on this step, failed attempts included
};

/// Follows the load path t: 0 -> 1 with Newton solves at each step.
class LoadStepper
{
public:
  /// `apply_load(t)` sets every load to its value at t (Dirichlet values, pressures, ...).
  LoadStepper(NonlinearSystem& system, NewtonSolver& newton, LoadSteppingOptions options,
              std::function<void(double)> apply_load);

  /// Run to t = 1, calling `on_step` after every converged step (write output there: a step
  /// reported is complete). Throws ConvergenceError when a step fails with no cut-back left
  /// or when cutting would take the step below dt_min.
  void run(const std::function<void(const StepRecord&)>& on_step);

  int total_cutbacks() const { return _total_cutbacks; }

private:
  NonlinearSystem& _system;
  NewtonSolver& _newton;
  LoadSteppingOptions _options;
  std::function<void(double)> _apply_load;
  int _total_cutbacks = 0;
};

} // namespace gelx
