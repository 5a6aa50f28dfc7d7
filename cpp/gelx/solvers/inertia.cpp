#include <gelx/solvers/inertia.h>
#include <gelx/solvers/central_difference.h>
#include <gelx/systems/mixed.h>
#include <gelx/io/parameters.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/systems/problem.h>

#include <cmath>
#include <petsc/private/tsimpl.h>
#include <sstream>

namespace gelx
{
namespace
{
/// PETSc 3.18's TSALPHA2 state, the struct TS_Alpha of src/ts/impls/implicit/alpha/alpha2.c,
/// which PETSc keeps private (InertialDynamics' class comment says why gelx reads and writes
/// it). Only the layout is repeated here, none of PETSc's code.
struct Alpha2State
{
  PetscReal stage_time, shift_V, shift_A, scale_F;
  Vec X0, Xa, X1;
  Vec V0, Va, V1;
  Vec A0, Aa, A1;
  Vec vec_dot;
  PetscReal Alpha_m, Alpha_f, Gamma, Beta;
  PetscInt order;
  Vec vec_sol_prev, vec_dot_prev;
  Vec vec_lte_work[2];
  TSStepStatus status;
};

/// TS's TSALPHA2 state, after TSSetUp; throws unless its layout is PETSc 3.18's: its
/// parameters equal TSAlpha2GetParams' and its vectors are vectors of the solution's size.
Alpha2State& alpha2_state(TS ts)
{
  auto* state = static_cast<Alpha2State*>(ts->data);
  PetscReal alpha_m, alpha_f, gamma, beta;
  GELX_PETSC(TSAlpha2GetParams(ts, &alpha_m, &alpha_f, &gamma, &beta));
  const bool same = state->Alpha_m == alpha_m && state->Alpha_f == alpha_f
                    && state->Gamma == gamma && state->Beta == beta
                    && vectors_of_solution_size(ts, {state->X0, state->X1, state->V0,
                                                     state->V1, state->A0, state->A1});
  if (!same)
    throw std::runtime_error("this PETSc's TSALPHA2 keeps its state in another layout than "
                             "PETSc 3.18's: gelx cannot restart or read its acceleration");
  return *state;
}

InertialDynamics& dynamics_of(void* ctx) { return *static_cast<InertialDynamics*>(ctx); }

PetscErrorCode form_function(TS, PetscReal t, Vec u, Vec v, Vec a, Vec F, void* ctx)
{
  InertialDynamics& d = dynamics_of(ctx);
  return guarded_callback(d.callback_error, [&] { d.form_function(t, u, v, a, F); });
}

PetscErrorCode form_jacobian(TS, PetscReal t, Vec u, Vec, Vec, PetscReal shift_v,
                             PetscReal shift_a, Mat, Mat P, void* ctx)
{
  InertialDynamics& d = dynamics_of(ctx);
  return guarded_callback(d.callback_error, [&] { d.form_jacobian(t, u, shift_v, shift_a, P); });
}

PetscErrorCode pre_stage(TS ts, PetscReal)
{
  void* ctx;
  PetscCall(TSGetApplicationContext(ts, &ctx));
  InertialDynamics& d = dynamics_of(ctx);
  return guarded_callback(d.callback_error, [&] { d.pre_stage(); });
}

PetscErrorCode prescribe(InertialDynamics& d, double t, Vec u, Vec v, Vec a)
{
  return guarded_callback(d.callback_error, [&] { d.prescribe(t, u, v, a); });
}

} // namespace

InertialDynamics::InertialDynamics(MPI_Comm comm, NonlinearSystem& system,
                                   const dolfinx::fem::Form<double>& mass_form,
                                   std::function<double()> strain_energy,
                                   std::function<void(double)> apply_load,
                                   const std::string& prefix)
    : _comm(comm), _system(system), _strain_energy(std::move(strain_energy)),
      _apply_load(std::move(apply_load)), _prefix(prefix),
      _loading_time(positive_option(prefix, "loading_time", 1.0)),
      _hold_time(positive_option(prefix, "hold_time", 0.0, true)),
      _kinetic_bound(positive_option(prefix, "kinetic_bound", 0.05)),
      _min_step(positive_option(prefix, "min_step", 1e-12 * _loading_time)),
      _has_reactions(system.unknowns() == system.problem().unknowns())
{
  const double a = positive_option(prefix, "rayleigh_mass", 0.0, true);
  const double b = positive_option(prefix, "rayleigh_stiffness", 0.0, true);
  _rayleigh_mass = a;
  // The scheme decides the mass: read TS's type before TS exists
  register_central_difference();
  _explicit = string_option(prefix, "ts_type", "alpha2") == TSCENTRALDIFFERENCE;
  const std::string mass_kind = choice_option(prefix, "mass", _explicit ? "lumped" : "consistent",
                                              {"consistent", "lumped"});
  if (_explicit && mass_kind != "lumped")
    throw InputError("-" + prefix + "mass consistent: explicit central differences need the "
                     "lumped mass (a consistent one would need a solve per step)");
  if (_explicit && b > 0)
    throw InputError("-" + prefix + "rayleigh_stiffness: explicit central differences take "
                     "mass-proportional damping only (b K would need a solve per step)");
  _prescribed = system.prescribed_rows();
  _mass = assemble_system_mass(system, mass_form, "InertialDynamics");
  if (mass_kind == "lumped")
  {
    Mat lumped = lumped_mass(_mass, _prescribed, string_option(prefix, "lumping", "auto"),
                             _lumping);
    GELX_PETSC(MatDestroy(&_mass));
    _mass = lumped;
  }
  _mass_D = without_prescribed_rows(system, _mass);
  PetscInt first_row;
  GELX_PETSC(MatGetOwnershipRange(_mass, &first_row, nullptr));
  if (a > 0 || b > 0)
  {
    // C = a M + b K0, K0 the tangent at the initial state with the prescribed rows and
    // columns zeroed (the tangent's identity there is no stiffness): a symmetric C whose
    // power v^T C v is the dissipation of the forces C v it applies
    GELX_PETSC(MatDuplicate(_mass, MAT_COPY_VALUES, &_damping));
    GELX_PETSC(MatScale(_damping, a));
    if (b > 0)
    {
      Mat K0 = system.create_matrix();
      _apply_load(0.0);
      system.unknowns_changed();
      system.tangent(K0);
      std::vector<PetscInt> rows = _prescribed;
      for (PetscInt& r : rows)
        r += first_row;
      GELX_PETSC(MatZeroRowsColumns(K0, PetscInt(rows.size()), rows.data(), 0.0, nullptr,
                                    nullptr));
      // (K0's pattern holds the lumped mass's diagonal, not the other way round)
      GELX_PETSC(MatAXPY(_damping, b, K0, DIFFERENT_NONZERO_PATTERN));
      GELX_PETSC(MatDestroy(&K0));
    }
    _damping_D = without_prescribed_rows(system, _damping);
  }
  _jacobian = system.create_matrix();
  _initial_velocity.reset(system.create_vector());
  GELX_PETSC(VecSet(_initial_velocity.get(), 0.0));
  _work.reset(system.create_vector());
  _mean_velocity.reset(system.create_vector());
  _reaction.reset(system.create_vector());
  _previous_reaction.reset(system.create_vector());
  _du.reset(system.create_vector());

  if (_explicit)
  {
    _step_fraction = positive_option(prefix, "stable_step_fraction", 0.9);
    _stable_step_every = int_option(prefix, "stable_step_every", 100);
    if (_step_fraction > 1 || _stable_step_every < 1)
      throw InputError("-" + prefix + "stable_step_fraction must be in (0, 1] and -" + prefix
                       + "stable_step_every at least 1");
    _fixed_step = positive_option(prefix, "dt", 0.0, true);
    measure_prescribed_motion();
    Vec m;
    GELX_PETSC(MatCreateVecs(_mass, &m, nullptr));
    GELX_PETSC(MatGetDiagonal(_mass, m));
    _lumped_mass.reset(m);
    if (const double dt = positive_option(prefix, "mass_scaling_step", 0.0, true); dt > 0)
    {
      Mat K = system.create_matrix();
      system.tangent(K);
      _added_mass = scale_mass_for_step(K, _lumped_mass.get(), _prescribed, dt, _step_fraction);
      GELX_PETSC(MatDestroy(&K));
    }
    _mass_diagonal.reset(system.create_vector());
    _damping_diagonal.reset(system.create_vector());
    set_lumped_mass(_lumped_mass.get());
  }
  if (!_lumping.empty())
  {
    Vec ones = system.create_vector();
    GELX_PETSC(VecSet(ones, 1.0));
    _total_mass = quadratic_form(_mass_D, ones, _work.get()) - _added_mass;
    GELX_PETSC(VecDestroy(&ones));
  }

  // Defaults (the user's options win), then TS, SNES and KSP from the options database
  set_time_stepping_defaults(prefix, "alpha2", _loading_time, _hold_time, _loading_time / 100);

  GELX_PETSC(TSCreate(comm, &_ts));
  GELX_PETSC(TSSetOptionsPrefix(_ts, prefix.c_str()));
  GELX_PETSC(TSSetProblemType(_ts, TS_NONLINEAR));
  GELX_PETSC(TSSetType(_ts, TSALPHA2));
  Vec r = system.create_vector();
  GELX_PETSC(TSSetI2Function(_ts, r, gelx::form_function, this));
  GELX_PETSC(VecDestroy(&r));
  GELX_PETSC(TSSetI2Jacobian(_ts, _jacobian, _jacobian, gelx::form_jacobian, this));
  GELX_PETSC(TSMonitorSet(_ts, monitor_accepted<InertialDynamics>, this, nullptr));
  GELX_PETSC(TSSetApplicationContext(_ts, this));
  GELX_PETSC(TSSetPreStep(_ts, pre_step_hook<InertialDynamics>));
  GELX_PETSC(TSSetPreStage(_ts, gelx::pre_stage));
  GELX_PETSC(TSSetPostStep(_ts, post_step_check<InertialDynamics>));
  GELX_PETSC(TSSetFromOptions(_ts));
  refuse_unread_options_of(prefix);
  reject_failed_line_searches(_ts);
  PetscBool alpha2;
  GELX_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(_ts), TSALPHA2, &alpha2));
  if (!alpha2 && !_explicit)
    throw InputError("-" + prefix + "ts_type must be alpha2 or " + TSCENTRALDIFFERENCE
                     + " (the second-order integrators whose state gelx saves)");
  if (_explicit)
    central_difference_set_mass(_ts, _mass_diagonal.get(), _rayleigh_mass > 0
                                                               ? _damping_diagonal.get()
                                                               : nullptr,
                                [this](double t, Vec u, Vec v, Vec a)
                                { return gelx::prescribe(*this, t, u, v, a); });
  TSAdapt adapt;
  GELX_PETSC(TSGetAdapt(_ts, &adapt));
  PetscBool fixed;
  GELX_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(adapt), TSADAPTNONE, &fixed));
  if (fixed && !_explicit)
    GELX_PETSC(TSGetTimeStep(_ts, &_fixed_step));
  SNES snes;
  GELX_PETSC(TSGetSNES(_ts, &snes));
  KSP ksp;
  GELX_PETSC(SNESGetKSP(snes, &ksp));
  prepare_linear_solver(ksp, system);
  // A step TS cannot take ends TSSolve with a negative reason, reported by run()
  GELX_PETSC(TSSetErrorIfStepFails(_ts, PETSC_FALSE));
}

