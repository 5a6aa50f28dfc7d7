#pragma once
/// @file output.h
/// Results of a run: XDMF/HDF5 field series, a per-step CSV, and summary.json.
///
/// Every file is replaced whole by a complete new version (written aside, then renamed), so a
/// run stopped half-way, even by SIGKILL, leaves every completed step readable: ParaView opens
/// fields.xdmf, steps.csv has one row per completed step.

#include <gelx/io/field_series.h>
#include <gelx/io/units.h>

#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/Mesh.h>
#include <array>
#include <dolfinx/mesh/MeshTags.h>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace gelx
{
class Parameters;

/// Lagrange space of the given degree and block size on the mesh's cell (discontinuous for
/// degree 0): for fields made for output.
std::shared_ptr<dolfinx::fem::FunctionSpace>
lagrange_space(std::shared_ptr<const dolfinx::mesh::Mesh> mesh, int degree, int block_size);

/// Cell-wise (DG0) output of a UFL Expression evaluated at the cell midpoints.
///
/// A scalar expression gives one field NAME. A 3x3 tensor (the Cauchy stress) gives the tensor
/// NAME (nine components, row by row, which ParaView reads as a tensor) and scalar fields
/// ParaView plots directly: its six components NAME_xx, NAME_yy, NAME_zz, NAME_yz, NAME_xz,
/// NAME_xy, the von Mises stress NAME_vm = sqrt(3/2 s:s) and the pressure NAME_p = -tr/3.
class CellField
{
public:
  CellField(const std::string& name, std::shared_ptr<const dolfinx::fem::Expression<double>> e);
  /// Re-evaluate the expression at the current state.
  void update();
  const std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>& functions() const
  {
    return _outputs;
  }

private:
  std::shared_ptr<const dolfinx::fem::Expression<double>> _expression;
  std::vector<std::shared_ptr<dolfinx::fem::Function<double>>> _fields;
  std::shared_ptr<dolfinx::fem::Function<double>> _tensor; ///< a 3x3 expression's, or null
  std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>> _outputs;
};

/// The displacement interpolated into vertex values (P1), which XDMF stores on the mesh nodes.
class NodalField
{
public:
  NodalField(const std::string& name, std::shared_ptr<const dolfinx::fem::Function<double>> u);
  void update();
  std::shared_ptr<dolfinx::fem::Function<double>> function() const { return _f; }

private:
  std::shared_ptr<const dolfinx::fem::Function<double>> _u;
  std::shared_ptr<dolfinx::fem::Function<double>> _f;
};

/// The names of the fields gelx writes, one name a quantity in every scene's fields.xdmf,
/// `./gelx view --field` and the READMEs (a tensor's outputs add _xx, _yy, _zz, _yz, _xz, _xy,
/// _vm for von Mises and _p for the pressure -tr/3; tests/vocabulary.py checks every scene's
/// output against this list):
/// - displacement (mm, or the scene's length unit; at the nodes)
/// - cauchy_stress (MPa, or the scene's stress unit; per cell; the 3x3 tensor and its outputs)
/// - energy_density (strain energy per reference volume; per cell)
/// - contact_status (1 in contact, 0 free), contact_gap (length), contact_force (nodal force;
///   at the candidate nodes of a contact)
/// - mode (a buckling mode's shape, normalised; modes/*.xdmf)
inline const std::vector<std::string> field_names
    = {"displacement", "cauchy_stress", "energy_density", "contact_status", "contact_gap",
       "contact_force", "mode", "chemical_potential", "swelling_ratio", "target_displacement"};

/// The fields a scene writes at every step, updated and written together: displacements at
/// the mesh nodes (NodalField), stresses and energy densities per cell (CellField). Each
/// name must be one of field_names (std::logic_error otherwise: a new quantity is added
/// there, once).
class FieldSet
{
public:
  /// A field at the nodes: u interpolated into vertex values.
  void add(const std::string& name, std::shared_ptr<const dolfinx::fem::Function<double>> u);
  /// A field per cell, from an Expression (a 3x3 tensor gives its components, von Mises and
  /// pressure; see CellField).
  void add(const std::string& name, std::shared_ptr<const dolfinx::fem::Expression<double>> e);
  /// Update every field at the current state; returns them for writing.
  std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>> update();
  /// The vertex values of the nodal field `name` (at the last update).
  std::shared_ptr<const dolfinx::fem::Function<double>> nodal(const std::string& name) const;

private:
  std::vector<NodalField> _nodal;
  std::vector<CellField> _cells;
};

/// Versions of gelx (its git commit) and of the libraries it runs on, as {name: version}.
nlohmann::json software_versions();

/// A triangle of a surface, its vertices counter-clockwise seen from outside.
using Triangle = std::array<std::array<double, 3>, 3>;

/// The deformed surface of the facets tagged `tag` (x = X + u at the vertices), gathered on
/// rank 0 (other ranks get none): for optics or CAD codes that read STL. `u_p1` is a vertex
/// displacement (NodalField::function()); quadrilateral facets are split in two triangles.
/// Collective.
std::vector<Triangle> deformed_surface(const dolfinx::fem::Function<double>& u_p1,
                                       const dolfinx::mesh::MeshTags<std::int32_t>& facet_tags,
                                       int tag);

/// How far a results folder has got: what a checkpoint records and a restart keeps.
struct ResultsProgress
{
  int field_steps = 0; ///< steps of fields.xdmf
  int rows = 0;        ///< rows of steps.csv
  std::map<std::string, int> tables; ///< rows of the other tables grown by append_rows
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(ResultsProgress, field_steps, rows, tables)

/// Writes one run's results into one folder.
///
/// Per-step files (write_stl) are named `.../step_<k>.<ext>`, k the row of steps.csv they
/// belong to, so that a restart can remove those of the steps it takes again.
class ResultsWriter
{
public:
  /// Creates `folder` and starts its field series (fields.xdmf, fields/) on `mesh`; or, given
  /// `keep` (a restart), continues the results there after the first keep->field_steps steps
  /// of fields.xdmf and keep->rows rows of steps.csv (and keep->tables' rows of the tables
  /// append_rows grows), removing what was written beyond them (per-step files step_<k> with
  /// k > keep->rows included). Throws std::runtime_error when the folder holds less.
  /// Quantities are written in `units` (units.h). Collective.
  ResultsWriter(MPI_Comm comm, const std::filesystem::path& folder,
                std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
                std::optional<ResultsProgress> keep = std::nullopt,
                const Units& units = millimetre);

  /// Append the fields at time (load factor) t to fields.xdmf as one step.
  void write_fields(double t,
                    const std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>& f);

  /// Append one row to steps.csv (columns from the first row's keys: `step` and the path's
  /// coordinate, t, T, d_over_H, ..., first, then the rest alphabetically; above the header, a
  /// comment line with each column's unit, units_line). The file is created whole with its
  /// first row, then grows by appending (append_to_file): what it holds up to its last
  /// newline are whole rows.
  void append_step(const nlohmann::json& row);

  /// Append rows to the table folder/file_name (columns and units as steps.csv's), which a
  /// restart continues as it does steps.csv: a table that grows with the path.
  void append_rows(const std::string& file_name, const std::vector<nlohmann::json>& rows);

  /// Write a whole table (columns and units as steps.csv's) to folder/file_name.
  void write_table(const std::string& file_name, const std::vector<nlohmann::json>& rows);

  /// Write `text` to folder/file_name (rank 0; atomically). Collective.
  void write_text(const std::string& file_name, const std::string& text);

  /// Write triangles (of deformed_surface, on rank 0) as binary STL to folder/file_name.
  void write_stl(const std::string& file_name, const std::vector<Triangle>& triangles);

  /// Write summary.json (atomically: a reader never sees half a file): the run's record —
  /// scene, status ("completed" or "failed: why"), parameters, library versions, MPI ranks —
  /// and the scene's `quantities`, with the unit of each under "units" (summary_units) and the
  /// scene's Units under "unit_system" (the unit of its length parameters, too).
  void write_summary(const std::string& scene, const std::string& status,
                     const Parameters& parameters, nlohmann::json quantities);

  const std::filesystem::path& folder() const { return _folder; }
  /// Steps of fields.xdmf and rows of steps.csv and of the other tables written so far
  /// (those kept on a restart included).
  ResultsProgress progress() const;

private:
  /// Keep the header and the first `rows` rows of the table file_name (none: no file; rank 0).
  /// Throws when it has fewer rows. Collective.
  void continue_table(const std::string& file_name, int rows);
  /// The same for steps.csv, and remove the per-step files beyond its rows (rank 0).
  void continue_steps(int rows);

  /// A table that grows by rows: its columns (rank 0) and its number of rows
  struct Table
  {
    std::vector<std::string> columns;
    int rows = 0;
  };

  MPI_Comm _comm;
  std::filesystem::path _folder;
  FieldSeries _fields;
  std::map<std::string, Table> _tables; ///< steps.csv and those of append_rows
  bool _root;
  Units _units;
};


} // namespace gelx
