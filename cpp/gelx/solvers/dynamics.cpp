#include <gelx/solvers/dynamics.h>
#include <gelx/systems/mixed.h>
#include <gelx/io/parameters.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/systems/problem.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/la/petsc.h>
#include <exception>
#include <petsc/private/tsimpl.h>
#include <sstream>

namespace gelx
{

double smooth_step(double t, double loading_time)
{
  const double s = std::clamp(t / loading_time, 0.0, 1.0);
  return s * s * s * (10 - 15 * s + 6 * s * s);
}

double smooth_step_derivative(double t, double loading_time, int order)
{
  const double s = t / loading_time;
  if (s <= 0 || s >= 1)
    return 0;
  if (order == 1)
    return 30 * s * s * (1 - s) * (1 - s) / loading_time;
  if (order == 2)
    return 60 * s * (1 - s) * (1 - 2 * s) / (loading_time * loading_time);
  throw std::invalid_argument("smooth_step_derivative: order 1 or 2");
}

nlohmann::json DynamicsSummary::to_json() const
{
  nlohmann::json j = {{"steps", steps},
                      {"rejected_steps", rejected_steps},
                      {"failed_solves", failed_solves},
                      {"time", time},
                      {"strain_energy", strain_energy},
                      {"kinetic_energy", kinetic_energy},
                      {"dissipated_energy", dissipated_energy},
                      {"dissipation_ratio", dissipation_ratio},
                      {"dissipation_bound", dissipation_bound},
                      {"kinetic_ratio", kinetic_ratio},
                      {"kinetic_bound", kinetic_bound},
                      {"quasi_static", quasi_static()},
                      {"verdict", quasi_static() ? "quasi-static" : "not quasi-static"}};
  if (!std::isnan(external_work))
    j.update({{"external_work", external_work}, {"balance_residual", balance_residual}});
  if (integrator.is_object())
    j.update(integrator);
  return j;
}

nlohmann::json DynamicsRecord::to_json() const
{
  nlohmann::json j = {{"step", step.step},
                      {"time", time},
                      {"amplitude", step.load},
                      {"dt", step.step_size},
                      {"strain_energy", strain_energy},
                      {"kinetic_energy", kinetic_energy},
                      {"dissipated_energy", dissipated_energy},
                      {"kinetic_ratio", kinetic_ratio()},
                      {"dissipation_ratio", dissipation_ratio()},
                      {"newton_iterations", step.newton.iterations},
                      {"rejected", step.cutbacks},
                      {"wall_time", step.wall_time}};
  if (!std::isnan(external_work))
    j.update({{"external_work", external_work}, {"balance_residual", balance_residual}});
  if (!std::isnan(stable_step))
    j["stable_step"] = stable_step;
  return j;
}

Mat assemble_system_mass(NonlinearSystem& system, const dolfinx::fem::Form<double>& mass_form,
                         const std::string& who)
{
  // Assembled in the problem's tangent pattern, so that its restriction has the system
  // tangent's pattern
  Mat mass = system.problem().create_matrix();
  GELX_PETSC(MatZeroEntries(mass));
  dolfinx::fem::assemble_matrix(dolfinx::la::petsc::Matrix::set_block_fn(mass, ADD_VALUES),
                                mass_form, {});
  GELX_PETSC(MatAssemblyBegin(mass, MAT_FINAL_ASSEMBLY));
  GELX_PETSC(MatAssemblyEnd(mass, MAT_FINAL_ASSEMBLY));
  Mat restricted;
  try
  {
    restricted = system.restrict_operator(mass);
  }
  catch (const std::invalid_argument& e)
  {
    MatDestroy(&mass);
    throw std::invalid_argument(who + ": " + e.what());
  }
  GELX_PETSC(MatDestroy(&mass));
  return restricted;
}

Mat without_prescribed_rows(const NonlinearSystem& system, Mat A, double scale)
{
  Mat B;
  GELX_PETSC(MatDuplicate(A, MAT_COPY_VALUES, &B));
  GELX_PETSC(MatScale(B, scale));
  GELX_PETSC(MatSetOption(B, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
  PetscInt first_row;
  GELX_PETSC(MatGetOwnershipRange(B, &first_row, nullptr));
  std::vector<PetscInt> rows = system.prescribed_rows();
  for (PetscInt& r : rows)
    r += first_row;
  GELX_PETSC(MatZeroRows(B, PetscInt(rows.size()), rows.data(), 0.0, nullptr, nullptr));
  return B;
}

double positive_option(const std::string& prefix, const std::string& name, double fallback,
                       bool zero_allowed)
{
  const double value = real_option(prefix, name, fallback);
  if (!(value > 0 || (zero_allowed && value == 0)))
    throw InputError("-" + prefix + name + " must be "
                     + (zero_allowed ? "non-negative" : "positive"));
  return value;
}

double quadratic_form(Mat A, Vec v, Vec work)
{
  GELX_PETSC(MatMult(A, v, work));
  PetscScalar value;
  GELX_PETSC(VecDot(v, work, &value));
  return value;
}

double stop_below_min_step(TS ts, double min_step)
{
  PetscReal t, t_previous;
  GELX_PETSC(TSGetTime(ts, &t));
  GELX_PETSC(TSGetPrevTime(ts, &t_previous));
  if (t - t_previous >= min_step)
    return 0;
  GELX_PETSC(TSSetConvergedReason(ts, TS_DIVERGED_STEP_REJECTED));
  return t - t_previous;
}

void set_time_stepping_defaults(const std::string& prefix, const std::string& type,
                                double loading_time, double hold_time, double first_step)
{
  const auto number = [](double v)
  {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
  };
  set_default_option(prefix, "ts_type", type);
  set_default_option(prefix, "ts_adapt_type", "basic");
  set_default_option(prefix, "ts_adapt_dt_max", number(loading_time / 10));
  set_default_option(prefix, "ts_dt", number(real_option(prefix, "dt", first_step)));
  set_default_option(prefix, "ts_max_time", number(loading_time + hold_time));
  set_default_option(prefix, "ts_exact_final_time", "matchstep");
  // A failed Newton solve is no failure of the run: TS retries with a smaller step
  set_default_option(prefix, "ts_max_snes_failures", "-1");
  set_default_option(prefix, "ts_max_reject", "20");
  set_default_option(prefix, "ts_max_steps", "100000");
  // Full Newton steps, few of them: where they fail, the smaller time step TS takes then is
  // the globalisation (its predictor starts closer), not a line search
  set_default_option(prefix, "snes_linesearch_type", "basic");
  set_default_option(prefix, "snes_max_it", "10");
  set_linear_solver_defaults(prefix);
}

namespace
{
PetscErrorCode line_search_succeeded(TSAdapt, TS ts, PetscReal, Vec, PetscBool* accept)
{
  SNES snes;
  PetscCall(TSGetSNES(ts, &snes));
  SNESLineSearch line_search;
  PetscCall(SNESGetLineSearch(snes, &line_search));
  SNESLineSearchReason line_search_reason;
  PetscCall(SNESLineSearchGetReason(line_search, &line_search_reason));
  SNESConvergedReason reason;
  PetscCall(SNESGetConvergedReason(snes, &reason));
  // Only that path: a solve that converged on its residual did no failed line search last
  // (the line search's reason may be a previous solve's when it converged at once)
  *accept = reason == SNES_CONVERGED_SNORM_RELATIVE
                    && line_search_reason != SNES_LINESEARCH_SUCCEEDED
                ? PETSC_FALSE
                : PETSC_TRUE;
  return 0;
}
} // namespace

void reject_failed_line_searches(TS ts)
{
  TSAdapt adapt;
  GELX_PETSC(TSGetAdapt(ts, &adapt));
  GELX_PETSC(TSAdaptSetCheckStage(adapt, line_search_succeeded));
}

StepRecord accepted_step(TS ts, int step, double amplitude, double dt, StepCounters& last)
{
  PetscInt snes_iterations, ksp_iterations, rejections;
  GELX_PETSC(TSGetSNESIterations(ts, &snes_iterations));
  GELX_PETSC(TSGetKSPIterations(ts, &ksp_iterations));
  GELX_PETSC(TSGetStepRejections(ts, &rejections));
  SNES snes;
  GELX_PETSC(TSGetSNES(ts, &snes));
  SNESConvergedReason reason;
  GELX_PETSC(SNESGetConvergedReason(snes, &reason));
  const double now = wall_clock();
  StepRecord record;
  record.step = step;
  record.load = amplitude;
  record.step_size = dt;
  record.newton.converged = reason > 0;
  record.newton.iterations = snes_iterations - last.snes_iterations;
  record.newton.linear_iterations = ksp_iterations - last.ksp_iterations;
  record.newton.reason = SNESConvergedReasons[reason];
  record.cutbacks = rejections - last.rejections;
  record.wall_time = now - last.wall_time;
  last = {int(snes_iterations), int(ksp_iterations), int(rejections), now};
  return record;
}

void throw_if_stopped_early(TS ts, double t, const std::string& what_ran,
                            double too_small_step, const std::string& prefix, double min_step,
                            const std::string& unit)
{
  TSConvergedReason reason;
  GELX_PETSC(TSGetConvergedReason(ts, &reason));
  PetscReal end_time;
  GELX_PETSC(TSGetMaxTime(ts, &end_time));
  // TS also stops "converged" at its step limit (-PREFIX_ts_max_steps): short of the end time
  if (reason >= 0 && t >= end_time * (1 - 1e-12))
    return;
  std::ostringstream what;
  what << what_ran << " stopped at t = " << t << " of " << end_time << ": "
       << TSConvergedReasons[reason];
  if (too_small_step > 0)
    what << " (a step of " << too_small_step << unit << ", below -" << prefix << "min_step "
         << min_step << unit << ": the path runs into states it cannot take)";
  throw ConvergenceError(what.str());
}

bool vectors_of_solution_size(TS ts, std::initializer_list<Vec> vectors)
{
  PetscInt n = 0;
  GELX_PETSC(VecGetLocalSize(ts->vec_sol, &n));
  for (Vec v : vectors)
  {
    PetscInt m = -1;
    if (!v || reinterpret_cast<PetscObject>(v)->classid != VEC_CLASSID
        || VecGetLocalSize(v, &m) != 0 || m != n)
      return false;
  }
  return true;
}

double wall_clock()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

namespace
{
DampedDynamics& dynamics_of(void* ctx) { return *static_cast<DampedDynamics*>(ctx); }

PetscErrorCode form_function(TS, PetscReal t, Vec u, Vec u_dot, Vec F, void* ctx)
{
  DampedDynamics& d = dynamics_of(ctx);
  return guarded_callback(d.callback_error, [&] { d.form_function(t, u, u_dot, F); });
}

PetscErrorCode form_jacobian(TS, PetscReal t, Vec u, Vec, PetscReal shift, Mat, Mat P,
                             void* ctx)
{
  DampedDynamics& d = dynamics_of(ctx);
  return guarded_callback(d.callback_error, [&] { d.form_jacobian(t, u, shift, P); });
}

/// PETSc 3.18's TSBDF state, the struct TS_BDF of src/ts/impls/bdf/bdf.c, which PETSc keeps
/// private (save_bdf_history says why gelx reads and writes it). Only the layout
/// is repeated here, none of PETSc's code. work[0] is the newest state, work[1..n] the
/// accepted ones before it at time[1..n]; k the order the next step uses.
struct BdfState
{
  PetscInt k, n;
  PetscReal time[6 + 2];
  Vec work[6 + 2];
  Vec tvwork[6 + 2];
  PetscReal shift;
  Vec vec_dot, vec_wrk, vec_lte;
  PetscBool transientvar;
  PetscInt order;
  TSStepStatus status;
};

/// TS's TSBDF state, after TSSetUp; throws unless its layout is PETSc 3.18's: its order is
/// TSBDFGetOrder's, k and n in range, and its vectors are vectors of the solution's size.
BdfState& bdf_state(TS ts)
{
  auto* state = static_cast<BdfState*>(ts->data);
  PetscInt order;
  GELX_PETSC(TSBDFGetOrder(ts, &order));
  const bool same = state->order == order && state->k >= 0 && state->k <= order
                    && state->n >= 0 && state->n <= 7 && !state->transientvar
                    && vectors_of_solution_size(ts, {state->work[0], state->work[1],
                                                     state->work[2], state->work[3],
                                                     state->work[4], state->work[5],
                                                     state->work[6], state->work[7]});
  if (!same)
    throw std::runtime_error("this PETSc's TSBDF keeps its state in another layout than "
                             "PETSc 3.18's: gelx cannot restart a BDF run");
  return *state;
}

bool is_bdf(TS ts)
{
  PetscBool bdf;
  GELX_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ts), TSBDF, &bdf));
  return bdf;
}

} // namespace

