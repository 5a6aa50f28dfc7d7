#include <gelx/systems/mixed.h>
#include <gelx/io/parameters.h>
#include <gelx/common/petsc_utils.h>

#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/Mesh.h>
#include <algorithm>

namespace gelx
{

namespace
{
/// The dofs of sub-space i in the parent's numbering, in the order of the collapsed space's.
std::pair<std::shared_ptr<const dolfinx::fem::FunctionSpace>, std::vector<std::int32_t>>
collapsed(const dolfinx::fem::FunctionSpace& W, int i)
{
  auto [V, map] = W.sub({i})->collapse();
  return {std::make_shared<const dolfinx::fem::FunctionSpace>(std::move(V)), std::move(map)};
}
} // namespace

std::shared_ptr<dolfinx::fem::Function<double>>
collapse_sub_function(const dolfinx::fem::Function<double>& w, int i)
{
  auto [V, map] = collapsed(*w.function_space(), i);
  auto f = std::make_shared<dolfinx::fem::Function<double>>(V);
  copy_sub_function(w, i, *f);
  return f;
}

void copy_sub_function(const dolfinx::fem::Function<double>& w, int i,
                       dolfinx::fem::Function<double>& target)
{
  // collapse() returns, for each dof of the collapsed space (block size included), its index in
  // the parent space; both arrays hold owned and ghost values
  auto [V, map] = collapsed(*w.function_space(), i);
  const int bs = target.function_space()->dofmap()->index_map_bs();
  const int bs_map = V->dofmap()->index_map_bs();
  if (bs != bs_map)
    throw std::runtime_error("copy_sub_function: target is not on the collapsed sub-space");
  std::span<const double> from = w.x()->array();
  std::span<double> to = target.x()->mutable_array();
  if (map.size() != to.size())
    throw std::runtime_error("copy_sub_function: target size does not match the sub-space");
  for (std::size_t k = 0; k < map.size(); ++k)
    to[k] = from[map[k]];
}

std::array<double, 3>
reaction_force(const NonlinearProblem& problem, const dolfinx::fem::FunctionSpace& displacement,
               const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags, int tag)
{
  const auto& mesh = *displacement.mesh();
  const int fdim = mesh.topology().dim() - 1;
  const auto& W = *problem.u()->function_space();
  const std::int32_t num_owned
      = W.dofmap()->index_map->size_local() * W.dofmap()->index_map_bs();
  Vec f = problem.create_vector();
  problem.internal_forces(f);
  const PetscScalar* f_array = nullptr;
  GELX_PETSC(VecGetArrayRead(f, &f_array));
  std::array<double, 3> local{};
  for (int c = 0; c < 3; ++c)
  {
    auto sub = displacement.sub({c});
    for (std::int32_t dof :
         dolfinx::fem::locate_dofs_topological(*sub, fdim, facet_tags.find(tag), true))
      if (dof < num_owned)
        local[c] += f_array[dof];
  }
  GELX_PETSC(VecRestoreArrayRead(f, &f_array));
  VecDestroy(&f);
  std::array<double, 3> global;
  MPI_Allreduce(local.data(), global.data(), 3, MPI_DOUBLE, MPI_SUM, mesh.comm());
  return global;
}

namespace
{
/// The matrix that preconditions a fieldsplit solver's Schur complement: the block of the
/// problem's form schur_preconditioner() on the rows `is_p` of `system`'s unknowns, assembled
/// once, or after every tangent when the form follows the state.
class SchurPreconditioner
{
public:
  SchurPreconditioner(NonlinearSystem& system, IS is_p)
      : _system(system), _form(system.problem().schur_preconditioner()), _is_p(is_p)
  {
    GELX_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(_is_p)));
    _full = dolfinx::fem::petsc::create_matrix(*_form);
    assemble(MAT_INITIAL_MATRIX);
    if (system.problem().schur_preconditioner_follows_state())
    {
      _update = std::make_shared<std::function<void()>>([this] { assemble(MAT_REUSE_MATRIX); });
      system.problem().after_tangent(_update);
    }
  }
  ~SchurPreconditioner()
  {
    MatDestroy(&_full);
    MatDestroy(&_block);
    ISDestroy(&_is_p);
  }
  SchurPreconditioner(const SchurPreconditioner&) = delete;
  SchurPreconditioner& operator=(const SchurPreconditioner&) = delete;
  Mat matrix() const { return _block; }

private:
  void assemble(MatReuse reuse)
  {
    // Prescribed rows as in the tangent (its Schur complement's are the identity's)
    const auto& bcs = _system.problem().bcs();
    GELX_PETSC(MatZeroEntries(_full));
    dolfinx::fem::assemble_matrix(dolfinx::la::petsc::Matrix::set_block_fn(_full, ADD_VALUES),
                                  *_form, bcs);
    GELX_PETSC(MatAssemblyBegin(_full, MAT_FLUSH_ASSEMBLY));
    GELX_PETSC(MatAssemblyEnd(_full, MAT_FLUSH_ASSEMBLY));
    dolfinx::fem::set_diagonal(dolfinx::la::petsc::Matrix::set_fn(_full, INSERT_VALUES),
                               *_form->function_spaces()[0], bcs);
    GELX_PETSC(MatAssemblyBegin(_full, MAT_FINAL_ASSEMBLY));
    GELX_PETSC(MatAssemblyEnd(_full, MAT_FINAL_ASSEMBLY));
    Mat unknowns = _system.restrict_operator(_full);
    GELX_PETSC(MatCreateSubMatrix(unknowns, _is_p, _is_p, reuse, &_block));
    MatDestroy(&unknowns);
  }

