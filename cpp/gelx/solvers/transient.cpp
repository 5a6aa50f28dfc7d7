#include <gelx/solvers/transient.h>

#include <gelx/common/petsc_utils.h>
#include <gelx/io/parameters.h>
#include <gelx/systems/mixed.h>

#include <algorithm>
#include <petsc/private/tsimpl.h>

namespace gelx
{
namespace
{
TransientProblem& transient_of(void* ctx) { return *static_cast<TransientProblem*>(ctx); }

PetscErrorCode form_function(TS, PetscReal t, Vec w, Vec w_dot, Vec F, void* ctx)
{
  TransientProblem& p = transient_of(ctx);
  return guarded_callback(p.callback_error, [&] { p.form_function(t, w, w_dot, F); });
}

PetscErrorCode form_jacobian(TS, PetscReal t, Vec w, Vec w_dot, PetscReal shift, Mat,
                             Mat P, void* ctx)
{
  TransientProblem& p = transient_of(ctx);
  return guarded_callback(p.callback_error, [&] { p.form_jacobian(t, w, w_dot, shift, P); });
}

PetscErrorCode correction_test(SNES snes, PetscInt iteration, PetscReal x_norm,
                               PetscReal dx_norm, PetscReal f_norm,
                               SNESConvergedReason* reason, void* ctx)
{
  // PETSc's tests first: a residual that is not finite, at its absolute tolerance, or
  // iterations run out
  PetscCall(SNESConvergedDefault(snes, iteration, x_norm, dx_norm, f_norm, reason, nullptr));
  TransientProblem& p = transient_of(ctx);
  return guarded_callback(p.callback_error,
                          [&] { p.test_newton_correction(snes, iteration, reason); });
}

} // namespace

TransientProblem::TransientProblem(MPI_Comm comm, NonlinearSystem& system,
                                   std::shared_ptr<dolfinx::fem::Function<double>> rate,
                                   dolfinx::fem::Constant<double>& shift,
                                   std::function<void(double)> set_time, double end_time,
                                   const std::string& prefix)
    : _system(system), _rate(std::move(rate)), _shift(shift),
      _set_time(std::move(set_time)), _prefix(prefix), _end_time(end_time),
      _min_step(positive_option(prefix, "min_step", 1e-14 * end_time))
{
  set_time_stepping_defaults(prefix, "bdf", end_time, 0, 1e-6 * end_time);
  set_default_option(prefix, "ts_bdf_order", "2");
  // Newton's tolerance a fraction of the step's error, not of machine precision: TSBDF's
  // predictor (the extrapolated history) is off by about the local error the adaptivity keeps
  // below ts_rtol, so a residual 1e-3 of the predictor's leaves an error 1e-3 of that (CVODE
  // asks 0.1 of it). One Newton iteration a step mostly reaches it where PETSc's 1e-8 took
  // two; the swelling cube's uptake moves by 8e-7 of itself, a thousandth of BDF2's error at
  // rtol 1e-4 (demos/swelling/README, Speed)
  set_default_option(prefix, "snes_rtol", "1e-3");
  _jacobian = system.create_matrix();
  _problem_rate = system.problem().create_vector();
  const std::string newton_test
      = choice_option(prefix, "newton_test", "residual", {"residual", "correction"});
  GELX_PETSC(TSCreate(comm, &_ts));
  GELX_PETSC(TSSetOptionsPrefix(_ts, prefix.c_str()));
  GELX_PETSC(TSSetProblemType(_ts, TS_NONLINEAR));
  Vec r = system.create_vector();
  GELX_PETSC(TSSetIFunction(_ts, r, gelx::form_function, this));
  GELX_PETSC(VecDestroy(&r));
  GELX_PETSC(TSSetIJacobian(_ts, _jacobian, _jacobian, gelx::form_jacobian, this));
  GELX_PETSC(TSMonitorSet(_ts, monitor_accepted<TransientProblem>, this, nullptr));
  GELX_PETSC(TSSetApplicationContext(_ts, this));
  GELX_PETSC(TSSetPostStep(_ts, post_step_check<TransientProblem>));
  GELX_PETSC(TSSetPreStep(_ts, pre_step_hook<TransientProblem>));
  GELX_PETSC(TSSetFromOptions(_ts));
  refuse_unread_options_of(prefix);
  reject_failed_line_searches(_ts);
  GELX_PETSC(TSSetErrorIfStepFails(_ts, PETSC_FALSE));
  SNES snes;
  GELX_PETSC(TSGetSNES(_ts, &snes));
  KSP ksp;
  GELX_PETSC(SNESGetKSP(snes, &ksp));
  prepare_linear_solver(ksp, system);
  if (newton_test == "correction")
  {
    _previous_iterate = system.create_vector();
    GELX_PETSC(SNESSetConvergenceTest(snes, correction_test, this, nullptr));
  }
}

TransientProblem::~TransientProblem()
{
  TSDestroy(&_ts);
  MatDestroy(&_jacobian);
  VecDestroy(&_problem_rate);
  VecDestroy(&_previous_iterate);
}

void TransientProblem::set_state(double t, Vec x, Vec x_dot)
{
  _set_time(t);
  _system.set_state(x);
  // The rate's owned values: TS's x' prolonged, w' = P x' (the constraints' g is constant;
  // Dirichlet dofs are unknowns of x with their own rows), its ghosts from their owners
  _system.prolong_vector(x_dot, _problem_rate);
  const PetscScalar* values;
  PetscInt n;
  GELX_PETSC(VecGetLocalSize(_problem_rate, &n));
  GELX_PETSC(VecGetArrayRead(_problem_rate, &values));
  std::copy_n(values, n, _rate->x()->mutable_array().begin());
  GELX_PETSC(VecRestoreArrayRead(_problem_rate, &values));
  _rate->x()->scatter_fwd();
}

void TransientProblem::form_function(double t, Vec w, Vec w_dot, Vec F)
{
  set_state(t, w, w_dot);
  if (!_system.admissible())
  {
    SNES snes;
    GELX_PETSC(TSGetSNES(_ts, &snes));
    GELX_PETSC(SNESSetFunctionDomainError(snes)); // the stage fails; TS cuts the step
    return;
  }
  _system.residual(F);
}

void TransientProblem::form_jacobian(double t, Vec w, Vec w_dot, double shift, Mat P)
{
  set_state(t, w, w_dot);
  _shift.value = {shift};
  _system.tangent(P);
}

void TransientProblem::test_newton_correction(SNES snes, int iteration,
                                              SNESConvergedReason* reason)
{
  Vec x;
  GELX_PETSC(SNESGetSolution(snes, &x));
  if (iteration == 0)
  {
    GELX_PETSC(VecCopy(x, _previous_iterate));
    return; // PETSc's test stands: at the absolute tolerance already, or iterating
  }
  // Newton's tolerance relative to the first residual no longer applies: the correction's
  // size against TS's error tolerance does
  if (*reason == SNES_CONVERGED_FNORM_RELATIVE || *reason == SNES_CONVERGED_SNORM_RELATIVE)
    *reason = SNES_CONVERGED_ITERATING;
  // The largest entry, not the RMS norm of TS's error test: the RMS spreads an error at the
  // swelling front over the unknowns far from it, and BDF4 on the layer's large jump then
  // took 116 steps against Newton-to-1e-3's 66 (its history's error shrank the steps); with
  // the largest entry, 67
  PetscReal correction, absolute, relative;
  GELX_PETSC(TSErrorWeightedNorm(_ts, x, _previous_iterate, NORM_INFINITY, &correction,
                                 &absolute, &relative));
  GELX_PETSC(VecCopy(x, _previous_iterate));
  if (iteration > 1)
    _correction_rate = std::max(0.2 * _correction_rate, correction / _last_correction);
  _last_correction = correction;
  if (*reason == SNES_CONVERGED_ITERATING && correction * std::min(1.0, _correction_rate) <= 0.1)
    *reason = SNES_CONVERGED_SNORM_RELATIVE;
}

void TransientProblem::accepted(int step, double t, Vec w)
{
  if (_skip_first_monitor)
  {
    // TSSolve's first call: the state it starts from (a resumed run's, recorded already)
    _skip_first_monitor = false;
    _counters.wall_time = wall_clock();
    return;
  }
  PetscReal t_previous;
  GELX_PETSC(TSGetPrevTime(_ts, &t_previous));
  _set_time(t);
  _system.set_state(w);
  TransientStep record;
  record.time = t;
  record.step = accepted_step(_ts, step, t, t - t_previous, _counters);
  (*_observe)(record);
}

void TransientProblem::check_step_size()
{
  if (const double step = stop_below_min_step(_ts, _min_step); step > 0)
    _too_small_step = step;
}

void TransientProblem::pre_step() { keep_restored_start(_ts, _resuming); }

void TransientProblem::save(PathState& state) const
{
  save_bdf_history(_ts, state);
  state.driver["newton_correction_rate"] = _correction_rate; // the correction test's memory
}

int TransientProblem::run(const std::function<void(const TransientStep&)>& observe,
                          const PathState* resume)
{
  _observe = &observe;
  _counters = StepCounters{};
  OwnedVec w(_system.create_vector());
  GELX_PETSC(VecCopy(_system.unknowns(), w.get()));
  _skip_first_monitor = true;
  _resuming = resume != nullptr;
  _correction_rate = resume ? resume->driver.value("newton_correction_rate", 1.0) : 1.0;
  if (resume)
    restore_bdf_history(_ts, w.get(), *resume);
  else
  {
    GELX_PETSC(TSSetTime(_ts, 0.0));
    GELX_PETSC(TSSetStepNumber(_ts, 0));
  }
  _too_small_step = 0;
  solve_guarded(callback_error, [&] { return TSSolve(_ts, w.get()); });
  _observe = nullptr;
  PetscReal t;
  PetscInt steps;
  GELX_PETSC(TSGetTime(_ts, &t));
  GELX_PETSC(TSGetStepNumber(_ts, &steps));
  _system.set_state(w.get());
  throw_if_stopped_early(_ts, t, "the transient", _too_small_step, _prefix, _min_step, " s");
  return int(steps);
}

} // namespace gelx
