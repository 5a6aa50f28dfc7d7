#include <gelx/io/mesh.h>
#include <gelx/common/timing.h>
#include <gelx/io/parameters.h>
#include <gelx/io/sources.h>

#include <dolfinx/common/MPI.h>
#include <dolfinx/fem/CoordinateElement.h>
#include <dolfinx/graph/AdjacencyList.h>
#include <dolfinx/io/cells.h>
#include <dolfinx/io/xdmf_utils.h>
#include <dolfinx/mesh/Topology.h>
#include <dolfinx/mesh/generation.h>
#include <dolfinx/mesh/utils.h>
#include <dolfinx/mesh/cell_types.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <gmsh.h>
#include <iomanip>
#include <limits>
#include <sstream>
#include <numeric>
#include <unistd.h>
#include <xtensor/xview.hpp>

namespace gelx
{
namespace
{
/// What rank 0 reads from gmsh: nodes, cells and boundary facets in gmsh's node order.
struct GmshData
{
  std::vector<double> x;                       // node coordinates, (num_nodes, 3)
  std::vector<std::int64_t> cells;             // cell -> node indices, dolfinx ordering
  std::vector<std::int32_t> cell_values;       // physical tag per cell
  std::vector<std::int64_t> facets;            // facet -> node indices
  std::vector<std::int32_t> facet_values;      // physical tag per facet
  int cell_type_code = 0;                      // 4 tetrahedron, 5 hexahedron
  std::map<std::string, int> names;
};

dolfinx::mesh::CellType cell_type_of(int gmsh_type)
{
  switch (gmsh_type)
  {
  case 4:
    return dolfinx::mesh::CellType::tetrahedron;
  case 5:
    return dolfinx::mesh::CellType::hexahedron;
  default:
    throw std::runtime_error("gmsh element type " + std::to_string(gmsh_type)
                             + " is not supported (use linear tetrahedra or hexahedra)");
  }
}

/// Elements of dimension `dim` in every physical group of that dimension, with their tags.
void read_physical_elements(int dim, const std::map<std::size_t, std::int64_t>& node_index,
                            int& element_type, std::vector<std::int64_t>& nodes,
                            std::vector<std::int32_t>& values, std::map<std::string, int>& names)
{
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim);
  for (auto [d, group] : groups)
  {
    std::string name;
    gmsh::model::getPhysicalName(d, group, name);
    if (!name.empty())
      names[name] = group;
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(d, group, entities);
    for (int entity : entities)
    {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, d, entity);
      for (std::size_t k = 0; k < types.size(); ++k)
      {
        if (element_type != 0 && element_type != types[k])
          throw std::runtime_error("mixed element types in physical groups of dimension "
                                   + std::to_string(dim));
        element_type = types[k];
        for (std::size_t tag : node_tags[k])
          nodes.push_back(node_index.at(tag));
        values.insert(values.end(), element_tags[k].size(), group);
      }
    }
  }
}

/// The fewest bytes a cell costs a run: P1 tetrahedra have ~0.2 nodes a cell, so 0.6
/// unknowns, and the leanest solver set (`amg`) took 6 kB an unknown at 1e6 unknowns
/// (README: the block's solver table): 3 kB. A bound from below, for refusing absurd meshes.
constexpr double min_bytes_per_cell = 3e3;

/// The memory of the machines `comm` runs on: this machine's times the number of machines
/// (ranks that share memory count once).
double memory_of_machines(MPI_Comm comm)
{
  MPI_Comm shared;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &shared);
  int shared_rank = 0;
  MPI_Comm_rank(shared, &shared_rank);
  MPI_Comm_free(&shared);
  int machines = shared_rank == 0 ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &machines, 1, MPI_INT, MPI_SUM, comm);
  const double memory = static_cast<double>(sysconf(_SC_PHYS_PAGES))
                        * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  return memory * machines;
}

/// Refuse a mesh of at least `cells` cells that cannot fit in `memory` bytes (InputError),
/// before it is made: a mesh size far too small otherwise meshes until the machine gives out.
void require_fits(double cells, double memory, const std::string& why)
{
  if (cells * min_bytes_per_cell <= memory)
    return;
  char text[256];
  std::snprintf(text, sizeof(text),
                "the mesh would have at least %.2g cells (%s), which need at least %.3g GiB: "
                "more than the %.3g GiB of memory this run has",
                cells, why.c_str(), cells * min_bytes_per_cell / std::pow(2.0, 30),
                memory / std::pow(2.0, 30));
  throw InputError(text);
}

