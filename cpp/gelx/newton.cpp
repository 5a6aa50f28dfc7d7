#include "newton.h"
#include "petsc_utils.h"

#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>

namespace gelx
{

NewtonSolver::NewtonSolver(MPI_Comm comm, const std::string& prefix)
    : _comm(comm), _prefix(prefix)
{
  _ksp = create_linear_solver(comm, prefix);
}

NewtonSolver::~NewtonSolver()
{
  KSPDestroy(&_ksp);
  MatDestroy(&_A);
  VecDestroy(&_r);
  VecDestroy(&_du);
  VecDestroy(&_x_trial_base);
  VecDestroy(&_x_start);
}

NewtonReport NewtonSolver::solve(NonlinearSystem& system)
{
  const double rtol = real_option(_prefix, "rtol", 1e-10);
  const double atol = real_option(_prefix, "atol", 1e-12);
  // 1e-8: the solution to about half the digits the residual test asks for (e.g. a residual
  // reduced by 1e-10 with a condition number ~1e2 leaves an error of ~1e-8 of the change)
  const double rtol_increment = real_option(_prefix, "rtol_increment", 1e-8);
  const double atol_increment = real_option(_prefix, "atol_increment", 1e-14);
  const double stol = real_option(_prefix, "stol", 1e-14);
  const int max_it = int_option(_prefix, "max_it", 25);
  const int max_backtracks = int_option(_prefix, "max_backtracks", 8);
  const std::string linesearch = string_option(_prefix, "linesearch", "bt");
  if (linesearch != "bt" && linesearch != "basic")
    throw std::runtime_error("-" + _prefix + "linesearch must be bt or basic, not " + linesearch);
  const bool monitor = int_option(_prefix, "monitor", 1) != 0
                       && dolfinx::MPI::rank(_comm) == 0;

  Vec x = system.unknowns();
  if (!_A)
  {
    _A = system.create_matrix();
    _r = system.create_vector();
    _du = system.create_vector();
    _x_trial_base = system.create_vector();
    _x_start = system.create_vector();
  }
  GELX_PETSC(VecCopy(x, _x_start));

  NewtonReport report;
  auto residual_norm = [&]()
  {
    system.residual(_r);
    PetscReal n;
    GELX_PETSC(VecNorm(_r, NORM_2, &n));
    return static_cast<double>(n);
  };

  double r_norm = residual_norm();
  report.residual0 = r_norm;
  report.residual_history.push_back(r_norm);
  if (monitor)
    std::printf("    %3s  %-11s %-11s %-11s %-7s %s\n", "it", "|R|", "|R|/|R0|", "|du|", "step",
                "ksp");
  if (monitor)
    std::printf("    %3d  %-11.4e %-11.4e\n", 0, r_norm, 1.0);
  if (!std::isfinite(r_norm))
  {
    report.reason = "residual is not finite at the initial iterate";
    return report;
  }

  const double residual_tolerance = std::max(atol, rtol * report.residual0);
  double error_estimate = 0; // no step taken yet: u_0 is what the residual test judges
  for (int it = 1;; ++it)
  {
    if (r_norm <= residual_tolerance)
    {
      GELX_PETSC(VecAXPY(_x_start, -1.0, x)); // u_0 - u_k
      PetscReal change;
      GELX_PETSC(VecNorm(_x_start, NORM_2, &change));
      GELX_PETSC(VecAXPY(_x_start, 1.0, x));
      if (error_estimate <= std::max(atol_increment, rtol_increment * change))
      {
        report.converged = true;
        report.reason = "residual and increment tolerances";
        break;
      }
    }
    if (it > max_it)
    {
      report.reason = "no convergence in " + std::to_string(max_it) + " iterations";
      break;
    }

    // Newton direction: K du = -R
    system.tangent(_A);
    GELX_PETSC(KSPSetOperators(_ksp, _A, _A));
    GELX_PETSC(KSPSolve(_ksp, _r, _du));
    KSPConvergedReason ksp_reason;
    GELX_PETSC(KSPGetConvergedReason(_ksp, &ksp_reason));
    PetscInt ksp_its;
    GELX_PETSC(KSPGetIterationNumber(_ksp, &ksp_its));
    report.linear_iterations += ksp_its;
    if (ksp_reason < 0)
    {
      report.reason = std::string("linear solver failed: ") + KSPConvergedReasons[ksp_reason];
      break;
    }
    GELX_PETSC(VecScale(_du, -1.0));

    // Line search on the step length a
    GELX_PETSC(VecCopy(x, _x_trial_base));
    double step = 1.0, trial_norm = NAN;
    bool accepted = false;
    for (int k = 0; k <= max_backtracks; ++k, step *= 0.5)
    {
      GELX_PETSC(VecWAXPY(x, step, _du, _x_trial_base));
      system.unknowns_changed();
      if (k > 0)
        ++report.backtracks;
      if (!system.admissible())
        continue;
      trial_norm = residual_norm();
      if (!std::isfinite(trial_norm))
        continue;
      // The first correction carries the increment of the Dirichlet values (see
      // NonlinearProblem): its residual is not comparable with the lifted one before it.
      if (linesearch == "basic" || it == 1 || trial_norm <= (1 - 1e-4 * step) * r_norm)
      {
        accepted = true;
        break;
      }
    }
    PetscReal du_norm, x_norm;
    GELX_PETSC(VecNorm(_du, NORM_2, &du_norm));
    GELX_PETSC(VecNorm(x, NORM_2, &x_norm));
    report.iterations = it;
    if (monitor)
      std::printf("    %3d  %-11.4e %-11.4e %-11.4e %-7.4g %d\n", it, trial_norm,
                  trial_norm / report.residual0, du_norm, accepted ? step : 0.0, (int)ksp_its);
    if (!accepted)
    {
      report.reason = "line search found no admissible decrease";
      break;
    }
    error_estimate = step * du_norm * trial_norm / r_norm;
    r_norm = trial_norm;
    report.residual_history.push_back(r_norm);
    if (step * du_norm <= stol * x_norm && r_norm > residual_tolerance)
    {
      report.reason = "stagnated: the step fell below stol |u| before |R| reached its tolerance";
      break;
    }
  }
  report.residual = r_norm;
  report.error_estimate = error_estimate;
  return report;
}

} // namespace gelx
