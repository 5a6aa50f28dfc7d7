#pragma once
/// @file dynamics.h
/// Damped quasi-static dynamics: a NonlinearSystem followed through time with PETSc TS, its
/// loads ramped smoothly, the energies of ABAQUS' quasi-static checks recorded at every step.

#include <gelx/common/petsc_utils.h>
#include <gelx/solvers/path.h>
#include <gelx/systems/system.h>

#include <cmath>
#include <dolfinx/fem/Form.h>
#include <exception>
#include <functional>
#include <initializer_list>
#include <memory>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <petscts.h>
#include <string>
#include <vector>

namespace gelx
{

/// The smooth step A(s) = 10 s^3 - 15 s^4 + 6 s^5 of s = t / T, clamped to [0, 1] (ABAQUS'
/// SMOOTH STEP amplitude): zero velocity and acceleration at both ends of the ramp, so that
/// the loading starts and stops without a jerk that would excite the body.
double smooth_step(double t, double loading_time);
/// Its first (order 1) or second (order 2) time derivative: the velocity and acceleration of
/// a prescribed motion g0 + A(t) dg.
double smooth_step_derivative(double t, double loading_time, int order);

// What first- and second-order dynamics (DampedDynamics, InertialDynamics) share

/// The mass form assembled on `system`'s unknowns (a copy where they are the problem's dofs,
/// P^T M P on a reduced space), in the pattern of system.create_matrix(), so that it adds to
/// the tangent entry by entry. Throws std::invalid_argument, naming `who`, for a system with
/// unknowns of its own (the arc-length's load). Collective.
Mat assemble_system_mass(NonlinearSystem& system, const dolfinx::fem::Form<double>& mass_form,
                         const std::string& who);
/// A copy of `A` times `scale` with the system's prescribed rows zeroed (they keep the
/// residual's u - g: algebraic equations of the time integration). Collective.
Mat without_prescribed_rows(const NonlinearSystem& system, Mat A, double scale = 1);
/// The real option -PREFIXname (or `fallback`), which must be positive (or non-negative):
/// InputError otherwise.
double positive_option(const std::string& prefix, const std::string& name, double fallback,
                       bool zero_allowed = false);
/// v^T A v (work: a vector of v's layout). Collective.
double quadratic_form(Mat A, Vec v, Vec work);
/// For a post-step hook: the step just accepted, if it is below `min_step`, and then TS is
/// stopped as by a step it could not take (DIVERGED_STEP_REJECTED); 0 otherwise. Why a floor
/// of gelx's own: PETSc 3.18's TSAdapt retries a failed stage at a quarter of its step
/// without any lower bound (-ts_adapt_dt_min only clamps the steps it proposes), and
/// -ts_max_reject counts rejections in a row only. A state driven to the edge of
/// admissibility (an element's volume going to zero: the pre-compressed bistrip at nz = 60,
/// measured) then has every other stage rejected and the others accepted at 1e-16 s, for
/// ever.
double stop_below_min_step(TS ts, double min_step);
/// TS's monitor and post-step hook for a gelx integrator (DampedDynamics, InertialDynamics,
/// TransientProblem: the TS's monitor and application context) with accepted(step, t, u),
/// check_step_size() and callback_error: what they throw is kept for run() to rethrow.
template <class Integrator>
PetscErrorCode monitor_accepted(TS, PetscInt step, PetscReal t, Vec u, void* ctx)
{
  Integrator& d = *static_cast<Integrator*>(ctx);
  return guarded_callback(d.callback_error, [&] { d.accepted(int(step), t, u); });
}
template <class Integrator>
PetscErrorCode post_step_check(TS ts)
{
  void* ctx;
  PetscCall(TSGetApplicationContext(ts, &ctx));
  Integrator& d = *static_cast<Integrator*>(ctx);
  return guarded_callback(d.callback_error, [&] { d.check_step_size(); });
}
/// The TS pre-step hook of an integrator with pre_step() (a resumed run's first step keeps
/// the integrator's restored state: see keep_restored_start).
template <class Integrator>
PetscErrorCode pre_step_hook(TS ts)
{
  void* ctx;
  PetscCall(TSGetApplicationContext(ts, &ctx));
  Integrator& d = *static_cast<Integrator*>(ctx);
  return guarded_callback(d.callback_error, [&] { d.pre_step(); });
}
/// Before the first step of a resumed TSSolve (`resuming`, then cleared): TS must not start
/// its method again from the current state alone (TSBDF_Restart, TSAlpha_Restart), which
/// would take the continued run off the uninterrupted one, but take the state restored.
void keep_restored_start(TS ts, bool& resuming);
/// TS's step number, time, next step size and previous time into `state` (step, load,
/// step_size, driver["previous_time"]), and back: where an integrator's restart begins.
void save_ts_position(TS ts, PathState& state);
void restore_ts_position(TS ts, const PathState& state);
/// Restart of TSBDF: its step number, time and next step size into `state` (step, load,
/// step_size), and, when TS is TSBDF, its history (the states and times its next steps
/// interpolate, its current order) as state.vectors bdf_state_* and state.driver entries,
/// with driver["restartable"] saying which. Why a hook into PETSc's private state: TSBDF keeps
/// its history to itself and at the start of every TSSolve starts again at order 1 from the
/// current state; gelx writes the history back into PETSc 3.18's TSBDF state (its layout
/// checked at run time against TSBDFGetOrder and the vectors' sizes: a PETSc whose layout
/// differs is refused in one line). Collective.
void save_bdf_history(TS ts, PathState& state);
/// The inverse: TS set up on `x` with the history, time, step number and step size of
/// `state`; call keep_restored_start in the next TSSolve's first pre-step. Throws InputError
/// when the state holds no TSBDF history (another -PREFIX_ts_type) or TS is no TSBDF.
void restore_bdf_history(TS ts, Vec x, const PathState& state);
/// The options both integrators default to (the user's win): TS `type`, basic adaptivity
/// with steps up to loading_time / 10, the first step -PREFIXdt (or `first_step`), the end
/// time loading + hold, failed Newton solves retried with smaller steps (20 in a row at
/// most), 1e5 steps at most; SNES with full steps (basic line search), 10 iterations at most;
/// the linear solver set (set_linear_solver_defaults).
void set_time_stepping_defaults(const std::string& prefix, const std::string& type,
                                double loading_time, double hold_time, double first_step);
/// Makes TS reject a stage whose Newton solve ended in a failed line search that SNES called
/// converged, so that TS retries it with a smaller step (a TSAdapt stage check; call after
/// TSSetFromOptions). Why: PETSc 3.18's SNESNEWTONLS reports a line search that failed,
/// with the step's norm below stol |x|, as converged (SNES_CONVERGED_SNORM_RELATIVE); the
/// basic line search stops without computing that norm when its full step is inadmissible
/// (a domain error), so the stage "converged" in 0 iterations at its initial guess, the
/// previous state. Measured on the bistrip with inertia at a loading time of 0.1 s: from
/// there on every step was accepted so, the end force frozen, until the kinetic energy
/// reached 1e269.
void reject_failed_line_searches(TS ts);

/// TS's counters at the last accepted step, so that each step reports its own share.
struct StepCounters
{
  int snes_iterations = 0, ksp_iterations = 0, rejections = 0;
  double wall_time = 0; ///< wall_clock() then
};
/// The record of the step TS just accepted: its number, amplitude and size, its Newton
/// iterations, linear iterations and rejected attempts since `last`, whether its last SNES
/// solve converged and why, its wall time; `last` moves on to now.
StepRecord accepted_step(TS ts, int step, double amplitude, double dt, StepCounters& last);
/// After TSSolve: throws ConvergenceError naming `what_ran`, TS's reason and the step below
/// -PREFIXmin_step if there was one (in `unit`), unless TS reached its final time.
void throw_if_stopped_early(TS ts, double t, const std::string& what_ran,
                            double too_small_step, const std::string& prefix, double min_step,
                            const std::string& unit);
/// Seconds of a monotonic clock.
double wall_clock();
/// For the hooks into PETSc's private integrator states: whether every one of `vectors` is a
/// PETSc vector of the local size of TS's solution (a layout check, with the parameters the
/// public API gives). Collective only in that the sizes are local.
bool vectors_of_solution_size(TS ts, std::initializer_list<Vec> vectors);

/// One accepted time step.
struct DynamicsRecord
{
  /// step, load (the amplitude A(t) in [0, 1]), step_size (dt), newton (the step's SNES
  /// iterations, linear iterations and reason), cutbacks (steps rejected before this one),
  /// wall_time
  StepRecord step;
  double time = 0;
  double strain_energy = 0;     ///< SE: the scene's stored energy (ABAQUS ALLSE)
  /// KE = 1/2 v^T M v (ALLKE): at the regularised velocity in DampedDynamics, of the
  /// body's motion in InertialDynamics
  double kinetic_energy = 0;
  /// ED = int c v^T M_D v dt, trapezoidal (ALLSD): the work of the viscous forces applied
  /// (M_D: M without the prescribed rows, whose motion the supports impose)
  double dissipated_energy = 0;
  /// InertialDynamics only (NaN otherwise): W, the work of the supports on the body
  /// (ALLWK), and the balance residual W - (SE - SE0) - (KE - KE0) - ED: the energy the time
  /// integration dissipated (ALLNUM-like: generalised-alpha's numerical damping) plus its
  /// error
  double external_work = NAN;
  double balance_residual = NAN;
  /// Explicit central differences only (NaN otherwise): the stable-step estimate in force
  double stable_step = NAN;
  /// KE / SE and ED / SE (NaN while SE = 0)
  double kinetic_ratio() const { return kinetic_energy / strain_energy; }
  double dissipation_ratio() const { return dissipated_energy / strain_energy; }
  /// A row of steps.csv: step, time, amplitude, dt, the energies and ratios (and the work
  /// and balance residual where they are known), iterations, rejected steps, wall time.
  nlohmann::json to_json() const;
};

using DynamicsObserver = std::function<void(const DynamicsRecord&)>;

/// What a run says about itself (DampedDynamics::run), for summary.json (to_json()).
struct DynamicsSummary
{
  int steps = 0;
  int rejected_steps = 0; ///< steps TS rejected (error estimate or failed Newton solve)
  int failed_solves = 0;  ///< stages whose Newton solve failed (inadmissible states included)
  double time = 0;
  double strain_energy = 0;
  double kinetic_energy = 0;
  double dissipated_energy = 0;
  double external_work = NAN;    ///< InertialDynamics only, as in DynamicsRecord
  double balance_residual = NAN; ///< InertialDynamics only, as in DynamicsRecord
  /// What the integrator says about its scheme and mass (InertialDynamics: scheme, mass,
  /// lumping, the added mass of mass scaling, the smallest stable step), merged into to_json
  nlohmann::json integrator;
  /// ED / SE at the end, against its bound
  double dissipation_ratio = 0, dissipation_bound = 0;
  /// The largest KE / SE over the steps (with SE > 0), against its bound
  double kinetic_ratio = 0, kinetic_bound = 0;
  bool quasi_static() const
  {
    return dissipation_ratio <= dissipation_bound && kinetic_ratio <= kinetic_bound;
  }
  nlohmann::json to_json() const;
};

/// Follows R(u; A(t)) = 0 through time as the first-order viscous problem
///     c M u' + R(u; t) = 0,   u(0) = the system's current state,
/// with M the mass matrix (a UFL mass form rho inner(du, v) dx, consistent), c a damping
/// coefficient (1/time) and the loads A(t) ramped by the smooth step over the loading time T,
/// then held for a hold time so that the state settles.
///
/// Why first-order: this is ABAQUS' *STABILIZE (volume-proportional viscous forces c M u'),
/// the regularisation meant for quasi-static problems with instabilities. Its solutions are
/// the equilibria wherever the path is stable (the viscous forces vanish as u' -> 0), and where
/// an equilibrium is lost (a snap, an unstable bifurcated state) it moves to a stable one
/// along a gradient-flow-like path, dissipating the energy released: the quasi-static answer
/// (ED / SE says how far), with none of the second-order inertia that would make a
/// generalised-alpha run ring around the new state (and need a damping tuned against the
/// lowest frequencies, and steps resolving them, before settling). Its time integrators are
/// the stiff, L-stable BDFs, whose step grows freely along the slow parts of a path; their
/// error estimate drives the step with `-PREFIX_ts_adapt_type basic`. The kinetic energy is
/// that of the body moving at the regularised velocity with its density rho: a diagnostic
/// (ABAQUS' ALLKE), not a state variable of the model.
///
/// TS set-up: IFunction F(t, u, u') = c M_D u' + R(u; t), IJacobian shift c M_D + K, with M_D
/// the mass matrix with the prescribed rows (NonlinearSystem::prescribed_rows) zeroed, so
/// that those rows keep R's u - g(t): an algebraic equation of the DAE, which BDF integrates
/// as such. The loads enter through apply_load(A(t)) before every evaluation. An inadmissible
/// state (admissible() false) is a SNES function-domain error: the stage fails and TS retries
/// it with a smaller step.
///
/// Options (prefix PREFIX, default `dynamics_`): gelx's loading_time (T, 1), hold_time (0),
/// damping (c, 1), dt (first step, T / 50), dissipation_bound (ED / SE, 0.05, ABAQUS'
/// recommended ALLSD / ALLIE), kinetic_bound (KE / SE, 0.05) and min_step (1e-12 T: an
/// accepted step below it ends the run with a ConvergenceError); PETSc's -PREFIX_ts_*
/// (defaults: ts_type bdf, ts_bdf_order 2, ts_adapt_type basic, ts_adapt_dt_max T / 10 so that
/// the ramp's energies are resolved, ts_max_snes_failures -1, ts_max_reject 20,
/// ts_max_steps 100000), -PREFIX_snes_*, -PREFIX_ksp_* and -PREFIX_pc_* (a direct solve).
///
/// The velocity of the records is the derivative at t_n of the polynomial through the last
/// three accepted states (two on the first step), the derivative BDF2 itself uses. The
/// energies obey the model's balance W = SE + ED (W the work of the loads and of the prescribed
/// motions); KE is no term of it, since the model has no inertia.
/// The system may be the problem or a decorator of it (a contact, a reduced space of
/// constraints: the mass is then P^T M P, NonlinearSystem::restrict_operator), not a bordered
/// system with unknowns of its own (the arc-length's load). commit() is called once per
/// accepted step, not per Newton iteration (a contact active set moves once per step).
///
/// Restart: save() puts TSBDF's history (save_bdf_history), the step size and the velocity's
/// states into a PathState, which a Checkpoints stores; run(observers, &state) continues
/// from it, equal to the uninterrupted run to round-off. Only with -PREFIX_ts_type bdf (the
/// default).
class DampedDynamics
{
public:
  /// `mass_form`: the bilinear mass form on the problem's space; `strain_energy()`: the
  /// stored energy at the system's current state (collective); `apply_load(a)`: every load
  /// at amplitude a in [0, 1], as LoadStepper's apply_load.
  DampedDynamics(MPI_Comm comm, NonlinearSystem& system,
                 const dolfinx::fem::Form<double>& mass_form,
                 std::function<double()> strain_energy, std::function<void(double)> apply_load,
                 const std::string& prefix = "dynamics_");
  ~DampedDynamics();
  DampedDynamics(const DampedDynamics&) = delete;
  DampedDynamics& operator=(const DampedDynamics&) = delete;

