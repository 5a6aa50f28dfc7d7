#pragma once
/// @file inertia.h
/// Second-order dynamics with inertia, M u'' + C u' + R(u; t) = 0, on PETSc's generalised-alpha
/// integrator TSALPHA2: what ABAQUS/Explicit and /Standard's dynamic steps compute, with their
/// energy history (ALLSE, ALLKE, ALLVD, ALLWK and the balance).

#include <gelx/solvers/dynamics.h>
#include <gelx/solvers/path.h>
#include <gelx/systems/system.h>

#include <dolfinx/fem/Form.h>
#include <exception>
#include <functional>
#include <mpi.h>
#include <petscts.h>
#include <string>
#include <vector>

namespace gelx
{

/// Follows a NonlinearSystem through time with inertia:
///     M u'' + C u' + R(u; A(t)) = 0,   u(0) = the system's current state, u'(0) = v0,
/// M the consistent mass matrix (a UFL mass form rho inner(du, v) dx), C = a M + b K0 Rayleigh
/// damping (K0 the tangent at the initial state: a constant C, so that the damping is linear
/// and its dissipation a quadratic form; a = b = 0 by default), and the loads A(t) ramped by
/// the smooth step over the loading time T (ABAQUS' SMOOTH STEP amplitude), then held for a
/// hold time.
///
/// Time integration: PETSc's TSALPHA2 (Chung & Hulbert's generalised-alpha), second-order
/// accurate, unconditionally stable for linear problems, its high-frequency dissipation set by
/// the spectral radius at infinity, -PREFIX_ts_alpha_radius rho_inf (1: none, the trapezoidal
/// rule, which conserves the energy of a linear undamped system exactly; PETSc's own default).
/// TS evaluates F(t, u, v, a) = M_D a + C_D v + R(u; t) at the stage (t_n+alpha_f, u_n+alpha_f,
/// v_n+alpha_f, a_n+alpha_m), with M_D, C_D the matrices with the prescribed rows zeroed: those
/// rows hold R's u - g with the loads at the step's alpha_f-weighted amplitude
/// (1 - alpha_f) A(t_n) + alpha_f A(t_n+1), so that every step ends on the prescribed
/// displacements g(t_n+1) (set_stage_time says why not A(t_n+alpha_f)).
/// The step adapts through TSAdapt (-PREFIX_ts_adapt_type basic by default, on TSALPHA2's
/// local error estimate; `none` for fixed steps). An inadmissible state (admissible() false)
/// is a SNES function-domain error: TS retries the step smaller.
///
/// Energies (as ABAQUS' history output), at every accepted step: SE (the scene's stored
/// energy, `strain_energy()`), KE = 1/2 v^T M v, the viscous dissipation ED = int v^T C v dt
/// (midpoint rule per step, which the trapezoidal rule's balance makes exact for linear
/// problems), the work of the supports W = int r . du over the prescribed rows with the
/// reactions r = (R(u) + M a + C v) there (trapezoidal), and the balance residual
/// W - (SE - SE0) - (KE - KE0) - ED: the numerical dissipation of rho_inf < 1 and the time
/// integration's error. W and the balance need reactions, so only for a system whose unknowns
/// are the problem's (the problem or a decorator keeping its layout; NaN otherwise); SE must then be all of the scene's potential energy (no
/// applied loads besides prescribed displacements, or their potential included).
///
/// Restart: save() puts the integrator's state after the last accepted step (velocity,
/// acceleration, the previous step's state and time for the error estimate, the step size,
/// the energy accounts) into a PathState, which a Checkpoints stores; run(observers, &state)
/// continues from it, equal to the uninterrupted run to round-off. Why a hook into PETSc's
/// private state: TSALPHA2 keeps the acceleration and the previous step to itself, and at the
/// start of every TSSolve it computes a new acceleration from two backward-Euler half steps
/// (TSAlpha_Restart), which would take a restarted run off the uninterrupted one by the
/// time-integration error. gelx writes them back into PETSc 3.18's TSALPHA2 state and skips
/// that start; the layout is checked at run time against TSAlpha2GetParams and the vectors'
/// sizes, and a PETSc whose layout differs is refused in one line.
///
/// Explicit central differences (-PREFIX_ts_type gelx_central_difference, the scheme of
/// ABAQUS/Explicit; central_difference.h): the same equation with a lumped mass, each step one
/// residual evaluation and no solve, the step below the stable step 2 / omega_max. The step is
/// fraction * 2 / sqrt(lambda), lambda Gershgorin's bound of the largest eigenvalue of M^-1 K
/// (never below it, so the step is never above the critical one), K the tangent at the
/// current state, re-estimated every `stable_step_every` steps; or fixed by -PREFIXdt. Mass
/// scaling (-PREFIXmass_scaling_step dt): the lumped masses raised where needed so that the
/// stable step is at least dt, from the tangent where the integrator is constructed (ABAQUS'
/// fixed mass scaling at the step's start), the mass added reported in the summary. Damping:
/// mass-proportional only (C = a M stays diagonal; b K would need a solve per step). The
/// prescribed displacements must be affine in the amplitude (checked), so that their
/// velocity and acceleration are the smooth step's derivatives, exact at every step end.
/// Restart as for TSALPHA2 (the acceleration is the central-difference type's own state).
///
/// Options (prefix PREFIX, default `inertial_`): gelx's loading_time (T, 1), hold_time (0), dt
/// (first step, T / 100; explicit: a fixed step instead of the stable-step estimate),
/// rayleigh_mass (a, 1/time, 0), rayleigh_stiffness (b, time, 0), kinetic_bound (KE / SE above
/// which summary says "not quasi-static", 0.05), min_step (1e-12 T), mass (consistent or
/// lumped; explicit: lumped only), lumping (auto, row_sum or diagonal: lumped_mass()),
/// stable_step_fraction (0.9), stable_step_every (100), mass_scaling_step (0: none);
/// PETSc's -PREFIX_ts_* (defaults: ts_type alpha2, ts_adapt_type basic,
/// ts_adapt_dt_max T / 10, ts_max_snes_failures -1, ts_max_reject 20, ts_max_steps 100000),
/// -PREFIX_snes_* (basic line search, max_it 10) and the linear solver set
/// -PREFIX_linear_solver.
class InertialDynamics
{
public:
  /// As DampedDynamics: `mass_form` the bilinear mass form on the problem's space,
  /// `strain_energy()` the stored energy at the current state, `apply_load(a)` every load
  /// at amplitude a.
  InertialDynamics(MPI_Comm comm, NonlinearSystem& system,
                   const dolfinx::fem::Form<double>& mass_form,
                   std::function<double()> strain_energy, std::function<void(double)> apply_load,
                   const std::string& prefix = "inertial_");
  ~InertialDynamics();
  InertialDynamics(const InertialDynamics&) = delete;
  InertialDynamics& operator=(const InertialDynamics&) = delete;

