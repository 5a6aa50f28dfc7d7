#pragma once
/// @file field_series.h
/// fields.xdmf: the fields of a run, one grid per step, for ParaView.

#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/Mesh.h>
#include <filesystem>
#include <memory>
#include <mpi.h>
#include <string>
#include <vector>

namespace gelx
{

/// A time series of fields on one mesh: `fields.xdmf` indexes one grid per step that holds every
/// field written at that step, so ParaView opens one dataset with all its arrays and a time
/// slider. The mesh is stored once, in `fields/mesh.h5`; the data of step k in
/// `fields/step_<k>.h5`. Functions of degree 1 are stored at the mesh nodes (Center="Node"),
/// cell-wise (DG0) ones per cell (Center="Cell").
///
/// Why one HDF5 file per step: a run killed while it writes (SIGKILL, an exhausted disk) must
/// leave every completed step readable. Appending to a single HDF5 file risks all of them, as
/// HDF5 1.10 keeps no journal and an interrupted metadata flush can leave the file unreadable.
/// Here a step's file is complete and closed before the index is replaced (written aside, then
/// renamed: atomic on POSIX file systems), so fields.xdmf only ever names complete files.
class FieldSeries
{
public:
  /// Start a series in `folder` (fields.xdmf, fields/): writes the mesh, an empty index, and
  /// removes the step files of an earlier run there. Collective.
  FieldSeries(MPI_Comm comm, const std::filesystem::path& folder, const dolfinx::mesh::Mesh& mesh);

  /// Continue the series in `folder` after its first `keep` steps (a restart): the index and
  /// the step files beyond them are dropped. Throws std::runtime_error when the folder holds
  /// fewer steps. Collective.
  FieldSeries(MPI_Comm comm, const std::filesystem::path& folder, const dolfinx::mesh::Mesh& mesh,
              int keep);

  /// Append a step at time t holding `fields` (each with its own name). Collective.
  void write(double t,
             const std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>& fields);

  /// Steps written so far.
  int size() const { return static_cast<int>(_grids.size()); }

private:
  /// The Topology and Geometry elements that every step's grid repeats
  std::string mesh_xml(const dolfinx::mesh::Mesh& mesh) const;
  /// Replace fields.xdmf by the current list of grids (rank 0)
  void write_index() const;

  MPI_Comm _comm;
  std::filesystem::path _folder;
  std::int64_t _num_nodes, _num_cells; ///< global sizes of the point and cell arrays
  std::string _mesh;                   ///< Topology and Geometry XML
  std::vector<std::string> _grids;     ///< one <Grid> element per step
};

} // namespace gelx