/// The fewest tetrahedra of the model gmsh has (before meshing) when its elements may be no
/// larger than Mesh.MeshSizeMax (times Mesh.MeshSizeFactor), and how, for require_fits; 0
/// when no size bounds them (a transfinite mesh's size is its scene's parameter) or the volume
/// is not known (only OpenCASCADE's solids have one before meshing)
std::pair<double, std::string> fewest_cells_of_model()
{
  double size_max = 0, factor = 1;
  gmsh::option::getNumber("Mesh.MeshSizeMax", size_max);
  gmsh::option::getNumber("Mesh.MeshSizeFactor", factor);
  const double h = size_max * factor;
  gmsh::vectorpair volumes;
  gmsh::model::getEntities(volumes, 3);
  double volume = 0;
  try
  {
    for (const auto& [dim, tag] : volumes)
    {
      double mass = 0;
      gmsh::model::occ::getMass(dim, tag, mass);
      volume += mass;
    }
  }
  catch (const std::string&) // a volume of gmsh's own kernel
  {
    return {0.0, ""};
  }
  if (!(h > 0) || h > 1e20 || !(volume > 0))
    return {0.0, ""};
  // a tetrahedron whose edges are at most h holds at most h^3 / (6 sqrt 2): V / h^3 is 8.5
  // times fewer cells than that bound
  char why[128];
  std::snprintf(why, sizeof(why), "mesh size %.3g in a volume of %.3g", h, volume);
  return {volume / (h * h * h), why};
}

/// gmsh's error (its API throws the message as a std::string) as one line
std::string gmsh_error(const std::string& message)
{
  std::string line = message;
  std::replace(line.begin(), line.end(), '\n', ' ');
  return "gmsh: " + line;
}