  /// The velocity a new run starts with (in the system's layout; zero unless set).
  void set_initial_velocity(Vec v);

  /// Run from the system's current state at t = 0 at the initial velocity, or, with
  /// `resume`, from the state save() wrote (the system already at its unknowns), to T + hold,
  /// calling every observer after every accepted step. Throws ConvergenceError when TS gives
  /// up; the system then holds the last accepted state.
  DynamicsSummary run(const std::vector<DynamicsObserver>& observers,
                      const PathState* resume = nullptr);

  /// The integrator's state after the last accepted step into `state` (step, time, next step
  /// size; vectors velocity, acceleration, previous_unknowns, previous_velocity; the energy
  /// accounts in state.driver). Collective.
  void save(PathState& state) const;

  /// The velocity and acceleration after the last accepted step (the system's layout).
  Vec velocity() const;
  Vec acceleration() const;

  const DynamicsSummary& summary() const { return _summary; }
  double loading_time() const { return _loading_time; }
  double end_time() const { return _loading_time + _hold_time; }
  TS ts() const { return _ts; }
  /// M (with the prescribed rows) on the system's unknowns: consistent or lumped
  Mat mass() const { return _mass; }
  /// Whether the scheme is explicit central differences
  bool is_explicit() const { return _explicit; }

  /// For the C callbacks
  void form_function(double t, Vec u, Vec v, Vec a, Vec F);
  void form_jacobian(double t, Vec u, double shift_v, double shift_a, Mat P);
  void accepted(int step, double t, Vec u);
  void pre_step();
  void pre_stage();
  void check_step_size();
  /// The prescribed rows' motion at t (central differences' PrescribedMotion)
  void prescribe(double t, Vec u, Vec v, Vec a);
  std::exception_ptr callback_error;

private:
  /// The loads at amplitude A(t)
  void set_time(double t);
  /// The loads of the stage at stage time t_stage (the step's alpha_f-weighted amplitude)
  void set_stage_time(double t_stage);
  /// r . du over the prescribed rows' reactions at (u, v, a), into _reaction (see above).
  void reactions(Vec u, Vec v, Vec a, Vec r);
  /// a(0) from the equation of motion at the current state and velocity v (see pre_stage)
  OwnedVec consistent_acceleration(Vec v);
  /// The integrator's step vectors (TSALPHA2's or central differences')
  struct StepVectors
  {
    Vec previous_unknowns, previous_velocity, previous_acceleration, acceleration;
  };
  StepVectors step_vectors() const;
  /// Central differences: M = diag(m) (mass, M_D, C and TS's diagonals from it)
  void set_lumped_mass(Vec m);
  /// Central differences: the prescribed rows' g(A) = g0 + A dg, checked affine
  void measure_prescribed_motion();
  /// Central differences: the step for the next step (stable-step estimate or fixed)
  void choose_explicit_step();

