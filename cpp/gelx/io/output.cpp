#include <gelx/io/output.h>
#include <gelx/io/files.h>
#include <gelx/common/collectives.h>
#include <gelx/io/parameters.h>
#include <gelx/common/timing.h>

#include <basix/finite-element.h>
#include <dolfinx/common/MPI.h>
#include <dolfinx/common/version.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/utils.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <numeric>
#include <regex>
#include <xtensor/xtensor.hpp>
#include <gmsh.h>
#include <gelx_version.h>
#include <petscversion.h>

namespace gelx
{
std::shared_ptr<dolfinx::fem::FunctionSpace>
lagrange_space(std::shared_ptr<const dolfinx::mesh::Mesh> mesh, int degree, int block_size)
{
  const auto cell = dolfinx::mesh::cell_type_to_basix_type(mesh->topology().cell_type());
  auto element = basix::create_element(basix::element::family::P, cell, degree,
                                       basix::element::lagrange_variant::gll_warped,
                                       degree == 0);
  // create_functionspace wants a mutable mesh, though it does not change it
  auto m = std::const_pointer_cast<dolfinx::mesh::Mesh>(mesh);
  return std::make_shared<dolfinx::fem::FunctionSpace>(
      dolfinx::fem::create_functionspace(m, element, block_size));
}

CellField::CellField(const std::string& name,
                     std::shared_ptr<const dolfinx::fem::Expression<double>> e)
    : _expression(std::move(e))
{
  std::vector<std::string> names;
  if (_expression->value_size() == 1)
    names = {name};
  else if (_expression->value_size() == 9)
    for (const char* suffix : {"_xx", "_yy", "_zz", "_yz", "_xz", "_xy", "_vm", "_p"})
      names.push_back(name + suffix);
  else
    throw std::runtime_error("cell field '" + name + "' must be a scalar or a 3x3 tensor");
  auto V = lagrange_space(_expression->mesh(), 0, 1);
  for (const auto& n : names)
  {
    _fields.push_back(std::make_shared<dolfinx::fem::Function<double>>(V));
    _fields.back()->name = n;
    _outputs.push_back(_fields.back());
  }
  if (_expression->value_size() == 9)
  {
    // The whole tensor, row by row: ParaView reads it as a tensor (XDMF AttributeType Tensor),
    // for its tensor filters and glyphs
    _tensor = std::make_shared<dolfinx::fem::Function<double>>(
        lagrange_space(_expression->mesh(), 0, 9));
    _tensor->name = name;
    _outputs.push_back(_tensor);
  }
}

void CellField::update()
{
  const auto& mesh = *_expression->mesh();
  const auto cell_map = mesh.topology().index_map(mesh.topology().dim());
  const std::int32_t num_cells = cell_map->size_local() + cell_map->num_ghosts();
  std::vector<std::int32_t> cells(num_cells);
  std::iota(cells.begin(), cells.end(), 0);
  const int n = _expression->value_size();
  xt::xtensor<double, 2> values({cells.size(), static_cast<std::size_t>(n)});
  _expression->eval(cells, values);

  const auto& dofmap = *_fields.front()->function_space()->dofmap();
  // a 3x3 expression's whole tensor (n == 9), blocked by 9
  const auto& tensor_dofmap = *(_tensor ? _tensor : _fields.front())->function_space()->dofmap();
  for (std::int32_t c = 0; c < num_cells; ++c)
  {
    const std::int32_t dof = dofmap.cell_dofs(c)[0];
    if (n == 1)
    {
      _fields[0]->x()->mutable_array()[dof] = values(c, 0);
      continue;
    }
    auto s = [&](int i, int j) { return values(c, 3 * i + j); };
    const double components[6] = {s(0, 0), s(1, 1), s(2, 2), s(1, 2), s(0, 2), s(0, 1)};
    const double p = -(s(0, 0) + s(1, 1) + s(2, 2)) / 3;
    double dev2 = 0; // s:s of the deviator
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        dev2 += std::pow(s(i, j) + (i == j ? p : 0.0), 2);
    for (int k = 0; k < 6; ++k)
      _fields[k]->x()->mutable_array()[dof] = components[k];
    _fields[6]->x()->mutable_array()[dof] = std::sqrt(1.5 * dev2);
    _fields[7]->x()->mutable_array()[dof] = p;
    const std::int32_t block = tensor_dofmap.cell_dofs(c)[0];
    for (int k = 0; k < 9; ++k)
      _tensor->x()->mutable_array()[9 * block + k] = values(c, k);
  }
}

NodalField::NodalField(const std::string& name,
                       std::shared_ptr<const dolfinx::fem::Function<double>> u)
    : _u(std::move(u))
{
  const auto& V = *_u->function_space();
  _f = std::make_shared<dolfinx::fem::Function<double>>(
      lagrange_space(V.mesh(), 1, V.dofmap()->index_map_bs()));
  _f->name = name;
}

void NodalField::update() { _f->interpolate(*_u); }

namespace
{
void require_field_name(const std::string& name)
{
  if (std::find(field_names.begin(), field_names.end(), name) == field_names.end())
    throw std::logic_error("field name '" + name + "' is not in gelx::field_names (output.h)");
}
} // namespace

void FieldSet::add(const std::string& name,
                   std::shared_ptr<const dolfinx::fem::Function<double>> u)
{
  require_field_name(name);
  _nodal.emplace_back(name, std::move(u));
}

void FieldSet::add(const std::string& name,
                   std::shared_ptr<const dolfinx::fem::Expression<double>> e)
{
  require_field_name(name);
  _cells.emplace_back(name, std::move(e));
}

std::shared_ptr<const dolfinx::fem::Function<double>> FieldSet::nodal(const std::string& name) const
{
  for (const NodalField& f : _nodal)
    if (f.function()->name == name)
      return f.function();
  throw std::runtime_error("no nodal field '" + name + "'");
}

std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>> FieldSet::update()
{
  TimedStage timing("output");
  std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>> fields;
  for (NodalField& f : _nodal)
  {
    f.update();
    fields.push_back(f.function());
  }
  for (CellField& f : _cells)
  {
    f.update();
    fields.insert(fields.end(), f.functions().begin(), f.functions().end());
  }
  return fields;
}

namespace
{
/// Create `folder` for a run's results and clear what an earlier run left there, so that it
/// cannot pass for this run's (steps.csv too, unless this run continues it); returns
/// `folder`. Collective.
const std::filesystem::path& prepare_folder(MPI_Comm comm, const std::filesystem::path& folder,
                                            bool continued)
{
  int ok = 1;
  if (dolfinx::MPI::rank(comm) == 0)
  {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    ok = !ec;
    for (const char* old : {"summary.json", "fields.h5"})
      std::filesystem::remove(folder / old, ec);
    if (!continued)
      std::filesystem::remove(folder / "steps.csv", ec);
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm);
  if (!ok)
    throw InputError("cannot create output folder '" + folder.string() + "'");
  return folder;
}

/// Binary STL: an 80-byte header, the triangle count, then per triangle a normal, three
/// vertices (float32) and two attribute bytes.
void write_binary_stl(std::ostream& out, const std::vector<Triangle>& triangles)
{
  std::array<char, 80> header{};
  const std::string title = "gelx deformed surface";
  std::copy(title.begin(), title.end(), header.begin());
  out.write(header.data(), header.size());
  const auto count = static_cast<std::uint32_t>(triangles.size());
  out.write(reinterpret_cast<const char*>(&count), sizeof(count));
  for (const auto& t : triangles)
  {
    std::array<float, 12> record{}; // normal (left zero: readers use the vertex order), vertices
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k)
        record[3 + 3 * v + k] = static_cast<float>(t[v][k]);
    out.write(reinterpret_cast<const char*>(record.data()), sizeof(record));
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char*>(&attributes), sizeof(attributes));
  }
}
void write_csv_header(std::ostream& out, const std::vector<std::string>& columns)
{
  for (std::size_t i = 0; i < columns.size(); ++i)
    out << (i ? "," : "") << columns[i];
  out << "\n";
}