  NonlinearSystem& _system;
  std::shared_ptr<const dolfinx::fem::Form<double>> _form;
  IS _is_p;
  Mat _full = nullptr, _block = nullptr;
  std::shared_ptr<std::function<void()>> _update;
};
} // namespace

void define_displacement_pressure_fields(PC pc, NonlinearSystem& system)
{
  const auto& W = *system.problem().u()->function_space();
  MPI_Comm comm = W.mesh()->comm();
  if (W.element()->num_sub_elements() != 2)
    throw InputError("the fieldsplit linear solver needs a mixed displacement-pressure space");
  const char* pc_prefix = nullptr;
  GELX_PETSC(PCGetOptionsPrefix(pc, &pc_prefix));
  const std::string prefix = pc_prefix ? pc_prefix : "";
  // BoomerAMG interpolates the rigid-body modes (vec_interp_variant) only on a nodal system,
  // a node's components consecutive (block size 3); a mixed space numbers u's components one
  // by one, so u's block has block size 1, on which hypre crashes (SEGV, measured on the
  // swelling cube). Refused with one line instead
  const std::string vec_interp
      = "-" + prefix + "fieldsplit_u_pc_hypre_boomeramg_vec_interp_variant";
  PetscBool vec_interp_given = PETSC_FALSE;
  GELX_PETSC(PetscOptionsHasName(nullptr, nullptr, vec_interp.c_str(), &vec_interp_given));
  if (vec_interp_given)
    throw InputError(vec_interp + ": BoomerAMG's interpolation of the rigid-body modes needs a "
                     "node's displacement components numbered together, which the mixed "
                     "space's u block does not have");
  const std::int32_t num_owned
      = W.dofmap()->index_map->size_local() * W.dofmap()->index_map_bs();
  const std::vector<PetscInt>& unknown = system.unknown_of_problem_dof();
  PetscInt first = 0, end = 0;
  GELX_PETSC(VecGetOwnershipRange(system.unknowns(), &first, &end));
  std::vector<char> in_a_field(end - first, 0);

  // The owned unknowns of sub-space i, each with the collapsed sub-space's dof it comes from
  auto field = [&](int i)
  {
    auto [V, map] = collapsed(W, i);
    std::vector<std::pair<PetscInt, std::int32_t>> rows;
    for (std::size_t k = 0; k < map.size(); ++k)
      if (map[k] < num_owned && unknown[map[k]] >= 0)
      {
        rows.push_back({first + unknown[map[k]], std::int32_t(k)});
        in_a_field[unknown[map[k]]] = 1;
      }
    return std::make_pair(V, rows);
  };
  auto [V, u_rows] = field(0);
  auto [Q, p_rows] = field(1);
  // The unknowns of neither sub-space (a constraint's macro displacements, a load factor) join
  // u's block, which they are coupled to through u's rows; they have no dof, so no rigid-body
  // mode entry (marked -1, zero in the near-nullspace: a hint to AMG, exact for LU)
  for (PetscInt i = 0; i < end - first; ++i)
    if (!in_a_field[i])
      u_rows.push_back({first + i, -1});
  std::sort(u_rows.begin(), u_rows.end());
  std::sort(p_rows.begin(), p_rows.end());

  auto index_set = [&](const std::vector<std::pair<PetscInt, std::int32_t>>& rows)
  {
    std::vector<PetscInt> indices;
    for (const auto& row : rows)
      indices.push_back(row.first);
    IS is;
    GELX_PETSC(ISCreateGeneral(comm, PetscInt(indices.size()), indices.data(),
                               PETSC_COPY_VALUES, &is));
    return is;
  };
  IS is_u = index_set(u_rows), is_p = index_set(p_rows);

  // The rigid-body modes on u's rows, orthonormalised (modified Gram-Schmidt)
  const std::vector<double> X = V->tabulate_dof_coordinates(false);
  const int bs = V->dofmap()->index_map_bs();
  std::vector<Vec> modes(6);
  for (int m = 0; m < 6; ++m)
  {
    GELX_PETSC(VecCreateMPI(comm, PetscInt(u_rows.size()), PETSC_DETERMINE, &modes[m]));
    PetscScalar* a;
    GELX_PETSC(VecGetArray(modes[m], &a));
    for (std::size_t r = 0; r < u_rows.size(); ++r)
    {
      const std::int32_t k = u_rows[r].second;
      a[r] = k < 0 ? 0.0 : rigid_body_modes_at(&X[3 * (k / bs)], k % bs)[m];
    }
    GELX_PETSC(VecRestoreArray(modes[m], &a));
    for (int n = 0; n < m; ++n)
    {
      PetscScalar dot;
      GELX_PETSC(VecDot(modes[m], modes[n], &dot));
      GELX_PETSC(VecAXPY(modes[m], -dot, modes[n]));
    }
    GELX_PETSC(VecNormalize(modes[m], nullptr));
  }
  MatNullSpace near_nullspace;
  GELX_PETSC(MatNullSpaceCreate(comm, PETSC_FALSE, 6, modes.data(), &near_nullspace));
  GELX_PETSC(PetscObjectCompose(reinterpret_cast<PetscObject>(is_u), "nearnullspace",
                                reinterpret_cast<PetscObject>(near_nullspace)));
  GELX_PETSC(PCFieldSplitSetIS(pc, "u", is_u));
  GELX_PETSC(PCFieldSplitSetIS(pc, "p", is_p));

  // The Schur complement's preconditioner, on request (-PREFIX_pc_fieldsplit_schur_precondition
  // user): the sub-space 1 block of the problem's form schur_preconditioner(). The pressure mass
  // over G of a nearly incompressible solid is spectrally equivalent to the Schur complement
  // only for an inf-sup stable pair (Q2-Q1, P2-P1); for Q1-P0 the spurious pressure modes make
  // it worse than the default selfp (measured on the pyramid, 3 cells, d/H = 0.006: 184 against
  // 132 Krylov iterations per Newton iteration)
  if (string_option(prefix, "pc_fieldsplit_schur_precondition", "") == "user")
  {
    if (!system.problem().schur_preconditioner())
      throw InputError("-" + prefix
                       + "pc_fieldsplit_schur_precondition user: this scene has no form for it");
    auto schur = std::make_unique<SchurPreconditioner>(system, is_p);
    GELX_PETSC(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_USER, schur->matrix()));
    // The PC owns it: while the PC lives, a form that follows the state is assembled again
    // after every tangent, so that the matrix the PC is set up with is the tangent's
    PetscContainer owner;
    GELX_PETSC(PetscContainerCreate(comm, &owner));
    GELX_PETSC(PetscContainerSetPointer(owner, schur.release()));
    GELX_PETSC(PetscContainerSetUserDestroy(owner,
                                            [](void* p) -> PetscErrorCode
                                            {
                                              delete static_cast<SchurPreconditioner*>(p);
                                              return 0;
                                            }));
    GELX_PETSC(PetscObjectCompose(reinterpret_cast<PetscObject>(pc),
                                  "gelx_schur_preconditioner",
                                  reinterpret_cast<PetscObject>(owner)));
    GELX_PETSC(PetscContainerDestroy(&owner));
  }
  for (Vec& v : modes)
    VecDestroy(&v);
  MatNullSpaceDestroy(&near_nullspace);
  ISDestroy(&is_u);
  ISDestroy(&is_p);
}

void prepare_linear_solver(KSP ksp, NonlinearSystem& system)
{
  PC pc;
  GELX_PETSC(KSPGetPC(ksp, &pc));
  PetscBool split;
  GELX_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCFIELDSPLIT, &split));
  if (split)
    define_displacement_pressure_fields(pc, system);
  refactor_after_failure(ksp);
}

} // namespace gelx
