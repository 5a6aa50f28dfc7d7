#include <gelx/systems/prestretch.h>

#include <dolfinx/fem/DofMap.h>
#include <dolfinx/mesh/utils.h>
#include <numeric>

namespace gelx
{

void set_prestretch(dolfinx::fem::Function<double>& F0,
                    const dolfinx::mesh::MeshTags<std::int32_t>& cell_tags,
                    const std::map<int, Tensor3>& values)
{
  const auto& V = *F0.function_space();
  const auto& dofmap = *V.dofmap();
  const int bs = dofmap.bs();
  if (bs != 9 || dofmap.cell_dofs(0).size() != 1)
    throw std::runtime_error("set_prestretch needs a DG0 3x3 tensor function");
  const auto& mesh = *V.mesh();
  const int tdim = mesh.topology().dim();
  const auto cell_map = mesh.topology().index_map(tdim);
  const std::int32_t num_cells = cell_map->size_local() + cell_map->num_ghosts();
  std::vector<int> tag_of(num_cells, 0);
  for (std::size_t k = 0; k < cell_tags.indices().size(); ++k)
    tag_of[cell_tags.indices()[k]] = cell_tags.values()[k];
  const Tensor3 identity = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::span<double> x = F0.x()->mutable_array();
  for (std::int32_t c = 0; c < num_cells; ++c)
  {
    auto it = values.find(tag_of[c]);
    const Tensor3& value = it == values.end() ? identity : it->second;
    const std::int32_t node = dofmap.cell_dofs(c)[0];
    std::copy(value.begin(), value.end(), x.begin() + bs * node);
  }
}

std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>>
tag_cells(std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
          const std::function<int(const std::array<double, 3>&)>& tag)
{
  const int tdim = mesh->topology().dim();
  const auto cell_map = mesh->topology().index_map(tdim);
  const std::int32_t num_cells = cell_map->size_local() + cell_map->num_ghosts();
  std::vector<std::int32_t> cells(num_cells);
  std::iota(cells.begin(), cells.end(), 0);
  const auto midpoints = dolfinx::mesh::compute_midpoints(*mesh, tdim, cells);
  std::vector<std::int32_t> indices, values;
  for (std::int32_t c = 0; c < num_cells; ++c)
  {
    const int t = tag({midpoints[3 * c], midpoints[3 * c + 1], midpoints[3 * c + 2]});
    if (t > 0)
    {
      indices.push_back(c);
      values.push_back(t);
    }
  }
  return std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(mesh, tdim, std::move(indices),
                                                                 std::move(values));
}

} // namespace gelx
