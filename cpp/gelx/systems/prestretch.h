#pragma once
/// @file prestretch.h
/// The prestretch F0 of the multiplicative split F = Fe F0 (forms/materials.py, prestretched),
/// given per cell tag: a strip stretched before it is glued into the bistrip of chapter 3, a
/// prestretched gel.

#include <array>
#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/MeshTags.h>
#include <functional>
#include <map>
#include <memory>

namespace gelx
{

/// A 3x3 tensor, row-major.
using Tensor3 = std::array<double, 9>;

/// Set the cell-wise (DG0 tensor) function F0: cells tagged t get values.at(t); every other
/// cell (untagged, or a tag not in `values`) gets the identity. Owned and ghost cells.
void set_prestretch(dolfinx::fem::Function<double>& F0,
                    const dolfinx::mesh::MeshTags<std::int32_t>& cell_tags,
                    const std::map<int, Tensor3>& values);

/// Cell tags from a rule on the cell midpoint: tag(x) > 0 tags the cell, 0 leaves it untagged.
/// Owned and ghost cells, so assembly sees the same tags on every rank.
std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>>
tag_cells(std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
          const std::function<int(const std::array<double, 3>&)>& tag);

} // namespace gelx