  /// Run from the system's current state at t = 0, or, with `resume`, from the state save()
  /// wrote (the system already at its unknowns), to T + hold, calling every observer after
  /// every accepted step. Throws ConvergenceError when TS gives up; the system then holds the
  /// last accepted state.
  DynamicsSummary run(const std::vector<DynamicsObserver>& observers,
                      const PathState* resume = nullptr);
  /// The integrator's state after the last accepted step into `state` (step, time, next step
  /// size; TSBDF's history and the velocity's states as vectors; the energy accounts in
  /// state.driver). Collective.
  void save(PathState& state) const;

  /// The run's summary so far (complete after run()).
  const DynamicsSummary& summary() const { return _summary; }
  double loading_time() const { return _loading_time; }
  double hold_time() const { return _hold_time; }
  /// The time the run ends at: loading and hold
  double end_time() const { return _loading_time + _hold_time; }
  double damping() const { return _damping; }
  TS ts() const { return _ts; }

  /// For the C callbacks: F = c M_D u' + R(u; t), and its Jacobian into P.
  void form_function(double t, Vec u, Vec u_dot, Vec F);
  void form_jacobian(double t, Vec u, double shift, Mat P);
  /// Energies and observers after an accepted step.
  void accepted(int step, double t, Vec u);
  /// After a step: a step below min_step stops TS (DIVERGED_STEP_REJECTED).
  void check_step_size();
  /// Before a step: a resumed run keeps the history it was given.
  void pre_step();
  /// An exception a callback raised, rethrown by run() after TSSolve returns
  std::exception_ptr callback_error;

private:
  void set_time(double t);
  /// The velocity at the last accepted state (see the class comment) into _velocity.
  void velocity(double t, Vec u);
  /// Keep (t, u) as the newest of the last three accepted states
  void remember(double t, Vec u);

  MPI_Comm _comm;
  NonlinearSystem& _system;
  std::function<double()> _strain_energy;
  std::function<void(double)> _apply_load;
  std::string _prefix;
  double _loading_time, _hold_time, _damping, _dissipation_bound, _kinetic_bound, _min_step;
  double _too_small_step = 0; ///< the step that stopped the run, if one did
  TS _ts = nullptr;
  Mat _mass = nullptr;   ///< M, for the energies
  Mat _damped = nullptr; ///< c M_D, for F and its Jacobian
  Mat _jacobian = nullptr;
  Vec _velocity = nullptr;
  OwnedVec _work; ///< M v, for the energies
  /// The last three accepted states and times, newest first (for the velocity)
  std::vector<OwnedVec> _history;
  std::vector<double> _history_time;

  // The run in progress
  const std::vector<DynamicsObserver>* _observers = nullptr;
  DynamicsSummary _summary;
  double _power = 0; ///< c v^T M v at the last accepted step
  StepCounters _counters;
  bool _resuming = false, _skip_first_monitor = false;
};

} // namespace gelx