InertialDynamics::~InertialDynamics()
{
  TSDestroy(&_ts);
  for (Mat* A : {&_mass, &_mass_D, &_damping, &_damping_D, &_jacobian})
    MatDestroy(A);
}

void InertialDynamics::set_initial_velocity(Vec v)
{
  GELX_PETSC(VecCopy(v, _initial_velocity.get()));
}

void InertialDynamics::set_time(double t) { _apply_load(smooth_step(t, _loading_time)); }

void InertialDynamics::set_stage_time(double t_stage)
{
  // The amplitude at the stage is the alpha_f-weighted mean of the step's end amplitudes,
  // not the amplitude at the stage time: the prescribed rows hold u_a - g with
  // u_a = (1 - alpha_f) u_n + alpha_f u_n+1, so that the step ends exactly on g(t_n+1) (for
  // prescribed values linear in the amplitude). With g(t_a) instead, at rho_inf = 1 it ends
  // off g by 2 g(t_a) - g(t_n) - g(t_n+1) = -g'' dt^2 / 4 plus the previous step's error with
  // its sign changed: an undamped alternation that the Newmark update turns into an
  // acceleration as large as g'' in those rows, felt by their free neighbours through the
  // mass. TSAlpha_Restart's backward-Euler half steps run with alpha_f = 1: the amplitude
  // at the stage time.
  PetscReal alpha_m, alpha_f, gamma, beta, dt;
  GELX_PETSC(TSAlpha2GetParams(_ts, &alpha_m, &alpha_f, &gamma, &beta));
  GELX_PETSC(TSGetTimeStep(_ts, &dt));
  const double t_start = t_stage - alpha_f * dt;
  _apply_load((1 - alpha_f) * smooth_step(t_start, _loading_time)
              + alpha_f * smooth_step(t_start + dt, _loading_time));
}