void keep_restored_start(TS ts, bool& resuming)
{
  if (resuming)
  {
    ts->steprestart = PETSC_FALSE;
    resuming = false;
  }
}

void save_ts_position(TS ts, PathState& state)
{
  PetscInt step;
  PetscReal t, t_previous, dt;
  GELX_PETSC(TSGetStepNumber(ts, &step));
  GELX_PETSC(TSGetTime(ts, &t));
  GELX_PETSC(TSGetPrevTime(ts, &t_previous));
  GELX_PETSC(TSGetTimeStep(ts, &dt));
  state.step = step;
  state.load = t;
  state.step_size = dt;
  state.driver["previous_time"] = t_previous;
}

void restore_ts_position(TS ts, const PathState& state)
{
  GELX_PETSC(TSSetTime(ts, state.load));
  GELX_PETSC(TSSetStepNumber(ts, state.step));
  GELX_PETSC(TSSetTimeStep(ts, state.step_size));
  ts->ptime_prev = state.driver.at("previous_time");
}

void save_bdf_history(TS ts, PathState& state)
{
  save_ts_position(ts, state);
  // Another TS type than bdf: a checkpoint of the state only, which restore_bdf_history
  // refuses (so that the scenes' checkpoints after every step never stop such a run)
  state.driver["restartable"] = is_bdf(ts);
  if (!is_bdf(ts))
    return;
  const BdfState& bdf = bdf_state(ts);
  for (PetscInt i = 0; i <= bdf.n; ++i)
    state.vectors["bdf_state_" + std::to_string(i)] = copy_of(bdf.work[i]);
  state.driver.update({{"bdf_order", bdf.k},
                       {"bdf_states", bdf.n},
                       {"bdf_times", std::vector<double>(bdf.time, bdf.time + bdf.n + 1)}});
}

