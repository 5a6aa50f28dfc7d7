#pragma once
/// @file transient.h
/// A problem whose residual holds the rate of its unknowns, R(w, w'; t) = 0, integrated in
/// time by an implicit PETSc TS: a differential-algebraic system such as a swelling gel's,
/// whose equilibrium rows hold no rate and whose solvent-conservation rows do.

#include <gelx/solvers/dynamics.h>
#include <gelx/systems/problem.h>

#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Function.h>
#include <exception>
#include <functional>
#include <memory>
#include <mpi.h>
#include <petscts.h>
#include <string>

namespace gelx
{

/// One accepted step of a TransientProblem: its record (number, time as the load, size,
/// Newton and linear iterations, rejected attempts, wall time) and its time.
struct TransientStep
{
  StepRecord step;
  double time = 0;
  /// Its steps.csv columns, as the dynamics scenes name them (a scene adds its quantities)
  nlohmann::json columns() const
  {
    return {{"step", step.step},
            {"time", time},
            {"dt", step.step_size},
            {"newton_iterations", step.newton.iterations},
            {"linear_iterations", step.newton.linear_iterations},
            {"rejected", step.cutbacks},
            {"wall_time", step.wall_time}};
  }
};

/// Integrates R(w, w'; t) = 0 from the system's current state at t = 0 to an end time.
///
/// The system is a NonlinearProblem or a decorator of one (a MultipointConstraint: TS then
/// integrates the reduced unknowns x, with w = P x + g and w' = P x'). The problem's residual
/// form holds the rate as the coefficient `rate` (on the problem's space), and its tangent
/// form is dR/dw + shift dR/dw' with `shift` a constant of the form: the Jacobian of TS's
/// implicit function, shift being TS's d(w')/dw. Its Dirichlet rows stay u - g(t): algebraic
/// equations, with g set by `set_time(t)` before every evaluation. Options prefix `prefix`
/// for TS, SNES and KSP; by default adaptive BDF of order 2 with first step end_time * 1e-6,
/// steps up to end_time / 10, a direct solve (MUMPS). Why TS and not a backward-Euler form of
/// one's own: its BDFs are L-stable and adapt the step to the transient, which spans decades
/// (a diffusion front's sqrt(t) start, then the slow approach to equilibrium). Restart:
/// save() puts TSBDF's history into a PathState (save_bdf_history), which a Checkpoints
/// stores; run(observe, &state) continues from it, equal to the uninterrupted run to
/// round-off.
///
/// A step's Newton iteration stops, by default, at -PREFIX_snes_rtol 1e-3 of its first
/// residual. `-PREFIX_newton_test correction` stops it instead by CVODE's test (Hindmarsh et
/// al., SUNDIALS, ACM TOMS 31, 2005), which PETSc 3.18's SNES lacks and which is here a
/// convergence-test hook: when the last correction, in TS's error weights (-PREFIX_ts_atol,
/// _ts_rtol: a correction of 1 is the local error the step adaptivity accepts) and its largest
/// entry, times the iteration's contraction rate (the ratio of successive corrections, at
/// least 0.2 of the last one's, kept from step to step and by save()) is at most 0.1. The
/// iterate is then within about a tenth of the error TS accepts of the step's root, whatever
/// the residual's scale; PETSc's tests still stop a residual that is not finite or at
/// -PREFIX_snes_atol, and iterations run out. It saves the second Newton iteration that the
/// residual's relative test asks for at loose TS tolerances (demos/swelling/README, Speed).
class TransientProblem
{
public:
  TransientProblem(MPI_Comm comm, NonlinearSystem& system,
                   std::shared_ptr<dolfinx::fem::Function<double>> rate,
                   dolfinx::fem::Constant<double>& shift,
                   std::function<void(double)> set_time, double end_time,
                   const std::string& prefix);
  ~TransientProblem();
  TransientProblem(const TransientProblem&) = delete;
  TransientProblem& operator=(const TransientProblem&) = delete;

  /// Run to the end time from the problem's current state at t = 0, or, with `resume`, from
  /// the state save() wrote (the system already at its unknowns), calling `observe` after
  /// every accepted step with the system at that step's state. Throws ConvergenceError when
  /// TS gives up; the system then holds the last accepted state. Returns the number of the
  /// last step.
  int run(const std::function<void(const TransientStep&)>& observe,
          const PathState* resume = nullptr);
  double end_time() const { return _end_time; }
  /// The integrator's state after the last accepted step into `state`. Collective.
  void save(PathState& state) const;

  /// For the C callbacks.
  void form_function(double t, Vec w, Vec w_dot, Vec F);
  void form_jacobian(double t, Vec w, Vec w_dot, double shift, Mat P);
  void accepted(int step, double t, Vec w);
  void check_step_size();
  void pre_step();
  /// CVODE's test on the Newton correction after `iteration`, over PETSc's `reason`
  void test_newton_correction(SNES snes, int iteration, SNESConvergedReason* reason);
  /// An exception a callback raised, rethrown by run() after TSSolve returns
  std::exception_ptr callback_error;

private:
  /// The system's unknowns and the rate coefficient at (t, x, x')
  void set_state(double t, Vec x, Vec x_dot);

  NonlinearSystem& _system;
  std::shared_ptr<dolfinx::fem::Function<double>> _rate;
  Vec _problem_rate = nullptr; ///< x' prolonged to the problem's dofs
  Vec _previous_iterate = nullptr; ///< Newton's last iterate, for CVODE's correction test
  double _last_correction = 0, _correction_rate = 1;
  dolfinx::fem::Constant<double>& _shift;
  std::function<void(double)> _set_time;
  std::string _prefix;
  double _end_time, _min_step;
  double _too_small_step = 0;
  TS _ts = nullptr;
  Mat _jacobian = nullptr;
  StepCounters _counters;
  const std::function<void(const TransientStep&)>* _observe = nullptr;
  bool _resuming = false, _skip_first_monitor = false;
};

} // namespace gelx
