#pragma once
/// @file fiber_cell_mesh.h
/// The unit cell of a periodic array of rigid fibers in a gel (thesis Fig. 4.4): a box
/// D x D x L with one fiber of diameter d and length l along z, centred at the origin, cut out
/// of it. The fiber is a capsule (a cylinder with hemispherical caps, l counting the caps) when
/// l < L and a straight rod through the cell when l = L.

#include <gelx/io/mesh.h>
#include <mpi.h>

namespace gelx::scenes
{

/// Lengths in nm; the mesh is refined toward the fiber.
struct FiberCellGeometry
{
  double d = 10;  ///< fiber diameter
  double l = 30;  ///< fiber length, caps included (d <= l <= L)
  double L = 30;  ///< cell length along the fiber
  double D = 50;  ///< cell width across the fiber (D > d)
  /// "eighth": 1/8 of the cell, [0, D/2]^2 x [0, L/2], bounded by the three mirror planes
  /// through the fiber's centre; "full": the whole cell [-D/2, D/2]^2 x [-L/2, L/2], meshed as
  /// the 1/8 cell and its mirror images (so opposite faces match node for node); "film": the
  /// 1/8 cell's mesh for a film one layer of fibers thick, its face x = D/2 the film's free
  /// surface (the cell's conditions are the caller's; the mesh is the same)
  std::string cell = "eighth";
  bool full() const { return cell == "full"; }
  bool film() const { return cell == "film"; }
  /// A film's layers of fibers, at x = k D for k = 0 ... layers - 1 (the film 2 layers - 1
  /// layers thick: the modelled half [0, (layers - 1/2) D] and its mirror image)
  int layers = 1;
  double h_fiber = 2;   ///< mesh size on the fiber surface
  double h_far = 10;    ///< mesh size from `grading` away from the fiber on
  double grading = 10;  ///< distance over which the size grows from h_fiber to h_far
  /// The fiber is a straight rod through the cell (l = L, to within rounding).
  bool rod() const { return l >= L * (1 - 1e-12); }
  /// Throws gelx::InputError naming the first inconsistency (D <= d, l outside [d, L], a whole
  /// cell with a rod, whose clamped ends would be periodic slaves); the sizes are checked
  /// positive as parameters.
  void check() const;
};

/// Mesh the cell with gmsh (OpenCASCADE: box minus fiber) in linear tetrahedra. Facet tags:
/// "fiber" (the fiber surface; a film's further layers' "fiber_1", "fiber_2", ...) and "x_min", "x_max", "y_min", "y_max", "z_min", "z_max" (the
/// cell faces; for the 1/8 cell the *_min faces are the mirror planes); cell tag "gel". Uses
/// mesh_gmsh_model's mirror_axes for the whole cell.
/// Calls g.check(). Collective.
TaggedMesh fiber_cell_mesh(MPI_Comm comm, const FiberCellGeometry& g);

} // namespace gelx::scenes