void restore_bdf_history(TS ts, Vec x, const PathState& state)
{
  const char* prefix;
  GELX_PETSC(TSGetOptionsPrefix(ts, &prefix));
  if (!is_bdf(ts) || !state.driver.value("restartable", false))
    throw InputError(std::string("-") + (prefix ? prefix : "")
                     + "ts_type: only bdf runs restart");
  GELX_PETSC(TSSetSolution(ts, x));
  GELX_PETSC(TSSetUp(ts));
  BdfState& bdf = bdf_state(ts);
  bdf.k = state.driver.at("bdf_order");
  bdf.n = state.driver.at("bdf_states");
  const std::vector<double> times = state.driver.at("bdf_times");
  for (PetscInt i = 0; i <= bdf.n; ++i)
  {
    bdf.time[i] = times[i];
    GELX_PETSC(VecCopy(state.vectors.at("bdf_state_" + std::to_string(i)).get(), bdf.work[i]));
  }
  restore_ts_position(ts, state);
}

DampedDynamics::DampedDynamics(MPI_Comm comm, NonlinearSystem& system,
                               const dolfinx::fem::Form<double>& mass_form,
                               std::function<double()> strain_energy,
                               std::function<void(double)> apply_load, const std::string& prefix)
    : _comm(comm), _system(system), _strain_energy(std::move(strain_energy)),
      _apply_load(std::move(apply_load)), _prefix(prefix),
      _loading_time(positive_option(prefix, "loading_time", 1.0)),
      _hold_time(positive_option(prefix, "hold_time", 0.0, true)),
      _damping(positive_option(prefix, "damping", 1.0)),
      _dissipation_bound(positive_option(prefix, "dissipation_bound", 0.05)),
      _kinetic_bound(positive_option(prefix, "kinetic_bound", 0.05)),
      _min_step(positive_option(prefix, "min_step", 1e-12 * _loading_time))
{
  // M (for the energies), and c M_D: M with the prescribed rows zeroed (for F and J), both
  // on the system's unknowns, so that J = K + shift c M_D adds entry by entry
  _mass = assemble_system_mass(system, mass_form, "DampedDynamics");
  _damped = without_prescribed_rows(system, _mass, _damping);
  _jacobian = system.create_matrix();
  _velocity = system.create_vector();
  _work.reset(system.create_vector());

  // Defaults (the user's options win), then TS, SNES and KSP from the options database
  set_time_stepping_defaults(prefix, "bdf", _loading_time, _hold_time, _loading_time / 50);
  set_default_option(prefix, "ts_bdf_order", "2");

  GELX_PETSC(TSCreate(comm, &_ts));
  GELX_PETSC(TSSetOptionsPrefix(_ts, prefix.c_str()));
  GELX_PETSC(TSSetProblemType(_ts, TS_NONLINEAR));
  Vec r = system.create_vector();
  GELX_PETSC(TSSetIFunction(_ts, r, gelx::form_function, this));
  GELX_PETSC(VecDestroy(&r));
  GELX_PETSC(TSSetIJacobian(_ts, _jacobian, _jacobian, gelx::form_jacobian, this));
  GELX_PETSC(TSMonitorSet(_ts, monitor_accepted<DampedDynamics>, this, nullptr));
  GELX_PETSC(TSSetApplicationContext(_ts, this));
  GELX_PETSC(TSSetPostStep(_ts, post_step_check<DampedDynamics>));
  GELX_PETSC(TSSetPreStep(_ts, pre_step_hook<DampedDynamics>));
  GELX_PETSC(TSSetFromOptions(_ts));
  refuse_unread_options_of(prefix);
  reject_failed_line_searches(_ts);
  SNES snes;
  GELX_PETSC(TSGetSNES(_ts, &snes));
  KSP ksp;
  GELX_PETSC(SNESGetKSP(snes, &ksp));
  prepare_linear_solver(ksp, system);
  // A step TS cannot take (more than ts_max_reject rejections) ends TSSolve with a negative
  // converged reason, which run() reports as a ConvergenceError, instead of a PETSc error
  // whose traceback each rank prints (measured: the bistrip's pre-compressed strip)
  GELX_PETSC(TSSetErrorIfStepFails(_ts, PETSC_FALSE));
}

