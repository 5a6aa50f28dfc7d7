#include <gelx/solvers/buckling.h>
#include <gelx/solvers/dynamics.h>
#include <gelx/common/timing.h>
#include <gelx/io/parameters.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/systems/problem.h>

#include <algorithm>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/la/petsc.h>
#include <slepceps.h>

namespace gelx
{
namespace
{
/// The owned entries of v as a Function on `space`, scaled to largest component 1.
std::shared_ptr<dolfinx::fem::Function<double>>
normalised_function(Vec v, std::shared_ptr<const dolfinx::fem::FunctionSpace> space,
                    MPI_Comm comm)
{
  auto f = std::make_shared<dolfinx::fem::Function<double>>(space);
  const PetscScalar* a;
  GELX_PETSC(VecGetArrayRead(v, &a));
  const std::int32_t n
      = space->dofmap()->index_map->size_local() * space->dofmap()->index_map_bs();
  std::copy_n(a, n, f->x()->mutable_array().begin());
  GELX_PETSC(VecRestoreArrayRead(v, &a));
  f->x()->scatter_fwd();
  double local_max = 0, largest;
  for (std::int32_t k = 0; k < n; ++k)
    local_max = std::max(local_max, std::abs(f->x()->array()[k]));
  MPI_Allreduce(&local_max, &largest, 1, MPI_DOUBLE, MPI_MAX, comm);
  for (double& x : f->x()->mutable_array())
    x /= largest;
  return f;
}
} // namespace

LinearBuckling::LinearBuckling(MPI_Comm comm, const std::string& prefix)
    : _comm(comm), _prefix(prefix)
{
  set_default_option(prefix, "st_ksp_type", "preonly");
  set_default_option(prefix, "st_pc_type", "lu");
  set_default_option(prefix, "st_pc_factor_mat_solver_type", "mumps");
}

std::vector<BucklingMode>
LinearBuckling::solve(Mat K, Mat K_perturbed, int num_modes,
                      std::shared_ptr<const dolfinx::fem::FunctionSpace> space)
{
  // -K_D = K - K_perturbed; Dirichlet rows cancel (identity in both)
  Mat minus_KD;
  GELX_PETSC(MatDuplicate(K, MAT_COPY_VALUES, &minus_KD));
  GELX_PETSC(MatAXPY(minus_KD, -1.0, K_perturbed, DIFFERENT_NONZERO_PATTERN));

  EPS eps;
  GELX_PETSC(EPSCreate(_comm, &eps));
  GELX_PETSC(EPSSetOptionsPrefix(eps, _prefix.c_str()));
  GELX_PETSC(EPSSetOperators(eps, minus_KD, K));
  GELX_PETSC(EPSSetProblemType(eps, EPS_GHEP));
  GELX_PETSC(EPSSetWhichEigenpairs(eps, EPS_LARGEST_REAL));
  GELX_PETSC(EPSSetDimensions(eps, num_modes, PETSC_DEFAULT, PETSC_DEFAULT));
  GELX_PETSC(EPSSetTolerances(eps, 1e-10, 500));
  GELX_PETSC(EPSSetFromOptions(eps));
  GELX_PETSC(EPSSolve(eps));
  PetscInt converged;
  GELX_PETSC(EPSGetConverged(eps, &converged));

  std::vector<BucklingMode> modes;
  Vec v;
  GELX_PETSC(MatCreateVecs(K, &v, nullptr));
  for (PetscInt i = 0; i < converged; ++i)
  {
    PetscScalar theta;
    GELX_PETSC(EPSGetEigenpair(eps, i, &theta, nullptr, v, nullptr));
    if (theta <= 0) // compression-free modes: no buckling under this load direction
      continue;
    auto shape = normalised_function(v, space, _comm);
    shape->name = "mode_" + std::to_string(modes.size() + 1);
    modes.push_back({1.0 / theta, shape});
  }
  VecDestroy(&v);
  EPSDestroy(&eps);
  MatDestroy(&minus_KD);
  std::sort(modes.begin(), modes.end(),
            [](auto& a, auto& b) { return a.load_factor < b.load_factor; });
  if (static_cast<int>(modes.size()) > num_modes)
    modes.resize(num_modes);
  return modes;
}

BucklingMode lowest_tangent_eigenpair(MPI_Comm comm, Mat K,
                                      std::shared_ptr<const dolfinx::fem::FunctionSpace> space)
{
  const std::string prefix = "stability_";
  set_default_option(prefix, "st_ksp_type", "preonly");
  set_default_option(prefix, "st_pc_type", "lu");
  set_default_option(prefix, "st_pc_factor_mat_solver_type", "mumps");
  EPS eps;
  GELX_PETSC(EPSCreate(comm, &eps));
  GELX_PETSC(EPSSetOptionsPrefix(eps, prefix.c_str()));
  GELX_PETSC(EPSSetOperators(eps, K, nullptr));
  GELX_PETSC(EPSSetProblemType(eps, EPS_NHEP));
  GELX_PETSC(EPSSetTarget(eps, 0.0));
  GELX_PETSC(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  ST st;
  GELX_PETSC(EPSGetST(eps, &st));
  GELX_PETSC(STSetType(st, STSINVERT));
  GELX_PETSC(EPSSetTolerances(eps, 1e-10, 500));
  GELX_PETSC(EPSSetFromOptions(eps));
  GELX_PETSC(EPSSolve(eps));
  PetscInt converged;
  GELX_PETSC(EPSGetConverged(eps, &converged));
  if (converged < 1)
  {
    EPSDestroy(&eps);
    throw std::runtime_error("the lowest eigenvalue of the tangent did not converge");
  }
  Vec v;
  GELX_PETSC(MatCreateVecs(K, &v, nullptr));
  PetscScalar value;
  GELX_PETSC(EPSGetEigenpair(eps, 0, &value, nullptr, v, nullptr));
  BucklingMode pair{value, normalised_function(v, space, comm)};
  pair.shape->name = "stability_mode";
  VecDestroy(&v);
  EPSDestroy(&eps);
  return pair;
}

std::vector<BucklingMode> vibration_modes(MPI_Comm comm, NonlinearSystem& system,
                                          const dolfinx::fem::Form<double>& mass_form,
                                          int num_modes)
{
  // -K_D v = theta K v with K_D = -M: M v = theta K v, theta = 1 / omega^2 largest first.
  // M without the prescribed rows and columns, whose tangent rows are the identity: their
  // theta is 0
  Mat K = system.create_matrix();
  system.tangent(K);
  Mat M = assemble_system_mass(system, mass_form, "vibration_modes");
  PetscInt first;
  GELX_PETSC(MatGetOwnershipRange(M, &first, nullptr));
  std::vector<PetscInt> rows = system.prescribed_rows();
  for (PetscInt& r : rows)
    r += first;
  GELX_PETSC(MatZeroRowsColumns(M, PetscInt(rows.size()), rows.data(), 0.0, nullptr, nullptr));
  Mat K_minus_M;
  GELX_PETSC(MatDuplicate(K, MAT_COPY_VALUES, &K_minus_M));
  GELX_PETSC(MatAXPY(K_minus_M, -1.0, M, SUBSET_NONZERO_PATTERN));
  std::vector<BucklingMode> modes;
  try
  {
    modes = LinearBuckling(comm, "vibration_")
                .solve(K, K_minus_M, num_modes, system.problem().u()->function_space());
  }
  catch (...)
  {
    MatDestroy(&K);
    MatDestroy(&M);
    MatDestroy(&K_minus_M);
    throw;
  }
  MatDestroy(&K);
  MatDestroy(&M);
  MatDestroy(&K_minus_M);
  return modes;
}

void default_to_symmetric_factorisation(const std::string& prefix)
{
  set_default_option(prefix, "ksp_type", "preonly");
  set_default_option(prefix, "pc_type", "cholesky");
  set_default_option(prefix, "pc_factor_mat_solver_type", "mumps");
  set_default_option(prefix, "mat_mumps_icntl_13", "1");
}

int factored_negative_eigenvalues(KSP ksp)
{
  PC pc;
  GELX_PETSC(KSPGetPC(ksp, &pc));
  PetscBool cholesky;
  GELX_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCCHOLESKY, &cholesky));
  const char* prefix = nullptr;
  GELX_PETSC(KSPGetOptionsPrefix(ksp, &prefix));
  const std::string solver = std::string("-") + (prefix ? prefix : "");
  if (!cholesky)
    throw InputError("the inertia of the tangent needs an LDL^T factorisation: " + solver
                     + "pc_type cholesky " + solver + "pc_factor_mat_solver_type mumps");
  Mat factor;
  GELX_PETSC(PCFactorGetMatrix(pc, &factor));
  // The zero count would need MUMPS's null-pivot detection (ICNTL(24)), which changes the
  // factorisation; a zero pivot of a tangent is an event of measure zero along a path
  PetscInt negative;
  GELX_PETSC(MatGetInertia(factor, &negative, nullptr, nullptr));
  return static_cast<int>(negative);
}

