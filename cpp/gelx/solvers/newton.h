#pragma once
/// @file newton.h
/// Newton's method for a NonlinearSystem: PETSc SNES, with gelx's admissibility check and
/// convergence test as hooks into it.

#include <gelx/systems/system.h>
#include <mpi.h>
#include <petscsnes.h>
#include <string>
#include <vector>

namespace gelx
{

/// Outcome of one nonlinear solve.
struct NewtonReport
{
  bool converged = false;
  int iterations = 0;
  int linear_iterations = 0;
  int backtracks = 0;        ///< step halvings for admissibility plus line-search reductions
  double residual0 = 0;      ///< |R| at the start
  double residual = 0;       ///< |R| at the end
  double error_estimate = 0; ///< estimated |x - x_exact| at the end (see NewtonSolver)
  std::string reason;        ///< why it stopped
  /// The SNES type that solved (SNESGetType after the solve): what the options database and
  /// the system's decorators actually set, recorded so a test can tell, e.g., a VI solve
  std::string snes_type;
  /// |R| at the start and after each iteration (for convergence-rate checks)
  std::vector<double> residual_history;
};

/// Solves R(x) = 0 for a NonlinearSystem with PETSc SNES, from the system's current state.
///
/// Every choice PETSc offers goes through the options database with the solver's prefix
/// (`newton_` by default), as PETSc documents it: -newton_snes_type (newtonls; vinewtonrsls
/// for bounds), -newton_snes_linesearch_type (bt by default; basic, l2, cp),
/// -newton_snes_monitor, -newton_snes_converged_reason, -newton_snes_rtol, _atol, _stol,
/// _max_it, -newton_snes_test_jacobian, and the linear solver's -newton_ksp_* and -newton_pc_*
/// (default: a direct solve, MUMPS LU).
///
/// gelx adds, as hooks of that SNES, what it does not provide:
/// - Admissibility, a line-search pre-check: a Newton step that would make the state
///   inadmissible (det F <= 0, or J <= phi0 for a gel, at a quadrature point) is halved until
///   it does not, before any line search evaluates the residual there: the energies are not
///   defined beyond, and PETSc's line searches only cut a step whose residual is Inf at their
///   first trial. Up to -PREFIX_admissible_halvings (8) halvings.
/// - The convergence test of deal.II's step-44, on the residual and on the increment:
///     |R_k| <= max(atol, rtol |R_0|)  and  e_k <= max(atol_increment, rtol_increment |x_k - x_0|)
///   with e_k = |x_k - x_(k-1)| |R_k| / |R_(k-1)| the next increment estimated from the last
///   contraction (Newton's next step is K^-1 R_k, and the last step measured |K^-1|), i.e. the
///   error of x_k, and x_0 the solve's start (the last converged point of a path): the error
///   must be small against what the step changed. A linear problem converges in one iteration,
///   and SNES's default acceptance of a small step alone (snes_stol) is a stagnation failure
///   here, never a convergence.
///   -PREFIX_snes_rtol (1e-10), _atol (1e-12), _stol (1e-14) and _max_it (25) are PETSc's;
///   -PREFIX_rtol_increment (1e-8) and -PREFIX_atol_increment (1e-14) are gelx's.
///   |R| is the norm SNES hands its convergence test: for the bound-constrained types
///   (vinewtonrsls, vinewtonssls) not |R| but the residual's norm on the rows that no bound
///   holds (SNESVIComputeInactiveSetFnorm for vinewtonrsls, at the start and after every line
///   search, PETSc 3.18 src/snes/impls/vi/rs/virs.c): at a solution the rows held at a bound
///   keep the bound's reaction (the contact force), which is no error. |R_0| is the predictor's
///   start, in the system's predictor form (below), the same number for either contact method.
/// - Per-iteration system updates (SNESSetUpdate): NonlinearSystem::commit().
/// - A predictor: the first Newton step of a solve is taken whole (halved only for
///   admissibility) before SNES takes over. It carries a load step's increment, often the
///   increment of prescribed values (NonlinearProblem's lifting), and its residual is not
///   comparable with the one before it, so a decrease test (bt) would cut it to a crawl:
///   measured on the inflated shell, bt shortened every step to 0.1 and did not converge in 25
///   iterations where the whole first step converges in 4. The tolerances refer to the state
///   before it.
///   The step is the system's in its predictor form (NonlinearSystem::set_predicting): for a
///   VI solver the rows that will lie on a bound are prescribed there, which carries a bound's
///   increment into the body. SNES alone projects the start onto the moved bounds and begins
///   from that kinked state, and the plain Newton step of the unbounded residual releases the
///   bounds' reactions: measured on the pyramid, both cycle or fail (demos/pyramid/README.md).
class NewtonSolver
{
public:
  explicit NewtonSolver(MPI_Comm comm, const std::string& prefix = "newton_");
  ~NewtonSolver();
  NewtonSolver(const NewtonSolver&) = delete;
  NewtonSolver& operator=(const NewtonSolver&) = delete;

  /// Solve from the current state of `system`, starting with the predictor; on failure the
  /// state is the last iterate (the caller restores a saved state). A solver serves one system
  /// (its first).
  NewtonReport solve(NonlinearSystem& system);
  /// Solve from the current state, a prediction the caller made from `last_point` (a
  /// continuation's corrector): no predictor; the increment test measures from `last_point`.
  NewtonReport correct(NonlinearSystem& system, Vec last_point);

  /// Bind the solver to `system` and read its options now rather than at the first solve, so
  /// that tolerances a driver sets on snes() hold from the first solve on.
  void bind(NonlinearSystem& system);

  SNES snes() const { return _snes; }
  const std::string& prefix() const { return _prefix; }

  /// What the convergence test and the hooks keep during a solve (public for the C callbacks).
  struct Progress
  {
    NonlinearSystem* system = nullptr;
    Vec x0 = nullptr, x_previous = nullptr, work = nullptr;
    double rtol_increment = 0, atol_increment = 0;
    int admissible_halvings = 0;
    bool predicted = false;  ///< the solve began with the predictor
    bool start_given = false; ///< x0 was set before SNES started (predictor or last point)
    double step_norm = 0; ///< |Y| after the admissibility check, before the line search
    NewtonReport report;
    bool converged = false;
  };

private:
  /// Bind the SNES to `system` (first solve): callbacks, matrices, hooks, options.
  void set_up(NonlinearSystem& system);
  /// The predictor step from _x (see the class comment); false when _x already converged.
  bool predict(NonlinearSystem& system);
  /// SNESSolve from _x and the report.
  NewtonReport run_snes(NonlinearSystem& system);
  /// bind(system) and reset the report.
  void begin(NonlinearSystem& system);
  MPI_Comm _comm;
  std::string _prefix;
  SNES _snes = nullptr;
  bool _bounded = false; ///< a VI type: SNES projects onto bounds
  Mat _A = nullptr;
  Vec _r = nullptr, _x = nullptr;
  Progress _progress;
};

} // namespace gelx