DampedDynamics::~DampedDynamics()
{
  TSDestroy(&_ts);
  MatDestroy(&_mass);
  MatDestroy(&_damped);
  MatDestroy(&_jacobian);
  VecDestroy(&_velocity);
}

void DampedDynamics::set_time(double t) { _apply_load(smooth_step(t, _loading_time)); }

void DampedDynamics::form_function(double t, Vec u, Vec u_dot, Vec F)
{
  set_time(t);
  _system.set_state(u);
  if (!_system.admissible())
  {
    SNES snes;
    GELX_PETSC(TSGetSNES(_ts, &snes));
    GELX_PETSC(SNESSetFunctionDomainError(snes)); // the stage fails; TS cuts the step
    return;
  }
  _system.residual(F);
  GELX_PETSC(MatMultAdd(_damped, u_dot, F, F));
}

void DampedDynamics::form_jacobian(double t, Vec u, double shift, Mat P)
{
  set_time(t);
  _system.set_state(u);
  _system.tangent(P);
  GELX_PETSC(MatAXPY(P, shift, _damped, SAME_NONZERO_PATTERN));
}

void DampedDynamics::velocity(double t, Vec u)
{
  // The derivative at t of the Lagrange polynomial through (t, u) and the accepted states
  // before it: sum_k L_k'(t) u_k
  std::vector<double> times{t};
  times.insert(times.end(), _history_time.begin(),
               _history_time.begin() + std::min<std::size_t>(2, _history_time.size()));
  std::vector<Vec> states{u};
  for (std::size_t k = 1; k < times.size(); ++k)
    states.push_back(_history[k - 1].get());
  GELX_PETSC(VecSet(_velocity, 0.0));
  for (std::size_t k = 0; k < times.size(); ++k)
  {
    double weight = 0;
    for (std::size_t j = 0; j < times.size(); ++j)
    {
      if (j == k)
        continue;
      double term = 1 / (times[k] - times[j]);
      for (std::size_t i = 0; i < times.size(); ++i)
        if (i != j && i != k)
          term *= (t - times[i]) / (times[k] - times[i]);
      weight += term;
    }
    GELX_PETSC(VecAXPY(_velocity, weight, states[k]));
  }
}

