#pragma once
/// @file progress.h
/// The one line per step that a run prints by default.

#include <gelx/solvers/path.h>
#include <chrono>
#include <functional>
#include <mpi.h>
#include <stdexcept>
#include <string>

namespace gelx
{

/// Prints one line per completed step on rank 0, the default output of a run:
///
///     step  12  d/H = 0.135  Newton  4  l_c/L = 0.1203   12.3 s, ~15 s left
///
/// the step, its load, the Newton iterations (and cut-backs), the scene's key quantity, the
/// time since the path started and an estimate of the time left, from the pace so far. The
/// solvers' own tables stay behind their monitor options (-newton_snes_monitor,
/// -arclength_snes_monitor, -dynamics_ts_monitor, ...). Put it after a path's other observers:
/// `quantity` may read what they computed for the step.
class ProgressLine
{
public:
  struct Options
  {
    std::string load_name = "t"; ///< what the load is called (t, d/H, p/G, T ...)
    /// its value after a step (default: the record's load factor)
    std::function<double(const StepRecord&)> load;
    /// the scene's key quantity after the step, as "name = value" (default: none)
    std::function<std::string()> quantity;
    /// how far the path has got, 0 to 1 (default: the load factor t of a load-stepped path);
    /// NaN where the end is not known in advance (a continuation that stops on an event):
    /// then no estimate of the time left
    std::function<double(const StepRecord&)> fraction;
  };

  ProgressLine(MPI_Comm comm, Options options);

  /// As a path's observer (StepObserver)
  void operator()(const StepRecord& record, PathState&)
  {
    print(record, _options.load(record), _options.fraction(record));
  }
  /// Print the line of a completed step at `load` and `fraction` of the path, where the record
  /// does not hold them (a dynamics run: its time t, and t over the run's end time)
  void print(const StepRecord& record, double load, double fraction);

private:
  /// The line itself (rank 0)
  void print_line(const StepRecord& record, double load, double fraction,
                  const std::string& quantity, std::chrono::steady_clock::time_point now) const;
  /// Count the step against set_step_budget's budget; refuse the options the solvers that
  /// took it left unread (unread_options_of_set_up_solvers: InputError)
  static void count_step();

  Options _options;
  bool _root;
  std::chrono::steady_clock::time_point _start;
  /// The first line's clock and fraction: the pace is measured from there, so that a
  /// restarted path estimates from its own steps
  std::chrono::steady_clock::time_point _first_time;
  double _first_fraction = NAN;
};

/// Stop the run after `steps` steps in all, over every path (0: no limit), to check quickly that
/// a command runs (--stop_after_steps): ProgressLine throws StepBudgetSpent after printing the
/// last one, on every rank at the same step.
void set_step_budget(int steps);

/// The run has taken the steps set_step_budget allowed: run_program ends it there, as a success.
class StepBudgetSpent : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// "name = value" with 6 significant digits: a ProgressLine's quantity.
std::string quantity_text(const std::string& name, double value);

} // namespace gelx
