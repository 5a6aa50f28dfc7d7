#pragma once
/// @file pyramid_mesh.h
/// A structured hexahedral mesh of one eighth, one quarter or one half of the pyramid unit cell
/// (thesis Fig. 2.2).

#include <gelx/io/mesh.h>
#include <mpi.h>
#include <string>

namespace gelx::scenes
{

struct PyramidGeometry
{
  double L = 8.0;  ///< pyramid base width (um); height H = L / sqrt(2)
  double W = 64.0; ///< unit cell width (um)
  double t = 32.0; ///< base thickness (um)
  int cells = 4;   ///< hexahedra along each edge of a pyramid block
  int tip_levels = 3; ///< apex refinement: the tip is cut at H/2, H/4, ... this many times
  double growth = 1.5; ///< size ratio of neighbouring cells in the base, away from the pyramid
  /// "quarter": the quarter x, y >= 0 of the unit cell; "eighth": the wedge 0 <= y <= x of the
  /// quarter (the quarter is symmetric about the plane x = y as well); "half": the half x >= 0
  /// (the quarter and its mirror image in y = 0). The eighth's mesh is the quarter's on one
  /// side of the diagonal (with base "diagonal"), and the half's is the quarter's and its
  /// mirror image, so that they share their discrete solution: the symmetry conditions change
  /// nothing.
  std::string domain = "quarter";
  /// The top face of the base outside the pyramid: "corner", graded quadrilaterals along the
  /// pyramid's foot and a block at the cell's corner (the quarter's and half's default), or
  /// "diagonal", columns with the diagonal x = y as a mesh line (the eighth needs it; a quarter
  /// on it is the eighth and its mirror image, for comparing the two).
  std::string base = "corner";
};

/// The quarter x, y >= 0 (or the eighth 0 <= y <= x, or the half x >= 0,
/// PyramidGeometry::domain) of the unit cell [-W/2, W/2]^2: the base [0, W/2]^2 x [0, t] and
/// on it the pyramid over [0, L/2]^2 with its apex at (0, 0, t + H), all hexahedra.
///
/// Why this mesh: contact starts at the apex, a sharp corner where tetrahedra are crushed
/// (shared/NOTES.md: uniform P2-P1 tetrahedra stall at d/H = 0.2-0.34). As in thesis
/// Fig. 2.2b, each of the two tetrahedra of the quarter pyramid (split by its diagonal plane
/// x = y) is split into hexahedra: near the apex into four (at each vertex: its edge
/// midpoints, face centroids and the centroid), and below a stack of horizontal cuts at
/// H/2, H/4, ... from the apex into triangular frusta of three hexahedra each, so that the
/// cells shrink geometrically toward the apex and every cell keeps the shape of a corner of the
/// tetrahedron. The top face of the base outside the pyramid is meshed in graded
/// quadrilaterals (PyramidGeometry::base): with the diagonal base in columns x = const
/// (y = const on the other side of the diagonal) with the diagonal x = y as a mesh line, so
/// that the mesh is conforming on the diagonal plane and symmetric about it (the eighth is
/// built as the tetrahedron A O P Q and the base below the wedge, the quarter as that and its
/// mirror image in x = y). The base is extruded from it in layers that grow away from the
/// pyramid.
///
/// Physical groups: volume "body"; surfaces "bottom" (z = 0), "sym_x" (x = 0), "sym_y" (y = 0),
/// "side_x" (x = W/2), "side_y" (y = W/2), "lateral", the lateral faces of the pyramid (the
/// contact candidates; one in the eighth, two in the quarter), and in the eighth "diagonal"
/// (x = y; it has no "sym_x" and "side_y"). The half has the quarter's groups (its y = 0
/// plane is interior).
TaggedMesh pyramid_mesh(MPI_Comm comm, const PyramidGeometry& g);

} // namespace gelx::scenes