/// Start gmsh (with `args` as its command line), let `build` create the model, mesh it in 3-D
/// and read it; a model whose mesh cannot fit in `memory` bytes (a sized model's estimate, or
/// the `known_cells` of a transfinite one) is refused before meshing. gmsh prints nothing: its
/// errors come back in the exceptions (InputError).
GmshData mesh_with_gmsh(std::vector<std::string> args, const std::function<void()>& build,
                        double known_cells, double memory)
{
  args.insert(args.begin(), "gelx");
  std::vector<char*> argv;
  for (auto& a : args)
    argv.push_back(a.data());
  gmsh::initialize(static_cast<int>(argv.size()), argv.data(), false);
  gmsh::option::setNumber("General.Verbosity", 0);
  GmshData data;
  try
  {
    build();
    const auto [cells, why] = fewest_cells_of_model();
    require_fits(cells, memory, why);
    require_fits(known_cells, memory, "the scene's structured mesh");
    gmsh::model::mesh::generate(3);

    std::vector<std::size_t> node_tags;
    std::vector<double> coords, parametric;
    gmsh::model::mesh::getNodes(node_tags, coords, parametric);
    std::map<std::size_t, std::int64_t> node_index;
    for (std::size_t i = 0; i < node_tags.size(); ++i)
      node_index[node_tags[i]] = static_cast<std::int64_t>(i);
    data.x = coords;

    int facet_type = 0;
    read_physical_elements(3, node_index, data.cell_type_code, data.cells, data.cell_values,
                           data.names);
    read_physical_elements(2, node_index, facet_type, data.facets, data.facet_values,
                           data.names);
    if (data.cells.empty())
      throw std::runtime_error("the gmsh model defines no physical volume");
  }
  catch (const std::string& message)
  {
    gmsh::finalize();
    throw InputError(gmsh_error(message));
  }
  catch (...)
  {
    gmsh::finalize();
    throw;
  }
  gmsh::finalize();

  // gmsh and dolfinx number the nodes of a cell differently
  const auto type = cell_type_of(data.cell_type_code);
  const int nv = dolfinx::mesh::num_cell_vertices(type);
  const std::vector<std::uint8_t> perm = dolfinx::io::cells::perm_gmsh(type, nv);
  data.cells = dolfinx::io::cells::apply_permutation(
      data.cells, {data.cells.size() / nv, static_cast<std::size_t>(nv)}, perm);
  return data;
}
/// Add the mirror image of the mesh in the plane x_axis = 0 and merge the two along it: the
/// nodes on the plane are shared, the facets on it become interior and lose their tags.
void mirror(GmshData& data, int axis)
{
  const std::size_t num_nodes = data.x.size() / 3;
  double extent = 0;
  for (double v : data.x)
    extent = std::max(extent, std::abs(v));
  const double tol = 1e-10 * extent;
  std::vector<std::int64_t> image(num_nodes);
  for (std::size_t i = 0; i < num_nodes; ++i)
  {
    if (std::abs(data.x[3 * i + axis]) <= tol)
    {
      image[i] = static_cast<std::int64_t>(i);
      continue;
    }
    image[i] = static_cast<std::int64_t>(data.x.size() / 3);
    for (int k = 0; k < 3; ++k)
      data.x.push_back(k == axis ? -data.x[3 * i + k] : data.x[3 * i + k]);
  }
  const std::size_t num_cell_nodes = data.cells.size();
  for (std::size_t i = 0; i < num_cell_nodes; ++i)
    data.cells.push_back(image[data.cells[i]]);
  const std::size_t num_cells = data.cell_values.size();
  for (std::size_t c = 0; c < num_cells; ++c)
    data.cell_values.push_back(data.cell_values[c]);

  const std::size_t facet_nv
      = data.facets.size() / std::max<std::size_t>(data.facet_values.size(), 1);
  std::vector<std::int64_t> facets;
  std::vector<std::int32_t> values, mirrored_values;
  std::vector<std::int64_t> mirrored;
  for (std::size_t f = 0; f < data.facet_values.size(); ++f)
  {
    const auto first = data.facets.begin() + f * facet_nv;
    const bool on_plane = std::all_of(first, first + facet_nv, [&](std::int64_t n)
                                      { return image[n] == n; });
    if (on_plane)
      continue;
    facets.insert(facets.end(), first, first + facet_nv);
    values.push_back(data.facet_values[f]);
    for (auto n = first; n != first + facet_nv; ++n)
      mirrored.push_back(image[*n]);
    mirrored_values.push_back(data.facet_values[f]);
  }
  facets.insert(facets.end(), mirrored.begin(), mirrored.end());
  values.insert(values.end(), mirrored_values.begin(), mirrored_values.end());
  data.facets = std::move(facets);
  data.facet_values = std::move(values);
}
} // namespace

int TaggedMesh::tag(const std::string& name) const
{
  auto it = names.find(name);
  if (it == names.end())
    throw std::runtime_error("the mesh has no physical group named '" + name + "'");
  return it->second;
}

TaggedMesh read_geo(MPI_Comm comm, const std::string& geo_file,
                    const std::map<std::string, double>& numbers,
                    const std::vector<int>& mirror_axes)
{
  const std::filesystem::path in_project = std::filesystem::path(GELX_MESHES) / geo_file;
  const std::string file = std::filesystem::is_regular_file(geo_file)
                                   || std::filesystem::path(geo_file).has_parent_path()
                               ? geo_file
                               : in_project.string();
  if (!std::filesystem::is_regular_file(file))
    throw InputError("mesh file '" + geo_file + "' not found");
  record_input_file(file, geo_file);
  try
  {
    std::vector<std::string> args;
    for (auto& [name, value] : numbers)
    {
      // Every digit (std::to_string keeps 6 decimals: a value of 1e-7 would arrive as 0)
      std::ostringstream text;
      text << std::setprecision(17) << value;
      args.insert(args.end(), {"-setnumber", name, text.str()});
    }
    return mesh_gmsh_model(comm, [&]() { gmsh::open(file); }, args, mirror_axes);
  }
  catch (const InputError& e) // on every rank (mesh_gmsh_model)
  {
    throw InputError("mesh file '" + geo_file + "': " + e.what());
  }
}