void InertialDynamics::form_function(double t, Vec u, Vec v, Vec a, Vec F)
{
  if (_explicit)
    set_time(t); // central differences evaluate at the step's end
  else
    set_stage_time(t);
  _system.set_state(u);
  if (!_system.admissible() && _explicit)
    throw ConvergenceError("explicit central differences reached an inadmissible state "
                           "(det F <= 0) at t = " + std::to_string(t)
                           + ": a step above the stable step, or the body crushed");
  if (!_system.admissible())
  {
    SNES snes;
    GELX_PETSC(TSGetSNES(_ts, &snes));
    GELX_PETSC(SNESSetFunctionDomainError(snes)); // the stage fails; TS cuts the step
    return;
  }
  _system.residual(F);
  GELX_PETSC(MatMultAdd(_mass_D, a, F, F));
  if (_damping_D)
    GELX_PETSC(MatMultAdd(_damping_D, v, F, F));
}

void InertialDynamics::form_jacobian(double t, Vec u, double shift_v, double shift_a, Mat P)
{
  set_stage_time(t);
  _system.set_state(u);
  _system.tangent(P);
  // A lumped mass stores its diagonal alone (lumped_mass); C = a M + b K0 then too, or K0's
  const MatStructure pattern = _lumping.empty() ? SAME_NONZERO_PATTERN : SUBSET_NONZERO_PATTERN;
  GELX_PETSC(MatAXPY(P, shift_a, _mass_D, pattern));
  if (_damping_D)
    GELX_PETSC(MatAXPY(P, shift_v, _damping_D, pattern));
}