void write_csv_row(std::ostream& out, const std::vector<std::string>& columns,
                   const nlohmann::json& row)
{
  out.precision(15);
  // A column the row does not have (a leg of another method: the flow has no supports' work
  // where the motion before it had) is written as a missing value, as NaN is (null)
  for (std::size_t i = 0; i < columns.size(); ++i)
    out << (i ? "," : "") << row.value(columns[i], nlohmann::json());
  out << "\n";
}

/// A table's columns: the step and the path's coordinate first (whichever of these a row
/// has, in this order), then the rest alphabetically (a JSON object's order)
std::vector<std::string> keys(const nlohmann::json& row)
{
  static const std::vector<std::string> leading
      = {"step", "mode", "t", "time", "T", "d_over_H", "load_factor", "end_distance"};
  std::vector<std::string> k;
  for (const auto& name : leading)
    if (row.contains(name))
      k.push_back(name);
  for (auto it = row.begin(); it != row.end(); ++it)
    if (std::find(leading.begin(), leading.end(), it.key()) == leading.end())
      k.push_back(it.key());
  return k;
}

} // namespace

nlohmann::json software_versions()
{
  nlohmann::json v;
  v["gelx"] = GELX_VERSION;
  v["dolfinx"] = DOLFINX_VERSION_STRING;
  v["petsc"] = std::to_string(PETSC_VERSION_MAJOR) + "." + std::to_string(PETSC_VERSION_MINOR)
               + "." + std::to_string(PETSC_VERSION_SUBMINOR);
  v["gmsh"] = GMSH_API_VERSION;
  return v;
}