TaggedMesh mesh_gmsh_model(MPI_Comm comm, const std::function<void()>& build,
                           const std::vector<std::string>& gmsh_args,
                           const std::vector<int>& mirror_axes, double known_cells)
{
  TimedStage timing("mesh");
  const int rank = dolfinx::MPI::rank(comm);
  const double memory = memory_of_machines(comm);
  GmshData data;
  // gmsh runs on rank 0: its failure reaches every rank as the same InputError
  std::string failure;
  if (rank == 0)
  {
    try
    {
      // each mirror image doubles the cells
      const double cells = std::ldexp(known_cells, static_cast<int>(mirror_axes.size()));
      data = mesh_with_gmsh(gmsh_args, build, cells, memory);
      for (int axis : mirror_axes)
        mirror(data, axis);
    }
    catch (const InputError& e)
    {
      failure = e.what();
    }
    catch (const std::exception& e) // the physical groups (read_physical_elements)
    {
      failure = e.what();
    }
  }
  int failure_size = static_cast<int>(failure.size());
  MPI_Bcast(&failure_size, 1, MPI_INT, 0, comm);
  failure.resize(failure_size);
  MPI_Bcast(failure.data(), failure_size, MPI_CHAR, 0, comm);
  if (!failure.empty())
    throw InputError(failure);

  // Rank 0 tells the others the cell type and the group names
  int type_code = data.cell_type_code;
  MPI_Bcast(&type_code, 1, MPI_INT, 0, comm);
  const auto type = cell_type_of(type_code);
  const int nv = dolfinx::mesh::num_cell_vertices(type);
  std::string names_text;
  for (auto& [name, tag] : data.names)
    names_text += name + " " + std::to_string(tag) + "\n";
  int names_size = static_cast<int>(names_text.size());
  MPI_Bcast(&names_size, 1, MPI_INT, 0, comm);
  names_text.resize(names_size);
  MPI_Bcast(names_text.data(), names_size, MPI_CHAR, 0, comm);

  const std::size_t num_cells = data.cells.size() / nv;
  std::vector<std::int32_t> offsets(num_cells + 1);
  for (std::size_t c = 0; c <= num_cells; ++c)
    offsets[c] = static_cast<std::int32_t>(c * nv);
  dolfinx::graph::AdjacencyList<std::int64_t> cells(data.cells, offsets);
  const dolfinx::fem::CoordinateElement cmap(type, 1);
  auto mesh = std::make_shared<dolfinx::mesh::Mesh>(dolfinx::mesh::create_mesh(
      comm, cells, cmap, data.x, {data.x.size() / 3, 3},
      dolfinx::mesh::GhostMode::shared_facet));

  TaggedMesh result;
  result.mesh = mesh;
  std::istringstream names_in(names_text);
  for (std::string name; names_in >> name;)
    names_in >> result.names[name];

  // Cell tags: every rank looks its cells up by their input index in the broadcast tag list
  std::int64_t num_input_cells = static_cast<std::int64_t>(data.cell_values.size());
  MPI_Bcast(&num_input_cells, 1, MPI_INT64_T, 0, comm);
  data.cell_values.resize(num_input_cells);
  MPI_Bcast(data.cell_values.data(), static_cast<int>(num_input_cells), MPI_INT32_T, 0, comm);
  const int tdim = mesh->topology().dim();
  const auto& original = mesh->topology().original_cell_index;
  std::vector<std::int32_t> cell_indices(original.size()), cell_values(original.size());
  std::iota(cell_indices.begin(), cell_indices.end(), 0);
  for (std::size_t c = 0; c < original.size(); ++c)
    cell_values[c] = data.cell_values[original[c]];
  result.cell_tags = std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(
      mesh, tdim, std::move(cell_indices), std::move(cell_values));

  // Facet tags: dolfinx sends each tagged facet to the ranks that hold it
  mesh->topology_mutable().create_entities(tdim - 1);
  mesh->topology_mutable().create_connectivity(tdim - 1, tdim);
  const int facet_nv = dolfinx::mesh::num_cell_vertices(
      dolfinx::mesh::cell_facet_type(type, 0));
  auto [facet_vertices, facet_values]
      = dolfinx::io::xdmf_utils::distribute_entity_data(*mesh, tdim - 1, data.facets,
                                                        data.facet_values);
  std::vector<std::int32_t> facet_offsets(facet_values.size() + 1);
  for (std::size_t f = 0; f < facet_offsets.size(); ++f)
    facet_offsets[f] = static_cast<std::int32_t>(f * facet_nv);
  result.facet_tags = std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(
      dolfinx::mesh::create_meshtags(
          mesh, tdim - 1,
          dolfinx::graph::AdjacencyList<std::int32_t>(facet_vertices, facet_offsets),
          std::span<const std::int32_t>(facet_values)));
  return result;
}

