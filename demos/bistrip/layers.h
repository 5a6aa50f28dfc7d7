#pragma once
/// @file layers.h
/// The strip's cross-section as a stack of layers (thesis Fig. 3.10: bistrips and tristrips),
/// read from its text form (`--section`). Apart from the mesh (section.h), so that the
/// parser's fuzzer (tests/fuzz) builds without gmsh and dolfinx.

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

} // namespace gelx::scenes
