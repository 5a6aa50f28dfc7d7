#include "probe.h"

#include <gelx/common/collectives.h>
#include <stdexcept>

namespace gelx
{

NodeProbe::NodeProbe(std::shared_ptr<const dolfinx::fem::Function<double>> f,
                     const std::function<bool(const std::array<double, 3>&)>& where)
    : _f(std::move(f))
{
  const auto& V = *_f->function_space();
  if (V.dofmap()->index_map_bs() != 1)
    throw std::logic_error("NodeProbe: the function is not scalar");
  const std::vector<double> X = V.tabulate_dof_coordinates(false);
  for (std::int32_t i = 0; i < V.dofmap()->index_map->size_local(); ++i)
    if (const std::array<double, 3> x{X[3 * i], X[3 * i + 1], X[3 * i + 2]}; where(x))
    {
      _nodes.push_back(i);
      _X.push_back(x);
    }
}

std::vector<NodeProbe::Sample> NodeProbe::samples() const
{
  std::vector<double> local; // X, value of each node
  for (std::size_t k = 0; k < _nodes.size(); ++k)
    local.insert(local.end(), {_X[k][0], _X[k][1], _X[k][2], _f->x()->array()[_nodes[k]]});
  const std::vector<double> all = all_gather(_f->function_space()->mesh()->comm(), local);
  std::vector<Sample> samples;
  for (std::size_t k = 0; k < all.size(); k += 4)
    samples.push_back({{all[k], all[k + 1], all[k + 2]}, all[k + 3]});
  return samples;
}

double NodeProbe::value() const
{
  const std::vector<Sample> at = samples();
  if (at.size() != 1)
    throw std::logic_error("NodeProbe: " + std::to_string(at.size())
                           + " nodes selected where one was meant");
  return at.front().value;
}

} // namespace gelx
