#include <gelx/systems/problem.h>
#include <gelx/solvers/path.h>
#include <gelx/common/petsc_utils.h>

#include <algorithm>
#include <cmath>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/Vector.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/Mesh.h>
#include <limits>
#include <numeric>
#include <xtensor/xtensor.hpp>

namespace gelx
{

namespace
{
/// Throws unless the system's unknowns are its problem's dofs, in order: then a problem's
/// operator or vector is one of the system as it is. `system_vector` is one of the system's
/// vectors (passed in rather than created: vectors are restricted once per solve).
void require_problem_layout(const NonlinearSystem& system, Vec system_vector)
{
  const auto& of_problem = system.unknown_of_problem_dof();
  const bool identity = std::all_of(of_problem.begin(), of_problem.end(),
                                    [i = PetscInt(0)](PetscInt k) mutable { return k == i++; });
  PetscInt n_local;
  GELX_PETSC(VecGetLocalSize(system_vector, &n_local));
  if (!identity || PetscInt(of_problem.size()) != n_local)
    throw std::invalid_argument("this system's unknowns are not its problem's dofs (a bordered "
                                "system): a problem's operator or vector has no meaning on them");
}
} // namespace

Mat NonlinearSystem::restrict_operator(Mat A) const
{
  Vec x = create_vector();
  require_problem_layout(*this, x);
  GELX_PETSC(VecDestroy(&x));
  GELX_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(A)));
  return A;
}

void NonlinearSystem::restrict_vector(Vec f, Vec r) const
{
  require_problem_layout(*this, r);
  GELX_PETSC(VecCopy(f, r));
}

void NonlinearSystem::prolong_vector(Vec x, Vec u) const
{
  require_problem_layout(*this, x);
  GELX_PETSC(VecCopy(x, u));
}

NonlinearProblem::NonlinearProblem(std::shared_ptr<dolfinx::fem::Function<double>> u,
                                   std::shared_ptr<const dolfinx::fem::Form<double>> residual_form,
                                   std::shared_ptr<const dolfinx::fem::Form<double>> tangent_form,
                                   BCs bcs,
                                   std::shared_ptr<const dolfinx::fem::Expression<double>> admissibility)
    : _u(std::move(u)), _R(std::move(residual_form)), _J(std::move(tangent_form)),
      _bcs(std::move(bcs)), _admissibility(std::move(admissibility)),
      _lifting(int_option("", "dirichlet_lifting", 1) != 0)
{
  _x = dolfinx::la::petsc::create_vector_wrap(*_u->x());
  PetscInt owned;
  GELX_PETSC(VecGetLocalSize(_x, &owned));
  _identity.resize(owned);
  std::iota(_identity.begin(), _identity.end(), PetscInt(0));
}