void InertialDynamics::reactions(Vec u, Vec v, Vec a, Vec r)
{
  _system.set_state(u);
  _system.problem().internal_forces(r);
  GELX_PETSC(MatMultAdd(_mass, a, r, r));
  if (_damping)
    GELX_PETSC(MatMultAdd(_damping, v, r, r));
  // Only the prescribed rows: the free rows' residual is the solve's, not a force
  PetscScalar* values;
  PetscInt n;
  GELX_PETSC(VecGetLocalSize(r, &n));
  std::vector<double> kept(_prescribed.size());
  GELX_PETSC(VecGetArray(r, &values));
  for (std::size_t i = 0; i < _prescribed.size(); ++i)
    kept[i] = values[_prescribed[i]];
  std::fill(values, values + n, 0.0);
  for (std::size_t i = 0; i < _prescribed.size(); ++i)
    values[_prescribed[i]] = kept[i];
  GELX_PETSC(VecRestoreArray(r, &values));
}

void InertialDynamics::pre_step()
{
  if (_explicit)
    choose_explicit_step();
  // A resumed run continues from the state save() wrote, not from a new TSALPHA2 start
  keep_restored_start(_ts, _resuming);
}

void InertialDynamics::pre_stage()
{
  // The first step's stages: TSALPHA2 has started the run (TSAlpha_Restart) with an
  // acceleration of its own, a backward difference of the velocities of two backward-Euler
  // half steps: first-order, and off by as much as the acceleration itself (measured on the
  // cantilever released at u = 0 with omega v0 = 3e-9: |a0| = 7.0e-9 where the equation of
  // motion gives 0). Its half steps run with the parameters (1, 1, 1, 1/2); the step itself
  // starts from the consistent acceleration instead, solved from the equation of motion at
  // t = 0. (With rho_inf = 1, the trapezoidal rule, u and v do not depend on the
  // acceleration: alpha_m = 1/2 and beta = 1/4 cancel it from the stage equation; with
  // rho_inf < 1 they do.)
  if (!_initial_acceleration)
    return; // not the first step, or central differences (which solve their own start)
  PetscReal alpha_m, alpha_f, gamma, beta;
  GELX_PETSC(TSAlpha2GetParams(_ts, &alpha_m, &alpha_f, &gamma, &beta));
  if (alpha_m == 1 && alpha_f == 1 && gamma == 1 && beta == 0.5)
    return;
  Alpha2State& alpha = alpha2_state(_ts);
  GELX_PETSC(VecCopy(_initial_acceleration.get(), alpha.A0));
}

void InertialDynamics::check_step_size()
{
  if (const double step = stop_below_min_step(_ts, _min_step); step > 0)
    _too_small_step = step;
  // Fixed steps (-PREFIX_ts_adapt_type none) come back after a cut: PETSc 3.18's TSADAPTNONE
  // keeps the step that a failed Newton solve cut (to a quarter) for the rest of the run
  // (measured: the bistrip buckling at 24.85 cm then went on at a sixteenth of its step)
  // Only where a whole step remains: near the end TSAdapt's own choice lands on the final
  // time (-ts_exact_final_time matchstep)
  if (_fixed_step > 0)
  {
    PetscReal t, end_time, next;
    GELX_PETSC(TSGetTime(_ts, &t));
    GELX_PETSC(TSGetMaxTime(_ts, &end_time));
    GELX_PETSC(TSGetTimeStep(_ts, &next));
    if (next < _fixed_step && end_time - t > _fixed_step * (1 + 1e-9))
      GELX_PETSC(TSSetTimeStep(_ts, _fixed_step));
  }
}

