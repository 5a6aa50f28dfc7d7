#pragma once
/// @file transient_record.h
/// What a transient scene records after each accepted step, in one place.

#include <gelx/io/program.h>
#include <gelx/solvers/transient.h>

#include <nlohmann/json.hpp>

namespace gelx
{

/// The bookkeeping of a transient scene after each accepted step, so that its observer says
/// only what it measures: the steps.csv row (TransientStep::columns() and the scene's
/// columns), the fields at times evenly spaced in log t (LogTimeOutputs), the summary (the
/// scene's quantities, the time, the Newton and linear iterations in total), the progress
/// line, and a checkpoint with TS's history, the totals and the outputs' state, so that a
/// restarted run records what the uninterrupted one would have.
class TransientRecorder
{
public:
  /// `start`: where the path starts (Run::start_path), restored totals and outputs included
  TransientRecorder(Run& run, ResultsWriter& results, const TransientProblem& transient,
                    FieldSet& fields, ProgressLine& progress, int outputs, double end_time,
                    const PathState& start);

  /// After the accepted step `s`, the scene's fields current: `quantities` go into the row
  /// and the summary, `columns` into the row only. Collective.
  void operator()(const TransientStep& s, const nlohmann::json& quantities,
              const nlohmann::json& columns = nlohmann::json::object());

private:
  Run& _run;
  ResultsWriter& _results;
  const TransientProblem& _transient;
  FieldSet& _fields;
  ProgressLine& _progress;
  LogTimeOutputs _outputs;
  StepObserver _checkpoints;
  int _newton_iterations, _linear_iterations;
};

} // namespace gelx