std::vector<PetscInt> NonlinearProblem::prescribed_rows() const
{
  const std::int32_t owned = _identity.size();
  std::vector<PetscInt> rows;
  for (const auto& bc : _bcs)
  {
    const auto [dofs, num_owned] = bc->dof_indices();
    for (std::int32_t i = 0; i < num_owned; ++i)
      if (dofs[i] < owned)
        rows.push_back(dofs[i]);
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  return rows;
}

NonlinearProblem::~NonlinearProblem()
{
  if (_x)
    VecDestroy(&_x);
}

void NonlinearProblem::unknowns_changed()
{
  GELX_PETSC(VecGhostUpdateBegin(_x, INSERT_VALUES, SCATTER_FORWARD));
  GELX_PETSC(VecGhostUpdateEnd(_x, INSERT_VALUES, SCATTER_FORWARD));
}

Vec NonlinearProblem::create_vector() const
{
  Vec r;
  GELX_PETSC(VecDuplicate(_x, &r));
  return r;
}

namespace
{
/// The six rigid-body modes of a 3-D vector space, orthonormalised: the near-nullspace that
/// lets algebraic multigrid (-newton_pc_type gamg) build good coarse spaces for elasticity.
MatNullSpace rigid_body_modes(const dolfinx::fem::FunctionSpace& V, Vec like)
{
  const auto map = V.dofmap()->index_map;
  const std::int32_t num_nodes = map->size_local();
  const std::vector<double> X = V.tabulate_dof_coordinates(false);
  std::vector<dolfinx::la::Vector<double>> basis(6, dolfinx::la::Vector<double>(map, 3));
  for (std::int32_t n = 0; n < num_nodes; ++n)
    for (int i = 0; i < 3; ++i)
    {
      const std::array<double, 6> modes = rigid_body_modes_at(&X[3 * n], i);
      for (int m = 0; m < 6; ++m)
        basis[m].mutable_array()[3 * n + i] = modes[m];
    }
  dolfinx::la::orthonormalize(std::span(basis));
  std::vector<Vec> vecs(6);
  for (int m = 0; m < 6; ++m)
  {
    GELX_PETSC(VecDuplicate(like, &vecs[m]));
    PetscScalar* a;
    GELX_PETSC(VecGetArray(vecs[m], &a));
    std::copy_n(basis[m].array().begin(), 3 * num_nodes, a);
    GELX_PETSC(VecRestoreArray(vecs[m], &a));
  }
  MatNullSpace space;
  GELX_PETSC(MatNullSpaceCreate(V.mesh()->comm(), PETSC_FALSE, 6, vecs.data(), &space));
  for (Vec& v : vecs)
    VecDestroy(&v);
  return space;
}
} // namespace

Mat NonlinearProblem::create_matrix() const
{
  Mat A = dolfinx::fem::petsc::create_matrix(*_J);
  const auto& V = *_u->function_space();
  if (V.dofmap()->index_map_bs() == 3 && V.element()->num_sub_elements() == 3)
  {
    MatNullSpace modes = rigid_body_modes(V, _x);
    GELX_PETSC(MatSetNearNullSpace(A, modes));
    GELX_PETSC(MatNullSpaceDestroy(&modes));
  }
  return A;
}

void assemble_local_vector(const dolfinx::fem::Form<double>& L, Vec f)
{
  Vec f_local;
  GELX_PETSC(VecGhostGetLocalForm(f, &f_local));
  GELX_PETSC(VecSet(f_local, 0.0));
  PetscInt n = 0;
  GELX_PETSC(VecGetSize(f_local, &n));
  PetscScalar* array = nullptr;
  GELX_PETSC(VecGetArray(f_local, &array));
  dolfinx::fem::assemble_vector(std::span<double>(array, n), L);
  GELX_PETSC(VecRestoreArray(f_local, &array));
  GELX_PETSC(VecGhostRestoreLocalForm(f, &f_local));
}

void assemble_global_vector(const dolfinx::fem::Form<double>& L, Vec f)
{
  assemble_local_vector(L, f);
  GELX_PETSC(VecGhostUpdateBegin(f, ADD_VALUES, SCATTER_REVERSE));
  GELX_PETSC(VecGhostUpdateEnd(f, ADD_VALUES, SCATTER_REVERSE));
}

void NonlinearProblem::internal_forces(Vec f) const { assemble_global_vector(*_R, f); }

double NonlinearProblem::static_residual()
{
  OwnedVec r(create_vector()), f(create_vector());
  residual(r.get());
  internal_forces(f.get());
  PetscReal r_norm, f_norm;
  GELX_PETSC(VecNorm(r.get(), NORM_2, &r_norm));
  GELX_PETSC(VecNorm(f.get(), NORM_2, &f_norm));
  return r_norm / f_norm;
}

void NonlinearProblem::residual(Vec r)
{
  if (!_lifting)
  {
    dolfinx::fem::petsc::set_bc(_x, _bcs, nullptr, 1.0); // u_D = g on the iterate
    unknowns_changed();
  }
  assemble_local_vector(*_R, r);
  dolfinx::fem::petsc::apply_lifting(r, {_J}, {_bcs}, {_x}, -1.0);
  GELX_PETSC(VecGhostUpdateBegin(r, ADD_VALUES, SCATTER_REVERSE));
  GELX_PETSC(VecGhostUpdateEnd(r, ADD_VALUES, SCATTER_REVERSE));
  dolfinx::fem::petsc::set_bc(r, _bcs, _x, -1.0);
}

void NonlinearProblem::tangent(Mat A)
{
  GELX_PETSC(MatZeroEntries(A));
  dolfinx::fem::assemble_matrix(dolfinx::la::petsc::Matrix::set_block_fn(A, ADD_VALUES), *_J,
                                _bcs);
  GELX_PETSC(MatAssemblyBegin(A, MAT_FLUSH_ASSEMBLY));
  GELX_PETSC(MatAssemblyEnd(A, MAT_FLUSH_ASSEMBLY));
  dolfinx::fem::set_diagonal(dolfinx::la::petsc::Matrix::set_fn(A, INSERT_VALUES),
                             *_J->function_spaces()[0], _bcs);
  GELX_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  GELX_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  std::erase_if(_after_tangent, [](const auto& update) { return update.expired(); });
  for (const auto& update : _after_tangent)
    (*update.lock())();
}

double NonlinearProblem::admissibility_margin() const
{
  double local_min = std::numeric_limits<double>::infinity();
  if (_admissibility)
  {
    const auto& mesh = *_admissibility->mesh();
    const int tdim = mesh.topology().dim();
    const std::int32_t num_cells = mesh.topology().index_map(tdim)->size_local();
    std::vector<std::int32_t> cells(num_cells);
    std::iota(cells.begin(), cells.end(), 0);
    const std::size_t num_points = _admissibility->X().second[0];
    xt::xtensor<double, 2> values({cells.size(), num_points});
    _admissibility->eval(cells, values);
    for (double v : values)
      local_min = std::isnan(v) ? -std::numeric_limits<double>::infinity()
                                : std::min(local_min, v);
  }
  double global_min;
  MPI_Allreduce(&local_min, &global_min, 1, MPI_DOUBLE, MPI_MIN, _u->function_space()->mesh()->comm());
  return global_min;
}

bool NonlinearProblem::admissible() const { return admissibility_margin() > 0; }

} // namespace gelx

