#include "fiber_cell_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <dolfinx/mesh/utils.h>
#include <gelx/io/parameters.h>
#include <gmsh.h>
#include <map>
#include <string>
#include <vector>

namespace gelx::scenes
{
namespace
{
/// The fiber as an OpenCASCADE solid centred at (x, 0, 0); returns its (dim, tag) pairs.
gmsh::vectorpair add_fiber(const FiberCellGeometry& g, double x)
{
  namespace occ = gmsh::model::occ;
  const double r = g.d / 2;
  if (g.rod()) // longer than the cell, so the cut leaves the rod's cross-section as holes
    return {{3, occ::addCylinder(x, 0, -g.L, 0, 0, 2 * g.L, r)}};
  const double c = g.l / 2 - r; // half-length of the cylindrical part
  gmsh::vectorpair caps = {{3, occ::addSphere(x, 0, -c, r)}};
  if (c <= 0) // l = d: the two caps make a sphere
    return caps;
  caps.push_back({3, occ::addSphere(x, 0, c, r)});
  gmsh::vectorpair fiber;
  std::vector<gmsh::vectorpair> unused;
  occ::fuse({{3, occ::addCylinder(x, 0, -c, 0, 0, 2 * c, r)}}, caps, fiber, unused);
  return fiber;
}

/// Distance from (x, y, z) to the nearest fiber's surface (negative inside).
double distance_to_fiber(const FiberCellGeometry& g, double x, double y, double z)
{
  const double r = g.d / 2;
  const double axial = g.rod() ? 0.0 : std::max(0.0, std::abs(z) - (g.l / 2 - r));
  // the fibers at x = k D, k = 0 ... layers - 1: the nearest is the one of k nearest x / D
  const double k = std::clamp(std::round(x / g.D), 0.0, double(g.layers - 1));
  const double dx = x - k * g.D;
  return std::sqrt(dx * dx + y * y + axial * axial) - r;
}

/// The whole cell is the 1/8 cell mirrored in x = 0, y = 0 and z = 0; the images of the faces
/// x_max, y_max, z_max keep their tags, so retag those with a negative coordinate as the *_min
/// faces of the whole cell (the mirror planes' groups, now interior and empty). Works on the
/// tagged facets each rank holds, so ghosts are retagged too.
void retag_min_faces(TaggedMesh& cell)
{
  const auto& old = *cell.facet_tags;
  std::vector<std::int32_t> values(old.values().begin(), old.values().end());
  const std::vector<double> midpoints
      = dolfinx::mesh::compute_midpoints(*cell.mesh, 2, old.indices());
  const std::array<std::string, 3> axes = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < values.size(); ++i)
      if (values[i] == cell.tag(axes[k] + "_max") && midpoints[3 * i + k] < 0)
        values[i] = cell.tag(axes[k] + "_min");
  cell.facet_tags = std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(
      cell.mesh, 2, std::vector<std::int32_t>(old.indices().begin(), old.indices().end()),
      std::move(values));
}
} // namespace

void FiberCellGeometry::check() const
{
  if (D <= d)
    throw InputError("the cell width D must exceed the fiber diameter d");
  if (l < d || l > L)
    throw InputError("the fiber length l must lie in [d, L]");
  if (full() && rod())
    throw InputError("the full periodic cell needs a fiber shorter than the cell (l < L)");
  if (layers < 1 || (layers > 1 && !film()))
    throw InputError("layers of fibers other than one make a film only (cell film)");
}

TaggedMesh fiber_cell_mesh(MPI_Comm comm, const FiberCellGeometry& g)
{
  g.check();
  auto build = [g]()
  {
    namespace occ = gmsh::model::occ;
    gmsh::model::add("fiber_cell");
    const int box = occ::addBox(0, 0, 0, (g.layers - 0.5) * g.D, g.D / 2, g.L / 2);
    gmsh::vectorpair fibers, cell;
    for (int k = 0; k < g.layers; ++k)
    {
      const gmsh::vectorpair fiber = add_fiber(g, k * g.D);
      fibers.insert(fibers.end(), fiber.begin(), fiber.end());
    }
    std::vector<gmsh::vectorpair> unused;
    occ::cut({{3, box}}, fibers, cell, unused);
    occ::synchronize();

    // Faces by their bounding box: flat and on a cell face, or else the fiber
    const double tol = 1e-6 * std::max(g.D, g.L);
    const std::array<std::string, 3> axes = {"x", "y", "z"};
    std::map<std::string, std::vector<int>> groups;
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    for (const auto& [dim, tag] : surfaces)
    {
      std::array<double, 6> b;
      gmsh::model::getBoundingBox(dim, tag, b[0], b[1], b[2], b[3], b[4], b[5]);
      // the fiber of layer k (its surface centred at x = k D; the first is cut in half by x = 0)
      const int k = int(std::lround(0.5 * (b[0] + b[3]) / g.D));
      std::string name = k == 0 ? "fiber" : "fiber_" + std::to_string(k);
      for (int i = 0; i < 3; ++i)
        if (b[i + 3] - b[i] < tol)
          name = axes[i] + (std::abs(b[i]) < tol ? "_min" : "_max");
      groups[name].push_back(tag);
    }
    int group = 1;
    for (const auto& [name, tags] : groups)
    {
      gmsh::model::addPhysicalGroup(2, tags, group);
      gmsh::model::setPhysicalName(2, group++, name);
    }
    std::vector<int> volumes;
    for (const auto& [dim, tag] : cell)
      volumes.push_back(tag);
    gmsh::model::addPhysicalGroup(3, volumes, 100);
    gmsh::model::setPhysicalName(3, 100, "gel");

    // Size: h_fiber on the fiber, growing linearly to h_far at `grading` from it
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    gmsh::model::mesh::setSizeCallback(
        [g](int, int, double x, double y, double z)
        {
          const double s = std::clamp(distance_to_fiber(g, x, y, z) / g.grading, 0.0, 1.0);
          return g.h_fiber + s * (g.h_far - g.h_fiber);
        });
  };
  if (!g.full())
    return mesh_gmsh_model(comm, build);
  // The mirror images match node for node on opposite faces, as periodic constraints need,
  // and the whole cell's symmetric solution is the 1/8 cell's to round-off
  TaggedMesh cell = mesh_gmsh_model(comm, build, {}, {0, 1, 2});
  retag_min_faces(cell);
  return cell;
}

} // namespace gelx::scenes