void InertialDynamics::accepted(int step, double t, Vec u)
{
  if (_skip_first_monitor)
  {
    // TSSolve's first call: the state the run starts from, recorded already
    _skip_first_monitor = false;
    _counters.wall_time = wall_clock();
    return;
  }
  _initial_acceleration.reset(); // the first step is taken
  const StepVectors alpha = step_vectors();
  Vec v = _ts->vec_dot;
  PetscReal t_previous;
  GELX_PETSC(TSGetPrevTime(_ts, &t_previous));
  const double dt = t - t_previous;

  // The supports' work over the step: the reactions at its start (kept from the last step,
  // computed at the first) and at its end
  if (_has_reactions)
  {
    if (!_have_previous_reaction)
    {
      set_time(t_previous);
      reactions(alpha.previous_unknowns, alpha.previous_velocity, alpha.previous_acceleration,
                _previous_reaction.get());
      _have_previous_reaction = true;
    }
    set_time(t);
    reactions(u, v, alpha.acceleration, _reaction.get());
    GELX_PETSC(VecWAXPY(_du.get(), -1.0, alpha.previous_unknowns, u));
    GELX_PETSC(VecAXPY(_reaction.get(), 1.0, _previous_reaction.get()));
    PetscScalar work;
    GELX_PETSC(VecDot(_reaction.get(), _du.get(), &work));
    _summary.external_work += 0.5 * work;
    // _reaction now holds r_n-1 + r_n: keep r_n for the next step
    GELX_PETSC(VecAXPY(_reaction.get(), -1.0, _previous_reaction.get()));
    std::swap(_reaction, _previous_reaction);
  }
  set_time(t);
  _system.set_state(u);
  _system.commit();
  if (_damping)
  {
    GELX_PETSC(VecAXPBYPCZ(_mean_velocity.get(), 0.5, 0.5, 0.0, v, alpha.previous_velocity));
    _summary.dissipated_energy += dt * quadratic_form(_damping, _mean_velocity.get(), _work.get());
  }

  DynamicsRecord record;
  record.step = accepted_step(_ts, step, smooth_step(t, _loading_time), dt, _counters);
  record.time = t;
  record.strain_energy = _strain_energy();
  record.kinetic_energy = 0.5 * quadratic_form(_mass, v, _work.get());
  record.dissipated_energy = _summary.dissipated_energy;
  record.stable_step = _stable_step;
  if (_has_reactions)
  {
    record.external_work = _summary.external_work;
    record.balance_residual = record.external_work - (record.strain_energy - _strain_energy0)
                              - (record.kinetic_energy - _kinetic_energy0)
                              - record.dissipated_energy;
  }
  _summary.steps = step;
  _summary.rejected_steps += record.step.cutbacks;
  PetscInt failed_solves;
  GELX_PETSC(TSGetSNESFailures(_ts, &failed_solves));
  _summary.failed_solves = failed_solves;
  _summary.time = t;
  _summary.strain_energy = record.strain_energy;
  _summary.kinetic_energy = record.kinetic_energy;
  _summary.balance_residual = record.balance_residual;
  if (_explicit)
    _summary.integrator["smallest_stable_step"] = _smallest_stable_step;
  _summary.dissipation_ratio = record.dissipation_ratio();
  if (record.strain_energy > 0)
    _summary.kinetic_ratio = std::max(_summary.kinetic_ratio, record.kinetic_ratio());
  for (const auto& observe : *_observers)
    observe(record);
}