namespace gelx
{
double assemble_global_scalar(const dolfinx::fem::Form<double>& M)
{
  const double local = dolfinx::fem::assemble_scalar(M);
  double global;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, M.mesh()->comm());
  return global;
}

Resultant boundary_resultant(const NonlinearProblem& problem,
                             const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag)
{
  auto u = problem.u();
  const auto& V = *u->function_space();
  const int bs = V.dofmap()->index_map_bs();
  if (bs != 3)
    throw std::runtime_error("boundary_resultant needs a 3-D vector displacement space");
  const int fdim = V.mesh()->topology().dim() - 1;
  const std::vector<std::int32_t> nodes
      = dolfinx::fem::locate_dofs_topological(V, fdim, facet_tags.find(tag), true);
  const std::int32_t num_owned = V.dofmap()->index_map->size_local();

  Vec f = problem.create_vector();
  problem.internal_forces(f);
  const PetscScalar* f_array = nullptr;
  GELX_PETSC(VecGetArrayRead(f, &f_array));
  const std::vector<double> X = V.tabulate_dof_coordinates(false);
  std::span<const double> u_array = u->x()->array();
  std::array<double, 6> local{};
  for (std::int32_t node : nodes)
  {
    if (node >= num_owned)
      continue;
    std::array<double, 3> x, r;
    for (int i = 0; i < 3; ++i)
    {
      x[i] = X[3 * node + i] + u_array[3 * node + i];
      r[i] = f_array[3 * node + i];
      local[i] += r[i];
    }
    local[3] += x[1] * r[2] - x[2] * r[1];
    local[4] += x[2] * r[0] - x[0] * r[2];
    local[5] += x[0] * r[1] - x[1] * r[0];
  }
  GELX_PETSC(VecRestoreArrayRead(f, &f_array));
  VecDestroy(&f);
  std::array<double, 6> global;
  MPI_Allreduce(local.data(), global.data(), 6, MPI_DOUBLE, MPI_SUM, V.mesh()->comm());
  return {{global[0], global[1], global[2]}, {global[3], global[4], global[5]}};
}
} // namespace gelx
