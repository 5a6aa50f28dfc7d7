#include <gelx/solvers/adjoint.h>

#include <gelx/common/petsc_utils.h>
#include <gelx/solvers/path.h>
#include <gelx/systems/mixed.h>
#include <gelx/systems/problem.h>

#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/petsc.h>

namespace gelx
{

AdjointGradient::AdjointGradient(
    NonlinearSystem& system, std::shared_ptr<const dolfinx::fem::Function<double>> design,
    std::shared_ptr<const dolfinx::fem::Form<double>> residual_d_design, Objective objective,
    const std::string& prefix)
    : _system(system), _design(std::move(design)),
      _residual_d_design(std::move(residual_d_design)), _objective(std::move(objective))
{
  if (!_objective.value || !_objective.d_state)
    throw std::invalid_argument("AdjointGradient: the objective needs its value and dJ/du");
  _ksp = create_linear_solver(_system.problem().u()->function_space()->mesh()->comm(), prefix);
  prepare_linear_solver(_ksp, _system);
  _tangent = _system.create_matrix();
  _residual_d_design_matrix = dolfinx::fem::petsc::create_matrix(*_residual_d_design);
}

AdjointGradient::~AdjointGradient()
{
  KSPDestroy(&_ksp);
  MatDestroy(&_tangent);
  MatDestroy(&_residual_d_design_matrix);
}

double AdjointGradient::value() const
{
  return assemble_global_scalar(*_objective.value)
         + (_objective.sampled_value ? _objective.sampled_value() : 0.0);
}

Vec AdjointGradient::create_design_vector() const
{
  const auto& space = *_design->function_space();
  return dolfinx::la::petsc::create_vector(*space.dofmap()->index_map,
                                           space.dofmap()->index_map_bs());
}

void AdjointGradient::gradient(Vec g)
{
  NonlinearProblem& problem = _system.problem();
  const OwnedVec dJ_du(problem.create_vector()), rhs(_system.create_vector()),
      lambda(_system.create_vector()), lambda_problem(problem.create_vector());

  // The adjoint: K^T lambda = P^T dJ/du at the equilibrium
  assemble_global_vector(*_objective.d_state, dJ_du.get());
  if (_objective.add_sampled_d_state)
    _objective.add_sampled_d_state(dJ_du.get());
  _system.restrict_vector(dJ_du.get(), rhs.get());
  _system.tangent(_tangent);
  GELX_PETSC(KSPSetOperators(_ksp, _tangent, _tangent));
  GELX_PETSC(KSPSolveTranspose(_ksp, rhs.get(), lambda.get()));
  KSPConvergedReason reason;
  GELX_PETSC(KSPGetConvergedReason(_ksp, &reason));
  PetscInt iterations;
  GELX_PETSC(KSPGetIterationNumber(_ksp, &iterations));
  _iterations = iterations;
  if (reason < 0)
    throw ConvergenceError("the adjoint solve failed (KSP reason "
                           + std::to_string(int(reason)) + ")");

  // Prescribed rows hold u_i = g_i, which does not depend on the design
  const std::vector<PetscInt> prescribed = _system.prescribed_rows();
  PetscScalar* values;
  GELX_PETSC(VecGetArray(lambda.get(), &values));
  for (PetscInt row : prescribed)
    values[row] = 0;
  GELX_PETSC(VecRestoreArray(lambda.get(), &values));
  _system.prolong_vector(lambda.get(), lambda_problem.get());

  // dJ/ds = dJ/ds|_u - (dR/ds)^T lambda
  GELX_PETSC(MatZeroEntries(_residual_d_design_matrix));
  dolfinx::fem::assemble_matrix(
      dolfinx::la::petsc::Matrix::set_block_fn(_residual_d_design_matrix, ADD_VALUES),
      *_residual_d_design, {});
  GELX_PETSC(MatAssemblyBegin(_residual_d_design_matrix, MAT_FINAL_ASSEMBLY));
  GELX_PETSC(MatAssemblyEnd(_residual_d_design_matrix, MAT_FINAL_ASSEMBLY));
  GELX_PETSC(MatMultTranspose(_residual_d_design_matrix, lambda_problem.get(), g));
  GELX_PETSC(VecScale(g, -1.0));
  if (_objective.d_design)
  {
    const OwnedVec dJ_ds(copy_of(g));
    assemble_global_vector(*_objective.d_design, dJ_ds.get());
    GELX_PETSC(VecAXPY(g, 1.0, dJ_ds.get()));
  }
}

} // namespace gelx