  MPI_Comm _comm;
  NonlinearSystem& _system;
  std::function<double()> _strain_energy;
  std::function<void(double)> _apply_load;
  std::string _prefix;
  double _loading_time, _hold_time, _kinetic_bound, _min_step;
  double _too_small_step = 0;
  double _fixed_step = 0; ///< with -PREFIX_ts_adapt_type none: the step, restored after cuts
  bool _has_reactions; ///< the unknowns are the problem's: W and the balance are known
  TS _ts = nullptr;
  Mat _mass = nullptr, _mass_D = nullptr;        ///< M and M_D
  Mat _damping = nullptr, _damping_D = nullptr;  ///< C and C_D (null without damping)
  Mat _jacobian = nullptr;
  OwnedVec _initial_acceleration; ///< until the first step is accepted (pre_stage)
  OwnedVec _initial_velocity, _work, _mean_velocity, _reaction, _previous_reaction, _du;
  std::vector<PetscInt> _prescribed; ///< local rows
  bool _explicit = false; ///< central differences
  double _rayleigh_mass = 0;
  std::string _lumping; ///< the lumped mass' method, empty for the consistent mass
  double _total_mass = 0, _added_mass = 0;
  double _step_fraction = 0.9, _smallest_stable_step = INFINITY, _stable_step = NAN;
  int _stable_step_every = 100, _steps_since_estimate = 0;
  OwnedVec _lumped_mass, _mass_diagonal, _damping_diagonal; ///< m; m (1 where prescribed); a m
  OwnedVec _prescribed_base, _prescribed_range; ///< g0, dg

  // The run in progress (and what save() keeps of it)
  const std::vector<DynamicsObserver>* _observers = nullptr;
  DynamicsSummary _summary;
  double _strain_energy0 = 0, _kinetic_energy0 = 0;
  bool _resuming = false, _skip_first_monitor = false, _have_previous_reaction = false;
  StepCounters _counters;
};

} // namespace gelx