OwnedVec InertialDynamics::consistent_acceleration(Vec v)
{
  // M_D a = -(R(u) + C_D v) in the free rows, a = 0 in the prescribed ones (the smooth step
  // starts without acceleration): M_D with the identity in the prescribed rows
  OwnedVec a(_system.create_vector()), rhs(_system.create_vector());
  _system.residual(rhs.get());
  if (_damping_D)
    GELX_PETSC(MatMultAdd(_damping_D, v, rhs.get(), rhs.get()));
  GELX_PETSC(VecScale(rhs.get(), -1.0));
  PetscInt first_row;
  GELX_PETSC(MatGetOwnershipRange(_mass, &first_row, nullptr));
  std::vector<PetscInt> rows = _prescribed;
  for (PetscInt& r : rows)
    r += first_row;
  Mat M;
  GELX_PETSC(MatDuplicate(_mass_D, MAT_COPY_VALUES, &M));
  GELX_PETSC(MatZeroRows(M, PetscInt(rows.size()), rows.data(), 1.0, nullptr, nullptr));
  PetscScalar* values;
  GELX_PETSC(VecGetArray(rhs.get(), &values));
  for (PetscInt r : _prescribed)
    values[r] = 0;
  GELX_PETSC(VecRestoreArray(rhs.get(), &values));
  set_default_option(_prefix + "mass_", "ksp_type", "preonly");
  set_default_option(_prefix + "mass_", "pc_type", "lu");
  set_default_option(_prefix + "mass_", "pc_factor_mat_solver_type", "mumps");
  KSP ksp;
  GELX_PETSC(KSPCreate(_comm, &ksp));
  GELX_PETSC(KSPSetOptionsPrefix(ksp, (_prefix + "mass_").c_str()));
  GELX_PETSC(KSPSetOperators(ksp, M, M));
  GELX_PETSC(KSPSetFromOptions(ksp));
  const PetscErrorCode ierr = KSPSolve(ksp, rhs.get(), a.get());
  KSPDestroy(&ksp);
  MatDestroy(&M);
  GELX_PETSC(ierr);
  return a;
}

InertialDynamics::StepVectors InertialDynamics::step_vectors() const
{
  if (_explicit)
  {
    const CentralDifferenceState cd = central_difference_state(_ts);
    return {cd.previous_unknowns, cd.previous_velocity, cd.previous_acceleration,
            cd.acceleration};
  }
  const Alpha2State& alpha = alpha2_state(_ts);
  return {alpha.X0, alpha.V0, alpha.A0, alpha.A1};
}

void InertialDynamics::set_lumped_mass(Vec m)
{
  // M = diag(m), M_D with the prescribed rows zeroed, C = a M; TS's diagonals: M_D with 1
  // where prescribed (those rows' F = u - g is zero: any divisor), a M_D
  OwnedVec free = copy_of(m);
  PetscScalar* values;
  GELX_PETSC(VecGetArray(free.get(), &values));
  for (PetscInt r : _prescribed)
    values[r] = 0;
  GELX_PETSC(VecRestoreArray(free.get(), &values));
  GELX_PETSC(MatDiagonalSet(_mass, m, INSERT_VALUES));
  GELX_PETSC(MatDiagonalSet(_mass_D, free.get(), INSERT_VALUES));
  GELX_PETSC(VecAXPBY(_damping_diagonal.get(), _rayleigh_mass, 0.0, free.get()));
  if (_damping)
  {
    GELX_PETSC(MatDiagonalSet(_damping, _damping_diagonal.get(), INSERT_VALUES));
    GELX_PETSC(MatDiagonalSet(_damping_D, _damping_diagonal.get(), INSERT_VALUES));
  }
  GELX_PETSC(VecCopy(free.get(), _mass_diagonal.get()));
  GELX_PETSC(VecGetArray(_mass_diagonal.get(), &values));
  for (PetscInt r : _prescribed)
    values[r] = 1;
  GELX_PETSC(VecRestoreArray(_mass_diagonal.get(), &values));
  if (m != _lumped_mass.get())
    GELX_PETSC(VecCopy(m, _lumped_mass.get()));
}

