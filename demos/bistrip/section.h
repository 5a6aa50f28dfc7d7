#pragma once
/// @file section.h
/// The structured hexahedral mesh of the strip's cross-section, a stack of layers (layers.h),
/// extruded along the strip.

#include "layers.h"
#include <gelx/io/mesh.h>
#include <mpi.h>
#include <string>
#include <vector>

namespace gelx::scenes
{

/// Cells of the structured mesh of a stack.
struct SectionCells
{
  int along;       ///< cell layers (slabs) along the strip
  int centre;      ///< across the narrowest layer's width
  int overhang;    ///< across each step between two widths, each side
  int stressfree;  ///< through each stress-free layer
  int prestretched; ///< through each prestretched layer
};

/// The stack, centred on x = 0 and extruded along z from 0 to L in conforming hexahedra (the
/// cross-section's quadrilaterals repeated in every slab, so that slabs are cell layers). The
/// bottom layer's top face is y = 0. Tags: cells 1 (prestretched, "A") and 2 (stress-free,
/// "B"); facets 1 ("fixed", z = 0) and 2 ("moving", z = L). Collective.
TaggedMesh layered_strip_mesh(MPI_Comm comm, const std::vector<Layer>& layers, double L,
                              const SectionCells& cells);

} // namespace gelx::scenes
