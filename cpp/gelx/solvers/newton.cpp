#include <gelx/solvers/newton.h>
#include <gelx/systems/mixed.h>
#include <gelx/common/petsc_utils.h>

#include <cmath>
#include <exception>

namespace gelx
{
namespace
{
using Progress = NewtonSolver::Progress;

struct Context
{
  Progress* progress;
  std::exception_ptr error;
};

Context& context_of(SNES snes)
{
  void* ctx = nullptr;
  SNESGetFunction(snes, nullptr, nullptr, &ctx);
  return *static_cast<Context*>(ctx);
}

PetscErrorCode form_residual(SNES snes, Vec x, Vec r, void* ctx)
{
  auto& c = *static_cast<Context*>(ctx);
  return guarded_callback(c.error,
                 [&]
                 {
                   c.progress->system->set_state(x);
                   if (!c.progress->system->admissible())
                     GELX_PETSC(SNESSetFunctionDomainError(snes)); // PETSc sets r to Inf
                   else
                     c.progress->system->residual(r);
                 });
}

PetscErrorCode form_tangent(SNES, Vec x, Mat, Mat P, void* ctx)
{
  auto& c = *static_cast<Context*>(ctx);
  return guarded_callback(c.error,
                 [&]
                 {
                   c.progress->system->set_state(x);
                   c.progress->system->tangent(P);
                 });
}

/// SNESSetUpdate: called at the start of every Newton iteration, at the accepted iterate.
PetscErrorCode commit_iterate(SNES snes, PetscInt)
{
  auto& c = context_of(snes);
  return guarded_callback(c.error, [&] { c.progress->system->commit(); });
}

/// Line-search pre-check: scale the step -Y by the system's factor (NonlinearSystem::
/// step_factor), then halve it until X - Y is admissible (see the class comment).
PetscErrorCode admissible_step(SNESLineSearch, Vec X, Vec Y, PetscBool* changed, void* ctx)
{
  auto& c = *static_cast<Context*>(ctx);
  return guarded_callback(c.error,
                 [&]
                 {
                   Progress& p = *c.progress;
                   const double factor = p.system->step_factor(X, Y);
                   *changed = factor != 1.0 ? PETSC_TRUE : PETSC_FALSE;
                   if (*changed)
                     GELX_PETSC(VecScale(Y, factor));
                   for (int k = 0; k < p.admissible_halvings; ++k)
                   {
                     GELX_PETSC(VecWAXPY(p.work, -1.0, Y, X));
                     p.system->set_state(p.work);
                     if (p.system->admissible())
                       break;
                     GELX_PETSC(VecScale(Y, 0.5));
                     *changed = PETSC_TRUE;
                     ++p.report.backtracks;
                   }
                   GELX_PETSC(VecNorm(Y, NORM_2, &p.step_norm));
                 });
}

/// Line-search post-check: count a reduction of the step by the line search itself (those
/// that backtrack hand over Y scaled by their step length), then let the system project the
/// new iterate W (NonlinearSystem::project).
PetscErrorCode count_reduction(SNESLineSearch, Vec, Vec Y, Vec W, PetscBool* changed_y,
                               PetscBool* changed_w, void* ctx)
{
  auto& c = *static_cast<Context*>(ctx);
  return guarded_callback(c.error,
                 [&]
                 {
                   *changed_y = *changed_w = PETSC_FALSE;
                   PetscReal norm;
                   GELX_PETSC(VecNorm(Y, NORM_2, &norm));
                   if (norm < (1 - 1e-12) * c.progress->step_norm)
                     ++c.progress->report.backtracks;
                   if (c.progress->system->project(W))
                     *changed_w = PETSC_TRUE;
                 });
}

/// The system in its predictor form for a scope (NonlinearSystem::set_predicting).
class PredictorForm
{
public:
  explicit PredictorForm(NonlinearSystem& system) : _system(system)
  {
    _system.set_predicting(true);
  }
  ~PredictorForm() { _system.set_predicting(false); }
  PredictorForm(const PredictorForm&) = delete;
  PredictorForm& operator=(const PredictorForm&) = delete;

private:
  NonlinearSystem& _system;
};

double distance(Vec a, Vec b, Vec work)
{
  GELX_PETSC(VecWAXPY(work, -1.0, b, a));
  PetscReal d;
  GELX_PETSC(VecNorm(work, NORM_2, &d));
  return d;
}

/// The convergence test of the class comment.
PetscErrorCode converged(SNES snes, PetscInt it, PetscReal, PetscReal, PetscReal fnorm,
                         SNESConvergedReason* reason, void* ctx)
{
  auto& c = *static_cast<Context*>(ctx);
  return guarded_callback(
      c.error,
      [&]
      {
        Progress& p = *c.progress;
        NewtonReport& r = p.report;
        Vec x;
        GELX_PETSC(SNESGetSolution(snes, &x));
        PetscReal rtol, atol, stol;
        PetscInt max_it, max_funcs;
        GELX_PETSC(SNESGetTolerances(snes, &atol, &rtol, &stol, &max_it, &max_funcs));
        *reason = SNES_CONVERGED_ITERATING;
        if (it == 0 && !p.start_given)
          GELX_PETSC(VecCopy(x, p.x0));
        if (it == 0 && !p.predicted)
        {
          GELX_PETSC(VecCopy(p.x0, p.x_previous));
          r.residual0 = fnorm;
          r.residual_history = {fnorm};
        }
        else if (it > 0)
          r.residual_history.push_back(fnorm);
        else
          r.residual_history.back() = fnorm; // the predicted state's residual, evaluated anew
        r.iterations = it + (p.predicted ? 1 : 0);
        r.residual = fnorm;
        if (!std::isfinite(fnorm))
        {
          *reason = SNES_DIVERGED_FNORM_NAN;
          r.reason = "the residual is not finite";
          return;
        }
        const int k = r.iterations; // the iterate's index, the predictor counted
        const double step = k > 0 ? distance(x, p.x_previous, p.work) : 0.0;
        GELX_PETSC(VecCopy(x, p.x_previous));
        r.error_estimate = k > 0 ? step * fnorm / r.residual_history[k - 1] : 0.0;
        const bool residual_ok = fnorm <= std::max(atol, rtol * r.residual0);
        if (residual_ok
            && r.error_estimate
                   <= std::max(p.atol_increment, p.rtol_increment * distance(x, p.x0, p.work)))
        {
          *reason = SNES_CONVERGED_FNORM_RELATIVE;
          p.converged = true;
          r.reason = "residual and increment tolerances";
        }
        else if (k > 0 && !residual_ok)
        {
          PetscReal xnorm;
          GELX_PETSC(VecNorm(x, NORM_2, &xnorm));
          if (step <= stol * xnorm)
          {
            *reason = SNES_DIVERGED_LOCAL_MIN;
            r.reason = "stagnated: the step fell below stol |x| before |R| reached its tolerance";
          }
        }
        if (*reason == SNES_CONVERGED_ITERATING && k >= max_it)
        {
          *reason = SNES_DIVERGED_MAX_IT;
          r.reason = "no convergence in " + std::to_string(max_it) + " iterations";
        }
      });
}
} // namespace

NewtonSolver::NewtonSolver(MPI_Comm comm, const std::string& prefix)
    : _comm(comm), _prefix(prefix)
{
  set_default_option(prefix, "snes_rtol", "1e-10");
  set_default_option(prefix, "snes_atol", "1e-12");
  set_default_option(prefix, "snes_stol", "1e-14");
  set_default_option(prefix, "snes_max_it", "25");
  set_linear_solver_defaults(prefix);
  GELX_PETSC(SNESCreate(comm, &_snes));
  GELX_PETSC(SNESSetOptionsPrefix(_snes, prefix.c_str()));
  // 1e-8: the solution to about the digits the residual tolerance leaves (a residual reduced
  // by 1e-10 with a condition number ~1e2 leaves an error of ~1e-8 of the change)
  _progress.rtol_increment = real_option(prefix, "rtol_increment", 1e-8);
  _progress.atol_increment = real_option(prefix, "atol_increment", 1e-14);
  _progress.admissible_halvings = int_option(prefix, "admissible_halvings", 8);
}

NewtonSolver::~NewtonSolver()
{
  if (_snes)
  {
    void* ctx = nullptr;
    SNESGetFunction(_snes, nullptr, nullptr, &ctx);
    delete static_cast<Context*>(ctx);
  }
  SNESDestroy(&_snes);
  MatDestroy(&_A);
  for (Vec* v : {&_r, &_x, &_progress.x0, &_progress.x_previous, &_progress.work})
    VecDestroy(v);
}

void NewtonSolver::set_up(NonlinearSystem& system)
{
  _progress.system = &system;
  _A = system.create_matrix();
  _r = system.create_vector();
  _x = system.create_vector();
  for (Vec* v : {&_progress.x0, &_progress.x_previous, &_progress.work})
    *v = system.create_vector();
  auto* context = new Context{&_progress, nullptr};
  GELX_PETSC(SNESSetFunction(_snes, _r, form_residual, context));
  GELX_PETSC(SNESSetJacobian(_snes, _A, _A, form_tangent, context));
  GELX_PETSC(SNESSetUpdate(_snes, commit_iterate));
  system.configure(_snes);
  GELX_PETSC(SNESSetFromOptions(_snes));
  refuse_unread_options_of(_prefix);
  KSP ksp;
  GELX_PETSC(SNESGetKSP(_snes, &ksp));
  prepare_linear_solver(ksp, system);
  // After the type is set: creating a VI type installs its own convergence test
  GELX_PETSC(SNESSetConvergenceTest(_snes, converged, context, nullptr));
  PetscBool bounded;
  GELX_PETSC(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(_snes), &bounded,
                                       SNESVINEWTONRSLS, SNESVINEWTONSSLS, ""));
  _bounded = bounded;
  SNESLineSearch linesearch;
  GELX_PETSC(SNESGetLineSearch(_snes, &linesearch));
  GELX_PETSC(SNESLineSearchSetPreCheck(linesearch, admissible_step, context));
  GELX_PETSC(SNESLineSearchSetPostCheck(linesearch, count_reduction, context));
}

