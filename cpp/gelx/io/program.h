#pragma once
/// @file program.h
/// The frame every gelx program shares: parameters, PETSc start-up, the run record
/// (summary.json), one-line errors.

#include <gelx/io/output.h>
#include <gelx/io/parameters.h>
#include <gelx/solvers/path.h>
#include <gelx/io/progress.h>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>

namespace gelx
{
class Checkpoints;

/// The record of one run of a scene: its results folder, its clock, and the quantities of
/// interest that go into summary.json. run_program writes summary.json when the run ends,
/// completed or failed, with the scene's name, its status, every scene parameter, every PETSc
/// option in effect (read back from the options database), the library versions, the MPI
/// ranks and the wall time; the scene keeps `summary` current as it goes, so that a failed
/// run's summary holds what it reached.
///
/// Checkpoint and restart: the scene starts its path with start_path(system) and gives the
/// path the observer checkpoints(), last; every --checkpoint_every steps it writes a
/// checkpoint (checkpoint.h) into OUTPUT/checkpoint, with the parameters, the results
/// written so far and `summary`. `--restart DIR` runs the scene again with the parameters of
/// DIR's newest checkpoint and the PETSc options it was started with (those the restart's
/// command line does not set): results(mesh) continues DIR's outputs after the checkpoint's
/// step, start_path(system) restores the system and returns the checkpoint's path state, and
/// the driver continues the path from there.
class Run
{
public:
  /// `checkpoint`: the checkpoint a restarted run (--restart) continues from; empty for a new
  /// run.
  Run(MPI_Comm comm, std::string scene, const Parameters& parameters,
      std::filesystem::path checkpoint = {});
  ~Run();

  MPI_Comm comm() const { return _comm; }
  /// The writer of the results folder (--output) for `mesh`, made at the first call, writing
  /// quantities in `units`; on a restart it continues the folder's outputs after the
  /// checkpoint's.
  ResultsWriter& results(std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
                         const Units& units = millimetre);
  /// Seconds since the run started.
  double elapsed() const;

  /// Where the scene's path starts: PathState{} for a new run; on a restart, the checkpoint's
  /// state, with `system` (the system the path's driver is given, at its initial state) set
  /// to the checkpoint's unknowns and history and `summary` to its quantities. checkpoints()
  /// saves this system. One path per run. Collective.
  PathState start_path(NonlinearSystem& system);
  /// The observer that writes a checkpoint of the path every --checkpoint_every steps. Put it
  /// last among the path's observers, so that the checkpoint covers their output of the step.
  StepObserver checkpoints();

  /// The scene's quantities of interest.
  nlohmann::json summary = nlohmann::json::object();

  /// Write summary.json with `status` ("completed" or "failed: why"), if the run made its
  /// results folder. Collective.
  void finish(const std::string& status);
  /// The same without communicating, from what this rank holds (rank 0 writes), for an error
  /// that may have struck one rank alone; a write that fails too (a full disk) is given up.
  void finish_alone(const std::string& status) noexcept;

private:
  /// What this rank knows of the run record, without communicating: `summary`, the wall
  /// time, the PETSc options, where a restart continued from
  nlohmann::json local_record() const;
  /// A new run removes the checkpoints of an earlier run in its folder (once)
  void forget_old_checkpoints();

  MPI_Comm _comm;
  std::string _scene;
  const Parameters& _parameters;
  std::chrono::steady_clock::time_point _start;
  std::unique_ptr<ResultsWriter> _results;
  std::filesystem::path _restart_from; ///< the checkpoint continued, or empty
  nlohmann::json _restart_record;      ///< its state.json
  nlohmann::json _given_petsc_options; ///< the options the run started with (checkpointed)
  std::unique_ptr<Checkpoints> _checkpoints;
  NonlinearSystem* _path_system = nullptr; ///< the system of start_path()
  bool _old_checkpoints_forgotten = false;
};

/// Run a gelx program.
///
/// Reads the scene parameters (plus `--output DIR`, `--checkpoint_every N` and `--restart DIR`,
/// declared here) from the command line; with --restart, the scene parameters are those of the
/// checkpoint (the command line may not change them; PETSc options it may) and the output
/// folder is DIR (see Run). Starts PETSc and SLEPc with what remains (the options database),
/// echoes the parameters, and runs `body`, then writes the run record. A PETSc option that no solver object read ends
/// the run like an unknown scene parameter: at the first step after its solver has run (a
/// misspelt option of that solver), or at the end. Every error ends as one line `NAME: error: ...` on
/// stderr and exit code 1; `--help` prints the parameter table and exits 0. Input errors are
/// found on every rank before any collective call, so no rank is left waiting.
int run_program(int argc, char* argv[], const std::string& name, Parameters& parameters,
                const std::function<void(Run&)>& body);

} // namespace gelx
