#pragma once
/// @file probe.h
/// A scalar field's values at chosen nodes, gathered on every rank: what a scene writes to its
/// steps.csv from a point (the solvent's potential at a gel's centre) or a line (a swelling
/// front's depth).

#include <array>
#include <dolfinx/fem/Function.h>
#include <functional>
#include <memory>
#include <vector>

namespace gelx
{

/// The nodes of a scalar Lagrange function whose reference position X satisfies `where`.
class NodeProbe
{
public:
  struct Sample
  {
    std::array<double, 3> X;
    double value;
  };

  /// Collective. Each selected node is counted once (by the rank that owns it).
  NodeProbe(std::shared_ptr<const dolfinx::fem::Function<double>> f,
            const std::function<bool(const std::array<double, 3>&)>& where);

  /// The function's current value at every selected node, on every rank, in rank order.
  /// Collective.
  std::vector<Sample> samples() const;
  /// The value at the only selected node; throws std::logic_error when the selection does not
  /// hold exactly one node. Collective.
  double value() const;

private:
  std::shared_ptr<const dolfinx::fem::Function<double>> _f;
  std::vector<std::int32_t> _nodes;
  std::vector<std::array<double, 3>> _X;
};

} // namespace gelx