void DampedDynamics::check_step_size()
{
  if (const double step = stop_below_min_step(_ts, _min_step); step > 0)
    _too_small_step = step;
}

void DampedDynamics::pre_step() { keep_restored_start(_ts, _resuming); }

void DampedDynamics::save(PathState& state) const
{
  save_bdf_history(_ts, state);
  if (!state.driver["restartable"].get<bool>())
    return;
  for (std::size_t i = 0; i < _history.size(); ++i)
    state.vectors["velocity_state_" + std::to_string(i)] = copy_of(_history[i].get());
  state.driver.update({{"velocity_times", _history_time},
                       {"power", _power},
                       {"dissipated_energy", _summary.dissipated_energy},
                       {"kinetic_ratio", _summary.kinetic_ratio},
                       {"rejected_steps", _summary.rejected_steps}});
}

void DampedDynamics::accepted(int step, double t, Vec u)
{
  if (_skip_first_monitor)
  {
    // TSSolve's first call: the state the run resumes from, recorded already
    _skip_first_monitor = false;
    _counters.wall_time = wall_clock();
    return;
  }
  const bool first = _history.empty();
  if (!first)
  {
    set_time(t);
    _system.set_state(u);
    _system.commit();
    velocity(t, u);
    const double twice_kinetic = quadratic_form(_mass, _velocity, _work.get());
    // The power of the viscous forces the model applies (none in the prescribed rows), so
    // that the work of the loads is SE + ED
    const double power = quadratic_form(_damped, _velocity, _work.get());
    const double dt = t - _history_time.front();
    _summary.dissipated_energy += 0.5 * (_power + power) * dt;
    _power = power;

    DynamicsRecord record;
    record.step = accepted_step(_ts, step, smooth_step(t, _loading_time), dt, _counters);
    record.time = t;
    record.strain_energy = _strain_energy();
    record.kinetic_energy = 0.5 * twice_kinetic;
    record.dissipated_energy = _summary.dissipated_energy;

    _summary.steps = step;
    _summary.rejected_steps = _counters.rejections;
    PetscInt failed_solves;
    GELX_PETSC(TSGetSNESFailures(_ts, &failed_solves));
    _summary.failed_solves = failed_solves;
    _summary.time = t;
    _summary.strain_energy = record.strain_energy;
    _summary.kinetic_energy = record.kinetic_energy;
    _summary.dissipation_ratio = record.dissipation_ratio();
    // Over the whole run, as ABAQUS' ALLKE / ALLSE: at the smooth step's start both energies
    // grow from zero, but their ratio stays bounded (SE ~ A^2, KE ~ A'^2, A'/A = 3/t)
    if (record.strain_energy > 0)
      _summary.kinetic_ratio = std::max(_summary.kinetic_ratio, record.kinetic_ratio());
    remember(t, u);
    // after remember(): a checkpoint the observers write holds this state in the history
    for (const auto& observe : *_observers)
      observe(record);
    return;
  }
  _counters.wall_time = wall_clock();
  remember(t, u);
}

