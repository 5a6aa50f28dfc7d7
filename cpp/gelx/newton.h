#pragma once
/// @file newton.h
/// Newton's method with a backtracking line search that also rejects inadmissible iterates.

#include "problem.h"
#include <mpi.h>
#include <petscksp.h>
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
  int backtracks = 0;
  double residual0 = 0;  ///< |R| at the start
  double residual = 0;   ///< |R| at the end
  double error_estimate = 0; ///< estimated |u - u_exact| at the end (see NewtonSolver)
  std::string reason;    ///< why it stopped
  /// |R| at the start and after each accepted iteration (for convergence-rate checks)
  std::vector<double> residual_history;
};

/// Newton's method for R(u) = 0.
///
/// Each iteration solves K du = -R with a PETSc KSP, then tries u + a du with a = 1, 1/2, ...:
/// a trial is rejected when its residual is not finite, when det F <= 0 somewhere
/// (NonlinearSystem::admissible) or, with the `bt` line search, when |R| does not decrease
/// (Armijo, c = 1e-4; not tested on the first correction, which carries the increment of the
/// prescribed values).
///
/// Convergence needs both tests of deal.II's step-44, on the residual and on the increment:
///   |R_k| <= max(atol, rtol |R_0|)   and   e_k <= max(atol_increment, rtol_increment |u_k - u_0|),
/// where e_k = |a_k du_k| |R_k| / |R_(k-1)| estimates the next increment, i.e. the error of u_k:
/// Newton's next step is K^-1 R_k, and the last step measured |K^-1| as |a_k du_k| / |R_(k-1)|.
/// Using the estimate instead of an extra iteration's increment proves a linear solve converged
/// in one iteration, as it is. A solve whose step falls below stol |u| before both tests pass
/// has stagnated: that is a failure, never a convergence.
///
/// Options, prefix `newton_` by default (`-newton_rtol 1e-10` ...): rtol, atol, rtol_increment,
/// atol_increment, stol, max_it, linesearch (bt|basic), max_backtracks, monitor (print the
/// per-iteration table; default on rank 0, `-newton_monitor 0` silences it). The linear solver
/// reads the same prefix (`-newton_ksp_type`, `-newton_pc_type`, ...); its default is a direct
/// solve with MUMPS.
class NewtonSolver
{
public:
  explicit NewtonSolver(MPI_Comm comm, const std::string& prefix = "newton_");
  ~NewtonSolver();
  NewtonSolver(const NewtonSolver&) = delete;
  NewtonSolver& operator=(const NewtonSolver&) = delete;

  /// Solve from the current unknowns of `system`; on failure the unknowns are left at the last
  /// iterate (the caller restores a saved state).
  NewtonReport solve(NonlinearSystem& system);

  KSP ksp() const { return _ksp; }
  const std::string& prefix() const { return _prefix; }

private:
  MPI_Comm _comm;
  std::string _prefix;
  KSP _ksp = nullptr;
  Mat _A = nullptr;
  Vec _r = nullptr, _du = nullptr, _x_trial_base = nullptr, _x_start = nullptr;
};

} // namespace gelx