bool NewtonSolver::predict(NonlinearSystem& system)
{
  Progress& p = _progress;
  NewtonReport& r = p.report;
  const PredictorForm form(system);
  system.set_state(_x);
  GELX_PETSC(VecCopy(_x, p.x0));
  system.residual(_r);
  PetscReal r0, atol;
  GELX_PETSC(VecNorm(_r, NORM_2, &r0));
  GELX_PETSC(SNESGetTolerances(_snes, &atol, nullptr, nullptr, nullptr, nullptr));
  r.residual0 = r0;
  r.residual_history = {r0};
  if (!(r0 > atol)) // converged already, or not finite: SNES reports either
    return false;
  system.commit();
  system.tangent(_A);
  KSP ksp;
  GELX_PETSC(SNESGetKSP(_snes, &ksp));
  // A VI solver hands this KSP the tangent restricted to its inactive rows, and a PC keeps
  // the size of its first operator: before and after the full tangent, the KSP starts
  // afresh, as the VI's own does when its set changes
  const auto restart_bounded_ksp = [&]
  {
    if (!_bounded)
      return;
    GELX_PETSC(KSPReset(ksp));
    GELX_PETSC(KSPResetFromOptions(ksp));
  };
  restart_bounded_ksp();
  GELX_PETSC(KSPSetOperators(ksp, _A, _A));
  GELX_PETSC(KSPSolve(ksp, _r, p.work));
  KSPConvergedReason reason;
  GELX_PETSC(KSPGetConvergedReason(ksp, &reason));
  PetscInt its = 0;
  GELX_PETSC(KSPGetIterationNumber(ksp, &its));
  r.linear_iterations = its; // the predictor's solve is one of the step's (run_snes adds SNES')
  restart_bounded_ksp();
  if (reason < 0)
    return false; // SNES meets the same failure and reports it
  GELX_PETSC(VecScale(p.work, system.step_factor(p.x0, p.work)));
  for (int k = 0; k <= p.admissible_halvings; ++k, ++r.backtracks)
  {
    GELX_PETSC(VecWAXPY(p.x_previous, -1.0, p.work, p.x0));
    system.set_state(p.x_previous);
    if (system.admissible())
      break;
    GELX_PETSC(VecScale(p.work, 0.5));
  }
  GELX_PETSC(VecCopy(p.x_previous, _x));
  GELX_PETSC(VecCopy(p.x0, p.x_previous)); // the convergence test measures the step from it
  r.residual_history.push_back(r0); // replaced by the predicted state's residual
  return true;
}

