#pragma once
/// @file petsc_utils.h
/// PETSc error codes as exceptions, and defaults in the options database that never override
/// what the user passed.

#include <exception>
#include <nlohmann/json.hpp>
#include <petscksp.h>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace gelx
{

/// Throws std::runtime_error naming the PETSc call when `ierr` is non-zero.
void petsc_check(PetscErrorCode ierr, const char* call);

/// Wrap a PETSc call: GELX_PETSC(VecNorm(x, NORM_2, &n));
#define GELX_PETSC(call) ::gelx::petsc_check((call), #call)

/// Run the body of a PETSc callback: PETSc is C and must not be unwound through, so an
/// exception becomes an error code and is kept in `error` for the caller of the PETSc solve
/// to rethrow.
template <typename Body>
PetscErrorCode guarded_callback(std::exception_ptr& error, Body&& body)
{
  try
  {
    body();
    return 0;
  }
  catch (...)
  {
    error = std::current_exception();
    return PETSC_ERR_USER;
  }
}

/// Run a PETSc solve (`solve()` returns its error code: TSSolve, SNESSolve) whose callbacks are
/// guarded_callback bodies keeping their exception in `error` (cleared first): PETSc's error
/// handler is quiet meanwhile, so that an error is one line, not PETSc's trace of every frame
/// it passed through; then the callback's exception is rethrown, or PETSc's error thrown.
template <typename Solve>
void solve_guarded(std::exception_ptr& error, Solve&& solve)
{
  error = nullptr;
  GELX_PETSC(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  const PetscErrorCode ierr = solve();
  GELX_PETSC(PetscPopErrorHandler());
  if (error)
    std::rethrow_exception(error);
  GELX_PETSC(ierr);
}

/// Set option `-<prefix><name>` to `value` unless it is already set (on the command line,
/// in PETSC_OPTIONS or an options file), so that scene defaults never override the user.
void set_default_option(const std::string& prefix, const std::string& name,
                        const std::string& value = "");
/// The same for each (name, value) of `options`: a solver's defaults as one table.
void set_default_options(const std::string& prefix,
                         const std::vector<std::pair<std::string, std::string>>& options);

/// Whether set_default_option set `option` (its name without the dash): a default that a
/// user's other choices may leave unread (MUMPS for an iterative solve) is no mistake.
bool is_default_option(const std::string& option);

/// Every option in PETSc's database, as {name: value} (value null for a bare flag): the
/// solver choices in effect, the scene's defaults included, read back rather than retyped.
nlohmann::json petsc_options();

/// The options no solver object read (a mistyped or misplaced option) but the defaults, as
/// "-a, -b"; "" when none. At the end of a run: every object has had its chance.
std::string unused_options();
/// The same, during a run, for the options of the solver objects that have read theirs: an
/// unread `-PREFIX_CLASS_...` (CLASS one of snes, ksp, pc, mat, ts, eps, st, tao) where some
/// other `-PREFIX_CLASS_...` option was read. An object reads its options when it is set up
/// and in its first solve (MUMPS' at the first factorisation), so after a completed step an
/// unread one under its prefix is misspelt (`-newton_snes_rtoll`); the options of objects not
/// made yet, and the views and converged reasons PETSc reads at the end of a solve, wait for
/// unused_options().
std::string unread_options_of_set_up_solvers();
/// Throw InputError naming every option under `prefix` that the solver object of that prefix
/// should have read when it read its options (SNESSetFromOptions, TSSetFromOptions: the
/// `snes_`, `ksp_`, `pc_` and `ts_` options of it, its line search and its linear solver)
/// and did not: a misspelt option is refused before the object's first solve, so before the
/// first step. Left to unread_options_of_set_up_solvers(), after the first step: MUMPS'
/// `mat_mumps_` options (read at the first factorisation), the split solvers of `fieldsplit`
/// (made at the preconditioner's set-up), the views and converged reasons (read after a
/// solve) and `_test_` options (read when the test runs).
void refuse_unread_options_of(const std::string& prefix);

/// The defaults of the linear solver with options `prefix`, from the named option set
/// `-<prefix>linear_solver` (each option of a set is a default: any one can be overridden):
/// - `direct` (the default): MUMPS LU. Robust, and fastest up to a few 10^4 unknowns; its time
///   and memory grow far faster than the number of unknowns N.
/// - `amg`: GMRES preconditioned by PETSc's smoothed-aggregation AMG (GAMG) with the rigid-body
///   near-nullspace (NonlinearProblem::create_matrix): for displacement-only laws (compressible
///   solids, the gel).
/// - `fieldsplit`: for mixed displacement-pressure spaces (P2-P1, Q2-Q1, Q1-P0): FGMRES with a
///   block (Schur complement) preconditioner, GAMG with the rigid-body modes on the displacement
///   block and Jacobi on PETSc's selfp approximation of the pressure Schur complement
///   (A_pp - A_pu diag(A_uu)^-1 A_up); `-<prefix>pc_fieldsplit_schur_precondition user` uses
///   the pressure mass matrix over G instead, where the problem has one. The fields `u` and
///   `p` (options -<prefix>fieldsplit_u_... and _p_...) are defined by
///   define_displacement_pressure_fields (mixed.h).
/// The Krylov sets solve to -<prefix>ksp_rtol 1e-10, which leaves Newton's quadratic
/// convergence and the direct solve's answer to the Newton tolerance; -<prefix>snes_ksp_ew
/// (Eisenstat-Walker) adapts it instead. Throws InputError for an unknown set.
void set_linear_solver_defaults(const std::string& prefix);

/// A KSP reading options with `prefix`, defaults from set_linear_solver_defaults. A solver of
/// a NonlinearSystem then prepares it for that system (prepare_linear_solver, systems/mixed.h).
KSP create_linear_solver(MPI_Comm comm, const std::string& prefix);

/// After a solve of `ksp` whose factorisation failed (a singular tangent at a limit point, a
/// non-finite one at an inadmissible trial state), forget that factorisation, so that the
/// next solve sets the factor up afresh. PETSc 3.18's MUMPS interface skips every numeric
/// factorisation while its last status is an error (MatFactorNumeric_MUMPS returns at once
/// when INFOG(1) < 0): without this, every retry of a failed step at a smaller size failed
/// too (seen on the inflation with constraints at 2 ranks: 17 cut-backs, all
/// DIVERGED_PC_FAILED). Acts on LU and Cholesky preconditioners (a split's fields, defined
/// once, would not survive a reset). A KSPSetPostSolve hook, not installed where the KSP has
/// one already (SNES's Eisenstat-Walker, -snes_ksp_ew). prepare_linear_solver installs it on
/// every solver of a system.
void refactor_after_failure(KSP ksp);

/// Value of a real option `-<prefix><name>`, or `fallback` when unset.
double real_option(const std::string& prefix, const std::string& name, double fallback);

/// Value of an integer option `-<prefix><name>`, or `fallback` when unset.
int int_option(const std::string& prefix, const std::string& name, int fallback);

/// Value of a string option `-<prefix><name>`, or `fallback` when unset.
std::string string_option(const std::string& prefix, const std::string& name,
                          const std::string& fallback);

/// Value of an option `-<prefix><name>` that names one of `choices`, or `fallback` when
/// unset. Throws InputError, naming the choices, for any other value.
std::string choice_option(const std::string& prefix, const std::string& name,
                          const std::string& fallback, const std::vector<std::string>& choices);

} // namespace gelx
