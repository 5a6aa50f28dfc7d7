#include <gelx/io/field_series.h>
#include <gelx/io/files.h>
#include <gelx/common/timing.h>

#include <dolfinx/common/IndexMap.h>
#include <dolfinx/common/MPI.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/fem/FiniteElement.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/io/HDF5Interface.h>
#include <dolfinx/io/xdmf_mesh.h>
#include <dolfinx/io/xdmf_utils.h>
#include <cstdio>
#include <fstream>
#include <pugixml.hpp>
#include <regex>
#include <sstream>

namespace gelx
{
namespace
{
namespace fs = std::filesystem;

/// "fields/step_000012.h5": where step k's data lives, relative to the folder of fields.xdmf.
std::string numbered(const char* stem, int k)
{
  char name[48];
  std::snprintf(name, sizeof name, "fields/%s_%06d.h5", stem, k);
  return name;
}

/// The step a file under fields/ belongs to (its number), or -1.
int number_of(const fs::path& file)
{
  static const std::regex pattern(R"((mesh|step)_(\d{6})\.h5)");
  std::smatch m;
  const std::string name = file.filename().string();
  return std::regex_match(name, m, pattern) ? std::stoi(m[2]) : -1;
}

/// A function stored per cell (a DG0 space) rather than at the mesh nodes.
bool is_cell_wise(const dolfinx::fem::Function<double>& f)
{
  const auto& dofmap = *f.function_space()->dofmap();
  return dofmap.element_dof_layout().num_dofs() == 1;
}

hid_t open_h5(MPI_Comm comm, const fs::path& path)
{
  return dolfinx::io::HDF5Interface::open_file(comm, path, "w", dolfinx::MPI::size(comm) > 1);
}
} // namespace

FieldSeries::FieldSeries(MPI_Comm comm, const fs::path& folder, const dolfinx::mesh::Mesh& mesh)
    : FieldSeries(comm, folder, mesh, 0)
{
}

FieldSeries::FieldSeries(MPI_Comm comm, const fs::path& folder, const dolfinx::mesh::Mesh& mesh,
                         int keep)
    : _comm(comm), _folder(folder)
{
  const int tdim = mesh.topology().dim();
  _num_nodes = mesh.geometry().index_map()->size_global();
  _num_cells = mesh.topology().index_map(tdim)->size_global();
  const bool root = dolfinx::MPI::rank(comm) == 0;
  int found = keep;
  if (root)
  {
    fs::create_directories(folder / "fields");
    if (keep > 0)
    {
      // Each step's grid is one line of the index (write_index)
      std::ifstream in(folder / "fields.xdmf");
      for (std::string line; std::getline(in, line) && int(_grids.size()) < keep;)
        if (line.find("<Grid Name=\"step_") != std::string::npos)
          _grids.push_back(line);
      found = int(_grids.size());
    }
    for (const auto& file : fs::directory_iterator(folder / "fields"))
      if (number_of(file.path()) > keep)
        fs::remove(file.path());
  }
  MPI_Bcast(&found, 1, MPI_INT, 0, comm);
  if (found < keep)
    throw std::runtime_error("the fields of " + folder.string() + " hold " + std::to_string(found)
                             + " steps, not the " + std::to_string(keep) + " to continue from");
  // Every rank numbers the files by the steps (rank 0 alone writes the index, from its lines)
  _grids.resize(keep);
  // The mesh of the steps this run writes (a restart on another rank count numbers the nodes
  // differently, so the steps before it keep their own mesh file)
  _mesh = mesh_xml(mesh);
  if (root)
    write_index();
}

std::string FieldSeries::mesh_xml(const dolfinx::mesh::Mesh& mesh) const
{
  const std::string file = numbered("mesh", size() + 1);
  const hid_t h5 = open_h5(_comm, _folder / file);
  pugi::xml_document doc;
  pugi::xml_node parent = doc.append_child("Domain");
  dolfinx::io::xdmf_mesh::add_mesh(_comm, parent, h5, mesh, "mesh");
  dolfinx::io::HDF5Interface::close_file(h5);
  // add_mesh names the data by the HDF5 file's name alone; it lives under fields/
  std::ostringstream xml;
  for (pugi::xml_node part : parent.child("Grid").children())
  {
    pugi::xml_node data = part.child("DataItem");
    const std::string where = data.text().get();
    data.text().set((file + where.substr(where.find(':'))).c_str());
    part.print(xml, "", pugi::format_raw);
  }
  return xml.str();
}

void FieldSeries::write(double t,
                        const std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>& fields)
{
  TimedStage timing("output");
  const int k = size() + 1;
  const std::string file = numbered("step", k);
  const bool parallel = dolfinx::MPI::size(_comm) > 1;
  std::ostringstream grid;
  grid.precision(17);
  grid << "<Grid Name=\"step_" << file.substr(12, 6) << "\" GridType=\"Uniform\"><Time Value=\""
       << t << "\"/>" << _mesh;
  const hid_t h5 = open_h5(_comm, _folder / file);
  for (const auto& f : fields)
  {
    const bool cells = is_cell_wise(*f);
    const std::vector<double> values = cells ? dolfinx::io::xdmf_utils::get_cell_data_values(*f)
                                             : dolfinx::io::xdmf_utils::get_point_data_values(*f);
    const std::int64_t width = f->function_space()->element()->value_size();
    const std::int64_t rows = values.size() / width;
    std::int64_t first = 0;
    MPI_Exscan(&rows, &first, 1, MPI_INT64_T, MPI_SUM, _comm);
    const std::int64_t total = cells ? _num_cells : _num_nodes;
    dolfinx::io::HDF5Interface::write_dataset(h5, "/" + f->name, values.data(),
                                              {first, first + rows}, {total, width}, parallel,
                                              false);
    // By width: a blocked space's value shape is flat, (9) for a 3x3 tensor
    const char* kind = width == 1 ? "Scalar" : width == 9 ? "Tensor" : "Vector";
    grid << "<Attribute Name=\"" << f->name << "\" AttributeType=\"" << kind << "\" Center=\""
         << (cells ? "Cell" : "Node") << "\"><DataItem Dimensions=\"" << total << " " << width
         << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << file << ":/" << f->name
         << "</DataItem></Attribute>";
  }
  dolfinx::io::HDF5Interface::close_file(h5); // collective: every rank's part is written
  grid << "</Grid>";
  _grids.push_back(grid.str());
  if (dolfinx::MPI::rank(_comm) == 0)
    write_index();
}

void FieldSeries::write_index() const
{
  replace_file(_folder / "fields.xdmf",
               [&](std::ostream& out)
               {
                 out << "<?xml version=\"1.0\"?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
                     << "<Grid Name=\"fields\" GridType=\"Collection\" "
                        "CollectionType=\"Temporal\">\n";
                 for (const auto& grid : _grids)
                   out << grid << "\n";
                 out << "</Grid>\n</Domain>\n</Xdmf>\n";
               });
}

} // namespace gelx