void InertialDynamics::measure_prescribed_motion()
{
  // g(A) read off the residual's prescribed rows, x - g, at amplitudes 0, 1 and 1/2
  Vec x = _system.unknowns();
  OwnedVec r(_system.create_vector());
  std::array<std::vector<double>, 3> g;
  const std::array<double, 3> amplitudes{0.0, 1.0, 0.5};
  for (int k = 0; k < 3; ++k)
  {
    _apply_load(amplitudes[k]);
    _system.unknowns_changed();
    _system.residual(r.get());
    const PetscScalar *xv, *rv;
    GELX_PETSC(VecGetArrayRead(x, &xv));
    GELX_PETSC(VecGetArrayRead(r.get(), &rv));
    for (PetscInt i : _prescribed)
      g[k].push_back(xv[i] - rv[i]);
    GELX_PETSC(VecRestoreArrayRead(r.get(), &rv));
    GELX_PETSC(VecRestoreArrayRead(x, &xv));
  }
  _apply_load(0.0);
  _system.unknowns_changed();
  double off = 0, size = 0;
  for (std::size_t i = 0; i < g[0].size(); ++i)
  {
    off = std::max(off, std::abs(g[2][i] - 0.5 * (g[0][i] + g[1][i])));
    size = std::max({size, std::abs(g[0][i]), std::abs(g[1][i])});
  }
  MPI_Allreduce(MPI_IN_PLACE, &off, 1, MPI_DOUBLE, MPI_MAX, _comm);
  MPI_Allreduce(MPI_IN_PLACE, &size, 1, MPI_DOUBLE, MPI_MAX, _comm);
  if (off > 1e-12 * std::max(size, 1e-300))
    throw InputError("explicit central differences need prescribed displacements affine in "
                     "the load amplitude; this scene's are off by "
                     + std::to_string(off / size) + " of their size at A = 1/2");
  _prescribed_base.reset(_system.create_vector());
  _prescribed_range.reset(_system.create_vector());
  GELX_PETSC(VecSet(_prescribed_base.get(), 0.0));
  GELX_PETSC(VecSet(_prescribed_range.get(), 0.0));
  PetscScalar *base, *range;
  GELX_PETSC(VecGetArray(_prescribed_base.get(), &base));
  GELX_PETSC(VecGetArray(_prescribed_range.get(), &range));
  for (std::size_t i = 0; i < _prescribed.size(); ++i)
  {
    base[_prescribed[i]] = g[0][i];
    range[_prescribed[i]] = g[1][i] - g[0][i];
  }
  GELX_PETSC(VecRestoreArray(_prescribed_range.get(), &range));
  GELX_PETSC(VecRestoreArray(_prescribed_base.get(), &base));
}

void InertialDynamics::prescribe(double t, Vec u, Vec v, Vec a)
{
  const double A = smooth_step(t, _loading_time);
  const double A1 = smooth_step_derivative(t, _loading_time, 1);
  const double A2 = smooth_step_derivative(t, _loading_time, 2);
  const PetscScalar *base, *range;
  GELX_PETSC(VecGetArrayRead(_prescribed_base.get(), &base));
  GELX_PETSC(VecGetArrayRead(_prescribed_range.get(), &range));
  PetscScalar *uv, *vv, *av;
  GELX_PETSC(VecGetArray(u, &uv));
  GELX_PETSC(VecGetArray(v, &vv));
  GELX_PETSC(VecGetArray(a, &av));
  for (PetscInt i : _prescribed)
  {
    uv[i] = base[i] + A * range[i];
    vv[i] = A1 * range[i];
    av[i] = A2 * range[i];
  }
  GELX_PETSC(VecRestoreArray(a, &av));
  GELX_PETSC(VecRestoreArray(v, &vv));
  GELX_PETSC(VecRestoreArray(u, &uv));
  GELX_PETSC(VecRestoreArrayRead(_prescribed_range.get(), &range));
  GELX_PETSC(VecRestoreArrayRead(_prescribed_base.get(), &base));
}

void InertialDynamics::choose_explicit_step()
{
  PetscReal t, end_time;
  GELX_PETSC(TSGetTime(_ts, &t));
  GELX_PETSC(TSGetMaxTime(_ts, &end_time));
  double dt = _fixed_step;
  if (dt == 0)
  {
    // The stiffness moves with the state (a stiffening law, contact of folds): re-estimated
    // every stable_step_every steps, each a tangent assembly, about as costly as a few
    // residual evaluations
    if (std::isnan(_stable_step) || ++_steps_since_estimate >= _stable_step_every)
    {
      set_time(t);
      _system.set_state(_ts->vec_sol);
      _system.tangent(_jacobian);
      const double bound = gershgorin_bound(_jacobian, _lumped_mass.get(), _prescribed);
      _stable_step = _step_fraction * 2 / std::sqrt(bound);
      _smallest_stable_step = std::min(_smallest_stable_step, _stable_step);
      _steps_since_estimate = 0;
    }
    dt = _stable_step;
  }
  GELX_PETSC(TSSetTimeStep(_ts, std::min(dt, end_time - t)));
}

Vec InertialDynamics::velocity() const { return _ts->vec_dot; }
Vec InertialDynamics::acceleration() const { return step_vectors().acceleration; }

