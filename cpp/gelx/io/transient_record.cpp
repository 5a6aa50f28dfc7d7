#include "transient_record.h"

#include <cmath>

namespace gelx
{

LogTimeOutputs::LogTimeOutputs(int count, double end_time, const nlohmann::json& scene)
    : _count(count), _end_time(end_time), _first_time(scene.value("first_time", 0.0)),
      _written(scene.value("outputs_written", 0))
{
}

double LogTimeOutputs::output_time(int k) const
{
  return _count == 1 ? _end_time
                     : _first_time * std::pow(_end_time / _first_time, double(k) / (_count - 1));
}

bool LogTimeOutputs::due(int step, double t)
{
  if (step == 1)
    _first_time = t;
  if (_written >= _count || t < output_time(_written) * (1 - 1e-12))
    return false;
  while (_written < _count && output_time(_written) <= t * (1 + 1e-12))
    ++_written;
  return true;
}

double LogTimeOutputs::progress(double t) const
{
  return t < _end_time ? std::log(t / _first_time) / std::log(_end_time / _first_time) : 1.0;
}

void LogTimeOutputs::save(nlohmann::json& scene) const
{
  scene["first_time"] = _first_time;
  scene["outputs_written"] = _written;
}

TransientRecorder::TransientRecorder(Run& run, ResultsWriter& results,
                                     TransientProblem& transient, FieldSet& fields,
                                     ProgressLine& progress, int outputs, PathState start)
    : _run(run), _results(results), _transient(transient), _fields(fields), _progress(progress),
      _start(std::move(start)), _outputs(outputs, transient.end_time(), _start.scene),
      _checkpoints(run.checkpoints()),
      _newton_iterations(_start.scene.value("newton_iterations", 0)),
      _linear_iterations(_start.scene.value("linear_iterations", 0))
{
}

void TransientRecorder::run(const std::function<Measured(const TransientStep&)>& measure)
{
  const int steps = _transient.run([&](const TransientStep& s) { record(s, measure(s)); },
                                   _start.step > 0 ? &_start : nullptr);
  _run.summary["steps"] = steps;
}

void TransientRecorder::record(const TransientStep& s, const Measured& m)
{
  _newton_iterations += s.step.newton.iterations;
  _linear_iterations += s.step.newton.linear_iterations;
  nlohmann::json row = s.columns();
  row.update(m.columns);
  row.update(m.quantities);
  _results.append_step(row);
  if (_outputs.due(s.step.step, s.time))
    _results.write_fields(s.time, _fields.update());
  _run.summary.update(m.quantities);
  _run.summary.update({{"time", s.time},
                       {"newton_iterations", _newton_iterations},
                       {"linear_iterations", _linear_iterations}});
  _progress.print(s.step, s.time, _outputs.progress(s.time));
  PathState state;
  _transient.save(state);
  state.scene = {{"newton_iterations", _newton_iterations},
                 {"linear_iterations", _linear_iterations}};
  _outputs.save(state.scene);
  _checkpoints(s.step, state);
}

} // namespace gelx
