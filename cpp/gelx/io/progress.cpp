#include <gelx/io/progress.h>
#include <gelx/io/parameters.h>
#include <gelx/common/petsc_utils.h>

#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>

namespace gelx
{
namespace
{
int step_budget = 0; ///< set_step_budget's; 0: none
int steps_taken = 0; ///< steps printed so far, by every ProgressLine of the run
} // namespace

void set_step_budget(int steps)
{
  step_budget = steps;
  steps_taken = 0;
}

ProgressLine::ProgressLine(MPI_Comm comm, Options options)
    : _options(std::move(options)), _root(dolfinx::MPI::rank(comm) == 0),
      _start(std::chrono::steady_clock::now())
{
  if (!_options.load)
    _options.load = [](const StepRecord& r) { return r.load; };
  if (!_options.fraction)
    _options.fraction = [](const StepRecord& r) { return r.load; };
}

void ProgressLine::print(const StepRecord& record, double load, double fraction)
{
  const auto now = std::chrono::steady_clock::now();
  if (std::isnan(_first_fraction))
  {
    _first_time = now;
    _first_fraction = fraction;
  }
  // on every rank: a scene's quantity may be collective
  const std::string quantity = _options.quantity ? _options.quantity() : "";
  if (_root)
    print_line(record, load, fraction, quantity, now);
  count_step();
}

void ProgressLine::print_line(const StepRecord& record, double load, double fraction,
                              const std::string& quantity,
                              std::chrono::steady_clock::time_point now) const
{
  const double elapsed = std::chrono::duration<double>(now - _start).count();
  std::string left;
  // The pace of the steps since the first line, extrapolated to the end of the path
  if (const double done = fraction - _first_fraction; std::isfinite(done) && done > 0)
  {
    const double pace = std::chrono::duration<double>(now - _first_time).count() / done;
    char text[48];
    std::snprintf(text, sizeof(text), ", ~%.0f s left", pace * std::max(0.0, 1 - fraction));
    left = text;
  }
  std::string iterations = "Newton " + std::to_string(record.newton.iterations);
  if (record.cutbacks > 0)
    iterations += " (" + std::to_string(record.cutbacks) + " cut-backs)";
  std::string events;
  if (record.limit_point)
    events += "  (limit point passed)";
  if (record.bifurcation)
    events += "  (bifurcation passed)";
  std::printf("  step %3d  %s = %-10.6g  %-12s  %s  %7.1f s%s%s\n", record.step,
              _options.load_name.c_str(), load, iterations.c_str(),
              quantity.c_str(), elapsed, left.c_str(),
              events.c_str());
  std::fflush(stdout);
}

void ProgressLine::count_step()
{
  // A misspelt option of a solver that has run ends the run here, not after its last step
  if (const std::string misspelt = unread_options_of_set_up_solvers(); !misspelt.empty())
    throw InputError("no solver object read the option(s) " + misspelt
                     + " (misspelt? the solver of that prefix has read its options)");
  if (step_budget > 0 && ++steps_taken >= step_budget)
    throw StepBudgetSpent("stopped after " + std::to_string(steps_taken)
                          + " steps (--stop_after_steps)");
}

std::string quantity_text(const std::string& name, double value)
{
  char text[96];
  std::snprintf(text, sizeof(text), "%s = %-10.6g", name.c_str(), value);
  return text;
}

} // namespace gelx
