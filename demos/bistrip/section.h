#pragma once
/// @file section.h
/// The strip's cross-section as a stack of layers (thesis Fig. 3.10: bistrips and tristrips),
/// and its structured hexahedral mesh.

#include <gelx/io/mesh.h>
#include <mpi.h>
#include <string>
#include <vector>

namespace gelx::scenes
{

/// One strip of the stack, in the bonded state (the mesh's reference configuration).
struct Layer
{
  bool prestretched;          ///< carries the stretch before bonding (strip A) or not (B)
  double width, thickness;    ///< mm, bonded state
};

/// Parse a section "B 9x3, A 9x3, B 9x0.2": layers from the bottom up, `KIND WxH` in mm. B is
/// stress-free; A is prestretched, given by its natural (unstretched) cross-section, which
/// shrinks by `lateral_stretch` when bonded; S is prestretched, given by its bonded
/// cross-section. Throws gelx::InputError naming what is wrong.
std::vector<Layer> parse_section(const std::string& section, double lateral_stretch);

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
