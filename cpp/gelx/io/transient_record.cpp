#include "transient_record.h"

namespace gelx
{

TransientRecorder::TransientRecorder(Run& run, ResultsWriter& results,
                                     const TransientProblem& transient, FieldSet& fields,
                                     ProgressLine& progress, int outputs, double end_time,
                                     const PathState& start)
    : _run(run), _results(results), _transient(transient), _fields(fields), _progress(progress),
      _outputs(outputs, end_time, start.scene), _checkpoints(run.checkpoints()),
      _newton_iterations(start.scene.value("newton_iterations", 0)),
      _linear_iterations(start.scene.value("linear_iterations", 0))
{
}

void TransientRecorder::operator()(const TransientStep& s, const nlohmann::json& quantities,
                               const nlohmann::json& columns)
{
  _newton_iterations += s.step.newton.iterations;
  _linear_iterations += s.step.newton.linear_iterations;
  nlohmann::json row = s.columns();
  row.update(columns);
  row.update(quantities);
  _results.append_step(row);
  if (_outputs.due(s.step.step, s.time))
    _results.write_fields(s.time, _fields.update());
  _run.summary.update(quantities);
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