ResultsWriter::ResultsWriter(MPI_Comm comm, const std::filesystem::path& folder,
                             std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
                             std::optional<ResultsProgress> keep, const Units& units)
    : _comm(comm), _folder(folder),
      _fields(comm, prepare_folder(comm, folder, keep.has_value()), *mesh,
              keep ? keep->field_steps : 0),
      _root(dolfinx::MPI::rank(comm) == 0), _units(units)
{
  if (keep)
  {
    continue_steps(keep->rows);
    for (const auto& [name, rows] : keep->tables)
      continue_table(name, rows);
  }
}

void ResultsWriter::continue_table(const std::string& file_name, int rows)
{
  Table& table = _tables[file_name];
  int found = rows;
  if (_root)
  {
    std::ifstream in(_folder / file_name);
    std::string units, header, line, kept;
    std::getline(in, units);
    std::getline(in, header);
    // A row is whole when its newline was written (append_to_file)
    for (found = 0; found < rows && std::getline(in, line) && !in.eof(); ++found)
      kept += line + "\n";
    if (rows > 0)
    {
      std::istringstream names(header);
      for (std::string name; std::getline(names, name, ',');)
        table.columns.push_back(name);
      replace_file(_folder / file_name,
                   [&](std::ostream& file) { file << units << "\n" << header << "\n" << kept; });
    }
    else
      std::filesystem::remove(_folder / file_name); // the columns come from the first row again
  }
  MPI_Bcast(&found, 1, MPI_INT, 0, _comm);
  if (found < rows)
    throw std::runtime_error(file_name + " of " + _folder.string() + " holds "
                             + std::to_string(found) + " rows, not the " + std::to_string(rows)
                             + " to continue from");
  table.rows = rows;
}

void ResultsWriter::continue_steps(int rows)
{
  namespace fs = std::filesystem;
  continue_table("steps.csv", rows);
  if (!_root)
    return;
  // Per-step files of the steps beyond (fields/ is the field series', checkpoint/ the
  // checkpoints')
  static const std::regex per_step(R"(step_(\d+)\..+)");
  std::vector<fs::path> beyond;
  for (auto it = fs::recursive_directory_iterator(_folder);
       it != fs::recursive_directory_iterator(); ++it)
  {
    std::smatch m;
    const std::string name = it->path().filename().string();
    if (it->is_directory() && (name == "fields" || name == "checkpoint"))
      it.disable_recursion_pending();
    else if (it->is_regular_file() && std::regex_match(name, m, per_step)
             && std::stoi(m[1]) > rows)
      beyond.push_back(it->path());
  }
  for (const auto& file : beyond)
    fs::remove(file);
}

ResultsProgress ResultsWriter::progress() const
{
  ResultsProgress progress{_fields.size(), 0, {}};
  for (const auto& [name, table] : _tables)
    if (name == "steps.csv")
      progress.rows = table.rows;
    else
      progress.tables[name] = table.rows;
  return progress;
}

void ResultsWriter::write_fields(
    double t, const std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>& fields)
{
  _fields.write(t, fields);
}


void ResultsWriter::append_step(const nlohmann::json& row) { append_rows("steps.csv", {row}); }

void ResultsWriter::append_rows(const std::string& file_name,
                                const std::vector<nlohmann::json>& rows)
{
  TimedStage timing("output");
  Table& table = _tables[file_name];
  if (!_root || rows.empty())
  {
    table.rows += rows.size();
    return;
  }
  std::ostringstream out;
  const bool starts = table.columns.empty();
  const auto columns = starts ? keys(rows.front()) : table.columns;
  if (starts)
  {
    out << units_line(columns, _units);
    write_csv_header(out, columns);
  }
  for (const auto& row : rows)
    write_csv_row(out, columns, row);
  if (starts) // a table without its header would be no table: written whole or not at all
    replace_file(_folder / file_name, [&](std::ostream& file) { file << out.str(); });
  else
    append_to_file(_folder / file_name, out.str());
  // Written: what progress() reports, and a checkpoint records
  table.columns = columns;
  table.rows += rows.size();
}

void ResultsWriter::write_table(const std::string& file_name,
                                const std::vector<nlohmann::json>& rows)
{
  TimedStage timing("output");
  if (!_root || rows.empty())
    return;
  replace_file(_folder / file_name,
               [&](std::ostream& out)
               {
                 const auto columns = keys(rows.front());
                 out << units_line(columns, _units);
                 write_csv_header(out, columns);
                 for (const auto& row : rows)
                   write_csv_row(out, columns, row);
               });
}

