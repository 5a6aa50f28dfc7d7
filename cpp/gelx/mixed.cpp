#include "mixed.h"
#include "petsc_utils.h"

#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/mesh/Mesh.h>

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

} // namespace gelx