std::array<std::array<double, 3>, 2> bounding_box(const dolfinx::mesh::Mesh& mesh)
{
  std::array<double, 3> lower, upper;
  lower.fill(std::numeric_limits<double>::infinity());
  upper.fill(-std::numeric_limits<double>::infinity());
  const std::span<const double> x = mesh.geometry().x(); // 3 per node, owned and ghost
  for (std::size_t i = 0; i < x.size(); i += 3)
    for (int k = 0; k < 3; ++k)
    {
      lower[k] = std::min(lower[k], x[i + k]);
      upper[k] = std::max(upper[k], x[i + k]);
    }
  MPI_Allreduce(MPI_IN_PLACE, lower.data(), 3, MPI_DOUBLE, MPI_MIN, mesh.comm());
  MPI_Allreduce(MPI_IN_PLACE, upper.data(), 3, MPI_DOUBLE, MPI_MAX, mesh.comm());
  return {lower, upper};
}

void require_span(const std::array<std::array<double, 3>, 2>& box, int axis, double lower,
                  double upper, const std::string& parameter)
{
  const double tol = 1e-9 * std::max(upper - lower, box[1][axis] - box[0][axis]);
  if (std::abs(box[0][axis] - lower) <= tol && std::abs(box[1][axis] - upper) <= tol)
    return;
  char text[256];
  std::snprintf(text, sizeof(text),
                "the mesh spans %c from %.6g to %.6g, but %s makes it %.6g to %.6g (the mesh "
                "must take the scene's dimensions, or the parameter the mesh's)",
                "xyz"[axis], box[0][axis], box[1][axis], parameter.c_str(), lower, upper);
  throw InputError(text);
}

TaggedMesh box_mesh(MPI_Comm comm, std::array<double, 3> L, std::array<std::size_t, 3> n,
                    dolfinx::mesh::CellType cell, std::array<double, 3> origin)
{
  TimedStage timing("mesh");
  const double tetrahedra_a_box = cell == dolfinx::mesh::CellType::tetrahedron ? 6 : 1;
  require_fits(tetrahedra_a_box * static_cast<double>(n[0]) * static_cast<double>(n[1])
                   * static_cast<double>(n[2]),
               memory_of_machines(comm), "a box of " + std::to_string(n[0]) + " x "
                                             + std::to_string(n[1]) + " x "
                                             + std::to_string(n[2]) + " cells");
  auto mesh = std::make_shared<dolfinx::mesh::Mesh>(dolfinx::mesh::create_box(
      comm, {{origin, {origin[0] + L[0], origin[1] + L[1], origin[2] + L[2]}}}, n, cell,
      dolfinx::mesh::GhostMode::shared_facet));
  const int fdim = 2;
  mesh->topology_mutable().create_entities(fdim);
  mesh->topology_mutable().create_connectivity(fdim, 3);
  TaggedMesh box{mesh, nullptr, nullptr, {}};
  std::vector<std::pair<std::int32_t, std::int32_t>> tagged;
  const char* axes = "xyz";
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int side = 0; side < 2; ++side)
    {
      const int tag = 2 * axis + side + 1;
      box.names[std::string(1, axes[axis]) + (side ? "_max" : "_min")] = tag;
      const double plane = origin[axis] + side * L[axis], tol = 1e-10 * L[axis];
      auto facets = dolfinx::mesh::locate_entities_boundary(
          *mesh, fdim,
          [&](const xt::xtensor<double, 2>& x) -> xt::xtensor<bool, 1>
          { return xt::abs(xt::row(x, axis) - plane) < tol; });
      for (auto f : facets)
        tagged.push_back({f, tag});
    }
  }
  std::sort(tagged.begin(), tagged.end()); // a boundary facet lies on exactly one face
  std::vector<std::int32_t> indices, values;
  for (auto [f, tag] : tagged)
  {
    indices.push_back(f);
    values.push_back(tag);
  }
  box.facet_tags = std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(
      mesh, fdim, std::move(indices), std::move(values));
  return box;
}

} // namespace gelx
