#include "output.h"
#include "parameters.h"

#include <basix/finite-element.h>
#include <dolfinx/common/MPI.h>
#include <dolfinx/common/version.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/io/XDMFFile.h>
#include <cmath>
#include <fstream>
#include <numeric>
#include <xtensor/xtensor.hpp>
#include <gmsh.h>
#include <petscversion.h>

namespace gelx
{
namespace
{
/// Lagrange space of the given degree on the mesh's cell (discontinuous for degree 0).
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
} // namespace

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

ResultsWriter::ResultsWriter(MPI_Comm comm, const std::filesystem::path& folder,
                             std::shared_ptr<const dolfinx::mesh::Mesh> mesh)
    : _comm(comm), _folder(folder), _root(dolfinx::MPI::rank(comm) == 0)
{
  int ok = 1;
  if (_root)
  {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    ok = !ec;
    // Results of a previous run in the same folder must not pass for this run's
    std::filesystem::remove(folder / "steps.csv", ec);
    std::filesystem::remove(folder / "summary.json", ec);
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm);
  if (!ok)
    throw InputError("cannot create output folder '" + folder.string() + "'");
  dolfinx::io::XDMFFile file(comm, folder / "fields.xdmf", "w");
  file.write_mesh(*mesh);
}

void ResultsWriter::write_fields(
    double t, const std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>& fields)
{
  dolfinx::io::XDMFFile file(_comm, _folder / "fields.xdmf", "a");
  for (const auto& f : fields)
    file.write_function(*f, t);
  file.close();
}

namespace
{
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
  for (std::size_t i = 0; i < columns.size(); ++i)
    out << (i ? "," : "") << row.at(columns[i]);
  out << "\n";
}

std::vector<std::string> keys(const nlohmann::json& row)
{
  std::vector<std::string> k;
  for (auto it = row.begin(); it != row.end(); ++it)
    k.push_back(it.key());
  return k;
}
} // namespace

void ResultsWriter::append_step(const nlohmann::json& row)
{
  if (!_root)
    return;
  const bool first = _columns.empty();
  if (first)
    _columns = keys(row);
  std::ofstream out(_folder / "steps.csv", std::ios::app);
  if (first)
    write_csv_header(out, _columns);
  write_csv_row(out, _columns, row);
}

void ResultsWriter::write_table(const std::string& file_name,
                                const std::vector<nlohmann::json>& rows)
{
  if (!_root || rows.empty())
    return;
  std::ofstream out(_folder / file_name);
  const auto columns = keys(rows.front());
  write_csv_header(out, columns);
  for (const auto& row : rows)
    write_csv_row(out, columns, row);
}

void ResultsWriter::write_summary(const nlohmann::json& summary)
{
  if (!_root)
    return;
  const auto tmp = _folder / "summary.json.tmp";
  {
    std::ofstream out(tmp);
    out << summary.dump(2) << "\n";
  }
  std::filesystem::rename(tmp, _folder / "summary.json");
}

nlohmann::json software_versions()
{
  nlohmann::json v;
  v["gelx"] = "0.1";
  v["dolfinx"] = DOLFINX_VERSION_STRING;
  v["petsc"] = std::to_string(PETSC_VERSION_MAJOR) + "." + std::to_string(PETSC_VERSION_MINOR)
               + "." + std::to_string(PETSC_VERSION_SUBMINOR);
  v["gmsh"] = GMSH_API_VERSION;
  return v;
}

} // namespace gelx
