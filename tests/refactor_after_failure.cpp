// A failed factorisation does not poison the solves after it (gelx::refactor_after_failure).
//
// PETSc 3.18's MUMPS interface skips every numeric factorisation while the last one's status
// is an error (MatFactorNumeric_MUMPS returns at once when INFOG(1) < 0), so after one singular
// tangent (a limit point hit exactly, a trial state past admissibility) every later solve with
// the same KSP failed as well, and a step retried at any smaller size could not pass: the
// inflation with constraints at 2 ranks stopped after 17 cut-backs, all DIVERGED_PC_FAILED.
// Here a KSP from gelx::create_linear_solver (MUMPS LU), with the hook, first meets a diagonal
// matrix with a zero on its diagonal (MUMPS reports it singular), then the same matrix with
// that entry set to 2: the second solve must converge to the exact x = b / diag. At 1 and 2
// ranks (the zero on the last rank).

#include "support.h"

#include <gelx/common/petsc_utils.h>

#include <cmath>
#include <petscksp.h>
#include <string>

int main(int argc, char* argv[])
{
  return gelx::test::run_checks(
      argc, argv,
      [](MPI_Comm comm, gelx::test::Checks& checks)
      {
        constexpr PetscInt rows_per_rank = 5;
        Mat A;
        GELX_PETSC(MatCreateAIJ(comm, rows_per_rank, rows_per_rank, PETSC_DETERMINE,
                                PETSC_DETERMINE, 1, nullptr, 0, nullptr, &A));
        PetscInt first, end, size;
        GELX_PETSC(MatGetOwnershipRange(A, &first, &end));
        GELX_PETSC(MatGetSize(A, &size, nullptr));
        const PetscInt singular_row = size - 1;
        const auto set_diagonal = [&](double at_singular_row)
        {
          for (PetscInt i = first; i < end; ++i)
            GELX_PETSC(MatSetValue(A, i, i, i == singular_row ? at_singular_row : 1.0 + i,
                                   INSERT_VALUES));
          GELX_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
          GELX_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
        };
        Vec b, x;
        GELX_PETSC(MatCreateVecs(A, &x, &b));
        GELX_PETSC(VecSet(b, 1.0));
        KSP ksp = gelx::create_linear_solver(comm, "refactor_");
        gelx::refactor_after_failure(ksp);
        const auto solve = [&]
        {
          GELX_PETSC(KSPSetOperators(ksp, A, A));
          GELX_PETSC(KSPSolve(ksp, b, x));
          KSPConvergedReason reason;
          GELX_PETSC(KSPGetConvergedReason(ksp, &reason));
          return reason;
        };

        set_diagonal(0.0);
        const KSPConvergedReason first_reason = solve();
        checks.require(std::string("the singular matrix: ") + KSPConvergedReasons[first_reason]
                           + " (DIVERGED_PC_FAILED expected)",
                       first_reason == KSP_DIVERGED_PC_FAILED);

        set_diagonal(2.0);
        const KSPConvergedReason second_reason = solve();
        checks.require(std::string("the same matrix made regular: ")
                           + KSPConvergedReasons[second_reason] + " (converged expected)",
                       second_reason > 0);
        // x = b / diag exactly, up to round-off
        const PetscScalar* values;
        GELX_PETSC(VecGetArrayRead(x, &values));
        double error = 0;
        for (PetscInt i = first; i < end; ++i)
          error = std::max(error, std::abs(values[i - first]
                                           - 1.0 / (i == singular_row ? 2.0 : 1.0 + i)));
        GELX_PETSC(VecRestoreArrayRead(x, &values));
        MPI_Allreduce(MPI_IN_PLACE, &error, 1, MPI_DOUBLE, MPI_MAX, comm);
        checks.absolute("the regular matrix: max |x - b / diag|", error, 0, 1e-14);
        KSPDestroy(&ksp);
        VecDestroy(&x);
        VecDestroy(&b);
        MatDestroy(&A);
      });
}
