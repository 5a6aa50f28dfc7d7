#pragma once
/// @file scalar_path.h
/// A path of one unknown x and a load lambda, R(x, lambda) = 0 with R a scalar function: the
/// path drivers' logic checked against closed forms. One rank.

#include <gelx/common/petsc_utils.h>
#include <gelx/systems/system.h>

#include <mpi.h>
#include <petscmat.h>
#include <stdexcept>
#include <vector>

namespace gelx::test
{

class ScalarPath : public gelx::NonlinearSystem
{
public:
  ScalarPath(MPI_Comm comm, double x)
  {
    GELX_PETSC(VecCreateMPI(comm, 1, PETSC_DETERMINE, &_x));
    GELX_PETSC(VecSet(_x, x));
  }
  ~ScalarPath() override { VecDestroy(&_x); }
  ScalarPath(const ScalarPath&) = delete;
  ScalarPath& operator=(const ScalarPath&) = delete;

  /// R and dR/dx at (x, lambda)
  virtual double value(double x, double lambda) = 0;
  virtual double derivative(double x, double lambda) = 0;

  void set_load(double lambda) { _lambda = lambda; }
  double load() const { return _lambda; }
  double x() const
  {
    const PetscScalar* v;
    GELX_PETSC(VecGetArrayRead(_x, &v));
    const double value = v[0];
    GELX_PETSC(VecRestoreArrayRead(_x, &v));
    return value;
  }

  Vec unknowns() override { return _x; }
  void unknowns_changed() override {}
  void residual(Vec r) override
  {
    GELX_PETSC(VecSetValue(r, 0, value(x(), _lambda), INSERT_VALUES));
    GELX_PETSC(VecAssemblyBegin(r));
    GELX_PETSC(VecAssemblyEnd(r));
  }
  void tangent(Mat A) override
  {
    GELX_PETSC(MatSetValue(A, 0, 0, derivative(x(), _lambda), INSERT_VALUES));
    GELX_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    GELX_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  Vec create_vector() const override
  {
    Vec v;
    GELX_PETSC(VecDuplicate(_x, &v));
    return v;
  }
  Mat create_matrix() const override
  {
    MPI_Comm comm;
    GELX_PETSC(PetscObjectGetComm(reinterpret_cast<PetscObject>(_x), &comm));
    Mat A;
    GELX_PETSC(MatCreateAIJ(comm, 1, 1, PETSC_DETERMINE, PETSC_DETERMINE, 1, nullptr, 0,
                            nullptr, &A));
    return A;
  }
  std::vector<PetscInt> prescribed_rows() const override { return {}; }
  gelx::NonlinearProblem& problem() override
  {
    throw std::logic_error("a scalar path has no finite-element problem");
  }
  const std::vector<PetscInt>& unknown_of_problem_dof() const override
  {
    throw std::logic_error("a scalar path has no finite-element problem");
  }

private:
  Vec _x;
  double _lambda = 0;
};

} // namespace gelx::test