void NewtonSolver::bind(NonlinearSystem& system)
{
  if (!_progress.system)
    set_up(system);
  else if (_progress.system != &system)
    throw std::logic_error("NewtonSolver '" + _prefix + "' serves one system");
}

void NewtonSolver::begin(NonlinearSystem& system)
{
  bind(system);
  _progress.report = NewtonReport{};
  _progress.converged = false;
  // SNES iterates on a vector of its own: its line searches evaluate trial states, which
  // set_state() copies into the system, and must not overwrite their base point
  GELX_PETSC(VecCopy(system.unknowns(), _x));
}

NewtonReport NewtonSolver::solve(NonlinearSystem& system)
{
  begin(system);
  _progress.predicted = _progress.start_given = predict(system);
  return run_snes(system);
}

NewtonReport NewtonSolver::correct(NonlinearSystem& system, Vec last_point)
{
  begin(system);
  GELX_PETSC(VecCopy(last_point, _progress.x0));
  _progress.predicted = false;
  _progress.start_given = true;
  return run_snes(system);
}

NewtonReport NewtonSolver::run_snes(NonlinearSystem& system)
{
  Context& context = context_of(_snes);
  solve_guarded(context.error, [&] { return SNESSolve(_snes, nullptr, _x); });
  system.set_state(_x);

  NewtonReport& report = _progress.report;
  PetscInt linear_iterations;
  GELX_PETSC(SNESGetLinearSolveIterations(_snes, &linear_iterations));
  report.linear_iterations += linear_iterations;
  SNESType snes_type;
  GELX_PETSC(SNESGetType(_snes, &snes_type));
  report.snes_type = snes_type;
  SNESConvergedReason reason;
  GELX_PETSC(SNESGetConvergedReason(_snes, &reason));
  report.converged = _progress.converged;
  if (report.converged)
    system.commit();
  else if (report.reason.empty())
  {
    report.reason = SNESConvergedReasons[reason];
    SNESLineSearch linesearch;
    SNESLineSearchReason failure;
    GELX_PETSC(SNESGetLineSearch(_snes, &linesearch));
    GELX_PETSC(SNESLineSearchGetReason(linesearch, &failure));
    if (failure == SNES_LINESEARCH_FAILED_DOMAIN || failure == SNES_LINESEARCH_FAILED_NANORINF)
      report.reason += ": a trial state was inadmissible";
  }
  return report;
}

} // namespace gelx
