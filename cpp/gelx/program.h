#pragma once
/// @file program.h
/// The frame every gelx program shares: parameters, PETSc start-up, the run record
/// (summary.json), one-line errors.

#include "output.h"
#include "parameters.h"
#include <chrono>
#include <functional>
#include <memory>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>

namespace gelx
{

/// The record of one run of a scene: its results folder, its clock, and the quantities of
/// interest that go into summary.json. run_program writes summary.json when the run ends,
/// completed or failed, with the scene's name, its status, every scene parameter, every PETSc
/// option in effect (read back from the options database), the library versions, the MPI
/// ranks and the wall time; the scene keeps `summary` current as it goes, so that a failed
/// run's summary holds what it reached.
class Run
{
public:
  Run(MPI_Comm comm, std::string scene, const Parameters& parameters);

  MPI_Comm comm() const { return _comm; }
  /// The writer of the results folder (--output) for `mesh`, made at the first call.
  ResultsWriter& results(std::shared_ptr<const dolfinx::mesh::Mesh> mesh);
  /// Seconds since the run started.
  double elapsed() const;

  /// The scene's quantities of interest.
  nlohmann::json summary = nlohmann::json::object();

  /// Write summary.json with `status` ("completed" or "failed: why"), if the run made its
  /// results folder. Collective.
  void finish(const std::string& status);

private:
  MPI_Comm _comm;
  std::string _scene;
  const Parameters& _parameters;
  std::chrono::steady_clock::time_point _start;
  std::unique_ptr<ResultsWriter> _results;
};

/// Run a gelx program.
///
/// Reads the scene parameters (plus `--output DIR`, declared here) from the command line,
/// starts PETSc and SLEPc with what remains (the options database), echoes the parameters, and
/// runs `body`, then writes the run record. A PETSc option that no solver object read ends
/// the run like an unknown scene parameter. Every error ends as one line `NAME: error: ...` on
/// stderr and exit code 1; `--help` prints the parameter table and exits 0. Input errors are
/// found on every rank before any collective call, so no rank is left waiting.
int run_program(int argc, char* argv[], const std::string& name, Parameters& parameters,
                const std::function<void(Run&)>& body);

} // namespace gelx