void InertialDynamics::save(PathState& state) const
{
  const StepVectors alpha = step_vectors();
  save_ts_position(_ts, state);
  state.vectors["velocity"] = copy_of(_ts->vec_dot);
  state.vectors["acceleration"] = copy_of(alpha.acceleration);
  state.vectors["previous_unknowns"] = copy_of(alpha.previous_unknowns);
  state.vectors["previous_velocity"] = copy_of(alpha.previous_velocity);
  if (_explicit)
    state.vectors["lumped_mass"] = copy_of(_lumped_mass.get()); // mass scaling included
  state.driver.update({{"strain_energy0", _strain_energy0},
                       {"kinetic_energy0", _kinetic_energy0},
                       {"dissipated_energy", _summary.dissipated_energy},
                       {"external_work", _summary.external_work},
                       {"kinetic_ratio", _summary.kinetic_ratio},
                       {"rejected_steps", _summary.rejected_steps}});
  if (_explicit)
    state.driver.update({{"stable_step", _stable_step},
                         {"smallest_stable_step", _smallest_stable_step},
                         {"steps_since_estimate", _steps_since_estimate}});
}

DynamicsSummary InertialDynamics::run(const std::vector<DynamicsObserver>& observers,
                                      const PathState* resume)
{
  _observers = &observers;
  _summary = DynamicsSummary{};
  _summary.dissipation_bound = INFINITY; // no quasi-static criterion of real inertia
  _summary.kinetic_bound = _kinetic_bound;
  _summary.integrator = {{"scheme", _explicit ? "central_difference" : "generalised_alpha"},
                         {"mass", _lumping.empty() ? "consistent" : "lumped " + _lumping}};
  if (_explicit)
    _summary.integrator["added_mass_ratio"] = _added_mass / _total_mass;
  _summary.external_work = _has_reactions ? 0.0 : NAN;
  _counters = StepCounters{};
  _have_previous_reaction = false;
  _too_small_step = 0;

  OwnedVec u = copy_of(_system.unknowns());
  OwnedVec v = copy_of(resume ? resume->vectors.at("velocity").get() : _initial_velocity.get());
  GELX_PETSC(TS2SetSolution(_ts, u.get(), v.get()));
  GELX_PETSC(TSSetUp(_ts));
  const StepVectors alpha = step_vectors();
  _stable_step = NAN;
  _smallest_stable_step = INFINITY;
  if (_explicit)
    *central_difference_state(_ts).acceleration_known = resume != nullptr;
  if (resume)
  {
    GELX_PETSC(VecCopy(resume->vectors.at("previous_unknowns").get(), alpha.previous_unknowns));
    GELX_PETSC(VecCopy(resume->vectors.at("previous_velocity").get(), alpha.previous_velocity));
    GELX_PETSC(VecCopy(resume->vectors.at("acceleration").get(), alpha.acceleration));
    if (_explicit)
    {
      set_lumped_mass(resume->vectors.at("lumped_mass").get());
      _stable_step = resume->driver.at("stable_step");
      _smallest_stable_step = resume->driver.at("smallest_stable_step");
      _steps_since_estimate = resume->driver.at("steps_since_estimate");
    }
    restore_ts_position(_ts, *resume);
    _strain_energy0 = resume->driver.at("strain_energy0");
    _kinetic_energy0 = resume->driver.at("kinetic_energy0");
    _summary.dissipated_energy = resume->driver.at("dissipated_energy");
    _summary.kinetic_ratio = resume->driver.at("kinetic_ratio");
    _summary.rejected_steps = resume->driver.at("rejected_steps");
    if (_has_reactions)
      _summary.external_work = resume->driver.at("external_work");
    _resuming = true;
    _initial_acceleration.reset();
  }
  else
  {
    GELX_PETSC(TSSetTime(_ts, 0.0));
    GELX_PETSC(TSSetStepNumber(_ts, 0));
    GELX_PETSC(TSSetTimeStep(_ts, real_option(_prefix, "ts_dt", _loading_time / 100)));
    set_time(0.0);
    _system.set_state(u.get());
    _strain_energy0 = _strain_energy();
    _kinetic_energy0 = 0.5 * quadratic_form(_mass, v.get(), _work.get());
    _resuming = false;
    // central differences solve their own (diagonal) start
    if (!_explicit)
      _initial_acceleration = consistent_acceleration(v.get());
  }
  _skip_first_monitor = true;
  // Errors of the callbacks (an explicit run that blows up, a step budget spent in a monitor)
  // are rethrown as one line
  solve_guarded(callback_error, [&] { return TSSolve(_ts, u.get()); });
  _observers = nullptr;
  _resuming = false;
  // The last accepted state (a failed step is rolled back)
  PetscReal t;
  GELX_PETSC(TSGetTime(_ts, &t));
  set_time(t);
  _system.set_state(_ts->vec_sol);
  throw_if_stopped_early(_ts, t, _explicit ? "explicit dynamics" : "inertial dynamics",
                         _too_small_step, _prefix, _min_step, "");
  return _summary;
}

} // namespace gelx
