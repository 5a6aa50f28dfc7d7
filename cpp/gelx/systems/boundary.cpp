#include <gelx/systems/boundary.h>

#include <cmath>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/Topology.h>
#include <numeric>

namespace gelx
{

DirichletConditions::DirichletConditions(
    std::shared_ptr<const dolfinx::fem::FunctionSpace> displacement_space,
    std::shared_ptr<const dolfinx::mesh::MeshTags<std::int32_t>> facet_tags)
    : _V(std::move(displacement_space)), _facet_tags(std::move(facet_tags))
{
}

void DirichletConditions::prescribe(int tag, int component, Profile value)
{
  prescribe(tag, component, std::move(value), nullptr);
}

void DirichletConditions::prescribe(int tag, int component, Profile value,
                                    const std::function<bool(const std::array<double, 3>&)>& where)
{
  const auto& mesh = *_V->mesh();
  const int fdim = mesh.topology().dim() - 1;
  if (component < 0 || component >= mesh.geometry().dim())
    throw std::runtime_error("displacement component " + std::to_string(component)
                             + " does not exist");
  std::vector<std::int32_t> facets = _facet_tags->find(tag);

  auto sub = _V->sub({component});
  auto collapsed = std::make_shared<dolfinx::fem::FunctionSpace>(sub->collapse().first);
  auto dofs = dolfinx::fem::locate_dofs_topological({*sub, *collapsed}, fdim, facets);
  if (where)
  {
    const std::vector<double> X = collapsed->tabulate_dof_coordinates(false);
    std::array<std::vector<std::int32_t>, 2> kept;
    for (std::size_t i = 0; i < dofs[1].size(); ++i)
    {
      const double* x = X.data() + 3 * dofs[1][i];
      if (where({x[0], x[1], x[2]}))
        for (int k : {0, 1})
          kept[k].push_back(dofs[k][i]);
    }
    dofs = std::move(kept);
  }
  auto g = std::make_shared<dolfinx::fem::Function<double>>(collapsed);

  _conditions.push_back({g, std::move(value)});
  _bcs.push_back(std::make_shared<const dolfinx::fem::DirichletBC<double>>(g, std::move(dofs), sub));
}

void DirichletConditions::fix(int tag, int component)
{
  prescribe(tag, component, [](double, const std::array<double, 3>&) { return 0.0; });
}

void DirichletConditions::fix(int tag, int component,
                              const std::function<bool(const std::array<double, 3>&)>& where)
{
  prescribe(tag, component, [](double, const std::array<double, 3>&) { return 0.0; }, where);
}

void DirichletConditions::clamp(int tag)
{
  for (int c = 0; c < _V->mesh()->geometry().dim(); ++c)
    fix(tag, c);
}

void DirichletConditions::update(double t)
{
  for (auto& condition : _conditions)
  {
    condition.value->interpolate(
        [&](const xt::xtensor<double, 2>& x) -> xt::xarray<double>
        {
          xt::xarray<double> values = xt::zeros<double>({x.shape(1)});
          for (std::size_t p = 0; p < x.shape(1); ++p)
            values(p) = condition.profile(t, {x(0, p), x(1, p), x(2, p)});
          return values;
        });
  }
}

std::shared_ptr<const dolfinx::fem::DirichletBC<double>>
prescribe_sub(std::shared_ptr<const dolfinx::fem::FunctionSpace> sub,
              std::shared_ptr<const dolfinx::fem::Function<double>> value,
              std::span<const std::int32_t> facets)
{
  const int facet_dim = sub->mesh()->topology().dim() - 1;
  return std::make_shared<dolfinx::fem::DirichletBC<double>>(
      value,
      dolfinx::fem::locate_dofs_topological({*sub, *value->function_space()}, facet_dim, facets),
      sub);
}

std::shared_ptr<const dolfinx::fem::DirichletBC<double>>
prescribe_sub_every_node(std::shared_ptr<const dolfinx::fem::FunctionSpace> sub,
                         std::shared_ptr<const dolfinx::fem::Function<double>> value)
{
  const int dim = sub->mesh()->topology().dim();
  const auto cells = sub->mesh()->topology().index_map(dim);
  std::vector<std::int32_t> all(cells->size_local() + cells->num_ghosts());
  std::iota(all.begin(), all.end(), 0);
  return std::make_shared<dolfinx::fem::DirichletBC<double>>(
      value, dolfinx::fem::locate_dofs_topological({*sub, *value->function_space()}, dim, all),
      sub);
}

std::pair<double, double> component_range(const dolfinx::fem::Function<double>& u,
                                          const dolfinx::mesh::MeshTags<std::int32_t>& facets,
                                          int tag, int c)
{
  const auto& V = *u.function_space();
  const int bs = V.dofmap()->index_map_bs();
  const auto nodes = dolfinx::fem::locate_dofs_topological(V, 2, facets.find(tag));
  double lo = INFINITY, hi = -INFINITY;
  for (std::int32_t node : nodes)
  {
    lo = std::min(lo, u.x()->array()[bs * node + c]);
    hi = std::max(hi, u.x()->array()[bs * node + c]);
  }
  MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, V.mesh()->comm());
  MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_DOUBLE, MPI_MAX, V.mesh()->comm());
  return {lo, hi};
}

} // namespace gelx