void ResultsWriter::write_summary(const std::string& scene, const std::string& status,
                                  const Parameters& parameters, nlohmann::json quantities)
{
  quantities.update({{"scene", scene},
                     {"status", status},
                     {"parameters", parameters.to_json()},
                     {"versions", software_versions()},
                     {"mpi_ranks", dolfinx::MPI::size(_comm)}});
  quantities["unit_system"] = _units; // what the scene's lengths, forces, energies are in
  quantities["units"] = summary_units(quantities, _units);
  if (_root)
    replace_file(_folder / "summary.json",
                 [&](std::ostream& out) { out << quantities.dump(2) << "\n"; });
}

void ResultsWriter::write_text(const std::string& file_name, const std::string& text)
{
  if (_root)
    replace_file(_folder / file_name, [&](std::ostream& file) { file << text; });
  MPI_Barrier(_comm);
}

void ResultsWriter::write_stl(const std::string& file_name,
                              const std::vector<Triangle>& triangles)
{
  TimedStage timing("output");
  if (!_root)
    return;
  const auto path = _folder / file_name;
  std::filesystem::create_directories(path.parent_path());
  replace_file(path, [&](std::ostream& out) { write_binary_stl(out, triangles); },
               std::ios::binary);
}

std::vector<Triangle> deformed_surface(const dolfinx::fem::Function<double>& u_p1,
                                       const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags,
                                       int tag)
{
  const auto& mesh = *u_p1.function_space()->mesh();
  const int tdim = mesh.topology().dim();
  auto& topology = const_cast<dolfinx::mesh::Topology&>(mesh.topology());
  topology.create_connectivity(tdim - 1, tdim);
  topology.create_connectivity(tdim, tdim - 1);
  const auto f_to_c = topology.connectivity(tdim - 1, tdim);
  const auto c_to_f = topology.connectivity(tdim, tdim - 1);
  const auto facet_vertices = dolfinx::mesh::get_entity_vertices(topology.cell_type(), tdim - 1);
  const std::int32_t owned_facets = topology.index_map(tdim - 1)->size_local();
  const auto& x_dofmap = mesh.geometry().dofmap();
  const auto X = mesh.geometry().x();
  const auto& dofmap = *u_p1.function_space()->dofmap();
  const auto& u = u_p1.x()->array();

  std::vector<double> local; // 9 coordinates per triangle
  for (std::size_t i = 0; i < facet_tags.indices().size(); ++i)
  {
    const std::int32_t facet = facet_tags.indices()[i];
    if (facet_tags.values()[i] != tag || facet >= owned_facets)
      continue;
    const std::int32_t cell = f_to_c->links(facet)[0];
    const auto cell_facets = c_to_f->links(cell);
    const int local_facet = std::distance(
        cell_facets.begin(), std::find(cell_facets.begin(), cell_facets.end(), facet));
    // Current positions of the cell's vertices (the geometry and the P1 dofs follow the
    // reference cell's vertex order)
    const auto nodes = x_dofmap.links(cell);
    const auto dofs = dofmap.cell_dofs(cell);
    auto position = [&](int v)
    {
      std::array<double, 3> x;
      for (int k = 0; k < 3; ++k)
        x[k] = X[3 * nodes[v] + k] + u[3 * dofs[v] + k];
      return x;
    };
    std::array<double, 3> cell_centre{};
    for (std::size_t v = 0; v < dofs.size(); ++v)
      for (int k = 0; k < 3; ++k)
        cell_centre[k] += position(v)[k] / dofs.size();
    const auto fv = facet_vertices.links(local_facet);
    // A quadrilateral's vertices are in tensor-product order: 0 1 3 2 around it
    const std::vector<std::array<int, 3>> splits
        = fv.size() == 4 ? std::vector<std::array<int, 3>>{{0, 1, 3}, {0, 3, 2}}
                         : std::vector<std::array<int, 3>>{{0, 1, 2}};
    for (const auto& split : splits)
    {
      Triangle t;
      for (int v = 0; v < 3; ++v)
        t[v] = position(fv[split[v]]);
      // Outward: the normal points away from the cell's centre
      std::array<double, 3> a, b, n;
      for (int k = 0; k < 3; ++k)
      {
        a[k] = t[1][k] - t[0][k];
        b[k] = t[2][k] - t[0][k];
      }
      n = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
      double outward = 0;
      for (int k = 0; k < 3; ++k)
        outward += n[k] * (t[0][k] - cell_centre[k]);
      if (outward < 0)
        std::swap(t[1], t[2]);
      for (const auto& vertex : t)
        local.insert(local.end(), vertex.begin(), vertex.end());
    }
  }

  // On rank 0 only: every rank's triangles
  std::vector<double> all = all_gather(mesh.comm(), local);
  if (dolfinx::MPI::rank(mesh.comm()) != 0)
    all.clear();
  std::vector<Triangle> triangles(all.size() / 9);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k)
        triangles[i][v][k] = all[9 * i + 3 * v + k];
  return triangles;
}

} // namespace gelx