int negative_eigenvalues(MPI_Comm comm, Mat K)
{
  TimedStage timing("stability");
  const std::string prefix = "inertia_";
  default_to_symmetric_factorisation(prefix);
  KSP ksp;
  GELX_PETSC(KSPCreate(comm, &ksp));
  GELX_PETSC(KSPSetOptionsPrefix(ksp, prefix.c_str()));
  GELX_PETSC(KSPSetFromOptions(ksp));
  GELX_PETSC(KSPSetOperators(ksp, K, K));
  const PetscErrorCode ierr = KSPSetUp(ksp);
  int negative = 0;
  if (ierr == 0)
    negative = factored_negative_eigenvalues(ksp);
  KSPDestroy(&ksp);
  GELX_PETSC(ierr);
  return negative;
}

int tangent_negative_eigenvalues(MPI_Comm comm, NonlinearSystem& system)
{
  // The tangent's assembly is part of the stability count, not of its caller's stage
  TimedStage timing("stability");
  Mat K = system.create_matrix();
  system.tangent(K);
  const int negative = negative_eigenvalues(comm, K);
  MatDestroy(&K);
  return negative;
}

void seed_imperfection(dolfinx::mesh::Mesh& mesh, const std::vector<BucklingMode>& modes,
                       const std::vector<double>& amplitudes)
{
  if (modes.size() != amplitudes.size())
    throw std::runtime_error("seed_imperfection: one amplitude per mode is needed");
  if (mesh.geometry().cmap().degree() != 1)
    throw std::runtime_error("seed_imperfection: the mesh geometry must be linear");
  const auto& x_dofmap = mesh.geometry().dofmap();
  std::span<double> x = mesh.geometry().x();
  const int tdim = mesh.topology().dim();
  const std::int32_t num_cells = mesh.topology().index_map(tdim)->size_local()
                                 + mesh.topology().index_map(tdim)->num_ghosts();
  // Each node gets the mode's value at that vertex: vertex dofs of a Lagrange space come
  // first in a cell's dof list, in the order of the cell's vertices.
  std::vector<double> shift(x.size(), 0.0);
  std::vector<bool> done(x.size() / 3, false);
  for (std::int32_t c = 0; c < num_cells; ++c)
  {
    auto nodes = x_dofmap.links(c);
    for (std::size_t i = 0; i < nodes.size(); ++i)
    {
      if (done[nodes[i]])
        continue;
      done[nodes[i]] = true;
      for (std::size_t m = 0; m < modes.size(); ++m)
      {
        const auto& f = *modes[m].shape;
        const int bs = f.function_space()->dofmap()->bs();
        const std::int32_t dof = f.function_space()->dofmap()->cell_dofs(c)[i];
        for (int k = 0; k < bs; ++k)
          shift[3 * nodes[i] + k] += amplitudes[m] * f.x()->array()[bs * dof + k];
      }
    }
  }
  for (std::size_t k = 0; k < x.size(); ++k)
    x[k] += shift[k];
}

} // namespace gelx
