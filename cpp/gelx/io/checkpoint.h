#pragma once
/// @file checkpoint.h
/// Checkpoints of a path: the system's unknowns and history with the path's state, written
/// after a step and read back to continue the path (`--restart`), at any number of ranks.

#include <gelx/solvers/path.h>
#include <gelx/systems/system.h>

#include <filesystem>
#include <limits>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <vector>

namespace gelx
{

/// The checkpoints of one path in one folder (a run's OUTPUT/checkpoint). Checkpoint k is the
/// folder step_<k>: `vectors.h5` holds the unknowns (the full vector, not the P1 interpolant
/// of fields.xdmf), the history (NonlinearSystem::save_history) and the arc-length direction;
/// `state.json` the rest of the PathState and the run's record. state.json is written last
/// (aside, then renamed), so a checkpoint is complete or has none, and the newest two
/// complete checkpoints are kept (MOOSE's checkpoint/recover does the same): a run killed
/// while it writes one still has the one before.
///
/// Why vectors are stored by position: a restart on another number of ranks partitions the
/// mesh differently and numbers the unknowns differently. Each row of vectors.h5 names its
/// unknown by its degree of freedom: (sub-space, component, X, Y, Z), the dof's reference
/// position in its (collapsed) sub-space, or for an unknown of no dof (a macro unknown of a
/// MultipointConstraint) (-1, its rank among those in global order, 0, 0, 0). Reading, every
/// rank takes all rows and finds each of its unknowns' rows by that key, positions within
/// 1e-9 of the mesh's extent (coordinates computed on another partition may differ in the
/// last bits).
class Checkpoints
{
public:
  Checkpoints(MPI_Comm comm, std::filesystem::path folder);

  /// Write the checkpoint of step state.step: `system` (the system the path's driver is
  /// given) at its current state, `state`, and `record` (what the run adds: parameters,
  /// outputs, quantities) under "run" in state.json. Then remove all but the newest two.
  /// Collective.
  void write(NonlinearSystem& system, const PathState& state, const nlohmann::json& record);

  /// Remove every checkpoint of the folder (a new run in an old results folder). Collective.
  void clear();

  /// The newest complete checkpoint in `folder` (of a step before `before`), or an empty
  /// path. Reads the file system only.
  static std::filesystem::path newest(const std::filesystem::path& folder,
                                      int before = std::numeric_limits<int>::max());

  /// The contents of a checkpoint's state.json. Throws InputError when it cannot be read.
  /// Reads the file system only.
  static nlohmann::json read_record(const std::filesystem::path& checkpoint);

  /// Restore `system` (unknowns and history) to `checkpoint` and return the path's state
  /// there. Throws InputError, on every rank, when an unknown of `system` has no row in the
  /// checkpoint (another mesh or discretisation). Collective.
  static PathState read(MPI_Comm comm, const std::filesystem::path& checkpoint,
                        NonlinearSystem& system);

private:
  MPI_Comm _comm;
  std::filesystem::path _folder;
  NonlinearSystem* _system = nullptr; ///< the system whose keys are _keys
  std::vector<double> _keys;          ///< 5 per owned unknown (see the class comment)
};

} // namespace gelx
