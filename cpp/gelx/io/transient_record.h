#pragma once
/// @file transient_record.h
/// What a transient scene records after each accepted step, in one place.

#include <gelx/io/program.h>
#include <gelx/solvers/transient.h>

#include <functional>
#include <nlohmann/json.hpp>

namespace gelx
{

/// When a transient writes its fields: at `count` times evenly spaced in log t from its first
/// step's time t1 to the end T, t1 (T/t1)^(k/(count - 1)) for k = 0 ... count - 1 (one output:
/// T), because a transient spans decades (a front's sqrt(t) start, the slow approach to
/// equilibrium); and how far it has got, in log t. Its state goes into a checkpoint's scene
/// record, so that a restarted run writes what the uninterrupted one would have.
class LogTimeOutputs
{
public:
  /// @param scene a restarted path's scene record (what save() wrote), or empty
  LogTimeOutputs(int count, double end_time, const nlohmann::json& scene);
  /// After the accepted step number `step` at time t: whether fields are due.
  bool due(int step, double t);
  /// How far the transient has got at time t, 0 to 1 in log t.
  double progress(double t) const;
  /// Its state into a checkpoint's scene record.
  void save(nlohmann::json& scene) const;

private:
  double output_time(int k) const;
  int _count;
  double _end_time;
  double _first_time = 0;
  int _written = 0;
};

/// Runs a transient scene's TransientProblem and keeps its books after each accepted step, so
/// that the scene says only what it measures: the steps.csv row (TransientStep::columns() and
/// the scene's columns), the fields at times evenly spaced in log t (LogTimeOutputs), the
/// summary (the scene's quantities, the time, the number of steps, the Newton and linear
/// iterations in total), the progress line, and a checkpoint with TS's history, the totals
/// and the outputs' state, so that a restarted run records what the uninterrupted one would
/// have.
class TransientRecorder
{
public:
  /// What a scene measures after an accepted step: `quantities` go into the row and the
  /// summary, `columns` into the row only.
  struct Measured
  {
    nlohmann::json quantities;
    nlohmann::json columns = nlohmann::json::object();
  };

  /// `start`: where the path starts (Run::start_path), restored totals and outputs included
  TransientRecorder(Run& run, ResultsWriter& results, TransientProblem& transient,
                    FieldSet& fields, ProgressLine& progress, int outputs, PathState start);

  /// Runs the transient to its end from `start`, calling `measure` after each accepted step
  /// with the system at that step's state (the scene's fields to be brought up to date
  /// there). Collective.
  void run(const std::function<Measured(const TransientStep&)>& measure);

private:
  void record(const TransientStep& s, const Measured& m);

  Run& _run;
  ResultsWriter& _results;
  TransientProblem& _transient;
  FieldSet& _fields;
  ProgressLine& _progress;
  PathState _start;
  LogTimeOutputs _outputs;
  StepObserver _checkpoints;
  int _newton_iterations, _linear_iterations;
};

} // namespace gelx