void DampedDynamics::remember(double t, Vec u)
{
  // Keep the last three accepted states, newest first (the oldest vector is reused)
  OwnedVec copy;
  if (_history.size() == 3)
  {
    copy = std::move(_history.back());
    _history.pop_back();
    _history_time.pop_back();
  }
  else
    copy.reset(_system.create_vector());
  GELX_PETSC(VecCopy(u, copy.get()));
  _history.insert(_history.begin(), std::move(copy));
  _history_time.insert(_history_time.begin(), t);
}

DynamicsSummary DampedDynamics::run(const std::vector<DynamicsObserver>& observers,
                                    const PathState* resume)
{
  _observers = &observers;
  _summary = DynamicsSummary{};
  _summary.dissipation_bound = _dissipation_bound;
  _summary.kinetic_bound = _kinetic_bound;
  _history.clear();
  _history_time.clear();
  _power = 0; // the run starts at rest
  _counters = StepCounters{};

  OwnedVec x(_system.create_vector());
  GELX_PETSC(VecCopy(_system.unknowns(), x.get()));
  _skip_first_monitor = _resuming = false;
  if (resume)
  {
    restore_bdf_history(_ts, x.get(), *resume);
    _history_time = resume->driver.at("velocity_times").get<std::vector<double>>();
    for (std::size_t i = 0; i < _history_time.size(); ++i)
      _history.push_back(copy_of(resume->vectors.at("velocity_state_" + std::to_string(i)).get()));
    _power = resume->driver.at("power");
    _summary.dissipated_energy = resume->driver.at("dissipated_energy");
    _summary.kinetic_ratio = resume->driver.at("kinetic_ratio");
    _summary.rejected_steps = resume->driver.at("rejected_steps");
    _skip_first_monitor = _resuming = true;
  }
  else
  {
    GELX_PETSC(TSSetTime(_ts, 0.0));
    GELX_PETSC(TSSetStepNumber(_ts, 0));
  }
  _too_small_step = 0;
  solve_guarded(callback_error, [&] { return TSSolve(_ts, x.get()); });
  _observers = nullptr;
  // The last accepted state (TS leaves x there; a failed step is rolled back)
  const double t = _history_time.empty() ? 0.0 : _history_time.front();
  set_time(t);
  _system.set_state(_history.empty() ? x.get() : _history.front().get());
  throw_if_stopped_early(_ts, t, "damped dynamics", _too_small_step, _prefix, _min_step, " s");
  return _summary;
}

} // namespace gelx
