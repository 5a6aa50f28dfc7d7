#pragma once
/// @file boundary.h
/// Dirichlet conditions by facet tag and displacement component, with values that follow the
/// load factor t.

#include <array>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/MeshTags.h>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace gelx
{

/// Dirichlet conditions on the displacement.
///
/// Each condition prescribes one component of the displacement on the facets with one tag to a
/// value u_c(t, X) of the load factor t and the reference position X. The displacement space
/// may be a sub-space (the u of a mixed u-p space).
class DirichletConditions
{
public:
  using Profile = std::function<double(double t, const std::array<double, 3>& X)>;

  DirichletConditions(std::shared_ptr<const dolfinx::fem::FunctionSpace> displacement_space,
                      std::shared_ptr<const dolfinx::mesh::MeshTags<std::int32_t>> facet_tags);

  /// Prescribe u_component = value(t, X) on the facets tagged `tag`.
  void prescribe(int tag, int component, Profile value);

  /// Hold u_component = 0 on the facets tagged `tag` (a roller when used for one component).
  void fix(int tag, int component);
  /// The same at the dofs of those facets whose position X satisfies `where` only (a line of
  /// a face: pins a rigid motion without holding the face's in-plane strain).
  void fix(int tag, int component, const std::function<bool(const std::array<double, 3>&)>& where);

  /// Clamp: u = 0 on the facets tagged `tag`.
  void clamp(int tag);

  /// Evaluate every prescribed value at load factor t.
  void update(double t);

  const std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>>& bcs() const
  {
    return _bcs;
  }

private:
  void prescribe(int tag, int component, Profile value,
                 const std::function<bool(const std::array<double, 3>&)>& where);
  struct Condition
  {
    /// Evaluated on every cell, so that each rank computes the values of all its dofs, owned
    /// and ghost, even where it does not hold the tagged facet the dof lies on
    std::shared_ptr<dolfinx::fem::Function<double>> value;
    Profile profile;
  };
  std::shared_ptr<const dolfinx::fem::FunctionSpace> _V;
  std::shared_ptr<const dolfinx::mesh::MeshTags<std::int32_t>> _facet_tags;
  std::vector<Condition> _conditions;
  std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>> _bcs;
};

/// The Dirichlet condition sub = value on a scalar sub-space of a mixed space (a chemical
/// potential, a pressure), `value` a function on its collapsed space: on the facets in
/// `facets` (find(tag) of a MeshTags), or, with every_node, at every node (the whole field
/// prescribed: a swelling gel's solvent held at equilibrium, whose conservation rows then drop
/// out).
std::shared_ptr<const dolfinx::fem::DirichletBC<double>>
prescribe_sub(std::shared_ptr<const dolfinx::fem::FunctionSpace> sub,
              std::shared_ptr<const dolfinx::fem::Function<double>> value,
              std::span<const std::int32_t> facets);
std::shared_ptr<const dolfinx::fem::DirichletBC<double>>
prescribe_sub_every_node(std::shared_ptr<const dolfinx::fem::FunctionSpace> sub,
                         std::shared_ptr<const dolfinx::fem::Function<double>> value);

/// Smallest and largest value of component `c` of a vector function at its dofs on the facets
/// tagged `tag` (all ranks): a probe for the displacement of a face.
std::pair<double, double> component_range(const dolfinx::fem::Function<double>& u,
                                          const dolfinx::mesh::MeshTags<std::int32_t>& facets,
                                          int tag, int c);

} // namespace gelx
