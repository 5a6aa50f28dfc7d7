#pragma once
/// @file mesh.h
/// Meshes from gmsh `.geo` files with their physical groups as dolfinx tags.

#include <array>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/cell_types.h>
#include <dolfinx/mesh/MeshTags.h>
#include <functional>
#include <map>
#include <memory>
#include <mpi.h>
#include <string>
#include <vector>

namespace gelx
{

/// A distributed mesh with the gmsh physical groups of its cells and boundary facets.
struct TaggedMesh
{
  std::shared_ptr<dolfinx::mesh::Mesh> mesh;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> cell_tags;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> facet_tags;
  /// Physical group names from the .geo file, name -> tag (cells and facets share the map)
  std::map<std::string, int> names;

  /// Tag of a named physical group; throws std::runtime_error naming it when absent.
  int tag(const std::string& name) const;
};

/// Mesh the `.geo` file with gmsh on rank 0 and distribute it over `comm`.
///
/// `geo_file` is a path, or the name of a file in the project's meshes/ folder (block.geo):
/// a scene's default mesh is named so, and a run records it so (scene.txt, with the file's
/// SHA-256), which makes the record replay in any checkout, not only in the one it ran in.
///
/// `numbers` overrides the file's `DefineConstant`/variables (gmsh `-setnumber`), so a
/// scene's geometry parameters reach the mesh without editing the file. Physical volumes become
/// cell tags and physical surfaces facet tags. Linear tetrahedra and hexahedra are supported.
/// `mirror_axes` as for mesh_gmsh_model. Throws gelx::InputError when the file is missing
/// (checked on every rank before any collective call).
TaggedMesh read_geo(MPI_Comm comm, const std::string& geo_file,
                    const std::map<std::string, double>& numbers = {},
                    const std::vector<int>& mirror_axes = {});

/// Mesh a model that `build` creates with the gmsh API (gmsh is initialised, with `gmsh_args`
/// as its command line, on rank 0 only) and distribute it over `comm`, as read_geo does. For
/// geometries a .geo file cannot express in reasonable length; `build` must add the physical
/// groups and may set transfinite meshing, and it is called on rank 0 only, so it must not
/// communicate. `mirror_axes`: reflect the mesh in the plane x_k = 0 for each k in turn and
/// merge it with its image (the facets on the plane become interior and lose their tags): the
/// larger domain of a symmetry-reduced model, to show that the reduction does not change the
/// answer. `known_cells`: the number of cells `build` makes (before mirroring), or a lower
/// bound, when the scene knows it: a transfinite mesh, whose size no mesh-size option bounds,
/// is then refused before meshing when it cannot fit in memory, as a sized model is (a
/// transfinite model's own size is not known to gmsh before meshing). Collective.
TaggedMesh mesh_gmsh_model(MPI_Comm comm, const std::function<void()>& build,
                           const std::vector<std::string>& gmsh_args = {},
                           const std::vector<int>& mirror_axes = {}, double known_cells = 0);

/// The smallest box that holds the mesh: {lower corner, upper corner}. Collective.
std::array<std::array<double, 3>, 2> bounding_box(const dolfinx::mesh::Mesh& mesh);

/// Refuse a mesh that does not span [lower, upper] along `axis` (to 1e-9 of the span) with an
/// InputError that says what `parameter` should be: a scene whose conditions use its geometry
/// parameters cannot take a mesh of other dimensions (a .geo file that ignores them).
void require_span(const std::array<std::array<double, 3>, 2>& box, int axis, double lower,
                  double upper, const std::string& parameter);

/// Box [0, L0] x [0, L1] x [0, L2] (shifted by `origin`) with n cells along each edge
/// (tetrahedra: six a box cell, dolfinx's create_box) and its faces tagged x_min = 1,
/// x_max = 2, y_min = 3, y_max = 4, z_min = 5, z_max = 6 (`names` holds them): for prismatic
/// scenes (columns, blocks) and verification tests.
TaggedMesh box_mesh(MPI_Comm comm, std::array<double, 3> L, std::array<std::size_t, 3> n,
                    dolfinx::mesh::CellType cell = dolfinx::mesh::CellType::tetrahedron,
                    std::array<double, 3> origin = {0, 0, 0});

} // namespace gelx
