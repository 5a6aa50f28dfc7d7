#pragma once
/// @file timing.h
/// Where a run's wall time goes, for summary.json: PETSc's own event log for the work inside
/// its solvers (SNES residual and tangent evaluations, KSP solves) and gelx log stages for the
/// work PETSc does not see (meshing, output, stability counts). PETSc's log is used, not
/// timers of our own, so that `-log_view` shows the same split in full detail.

#include <array>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <petsclog.h>
#include <string>

namespace gelx
{

/// The PETSc log stage `name` ("mesh", "output" or "stability"), pushed for the lifetime of
/// the object. PETSc stages are exclusive: a stage pushed inside another takes its time from
/// the enclosing one (a stability count inside an output is not output time).
class TimedStage
{
public:
  explicit TimedStage(const std::string& name);
  ~TimedStage();
  TimedStage(const TimedStage&) = delete;
  TimedStage& operator=(const TimedStage&) = delete;
};

/// While alive, PETSc's log counts the time as assembly (a gelx event, added to SNES's
/// residual and tangent evaluations by time_split): for evaluations outside any SNES, such as
/// an arc-length predictor's tangent, which SNES's events do not see and time_split would
/// otherwise count as "other". Not for evaluations inside a SNES callback (counted twice).
class TimedAssembly
{
public:
  TimedAssembly();
  ~TimedAssembly();
  TimedAssembly(const TimedAssembly&) = delete;
  TimedAssembly& operator=(const TimedAssembly&) = delete;
};

/// While alive, PETSc does not log KSPSolve and PCSetUp: for solves nested in a solve whose
/// events already time them (the arc-length system's solves with its wrapped tangent, inside
/// the bordered system's KSPSolve), which time_split would otherwise count twice.
class NestedSolves
{
public:
  NestedSolves();
  ~NestedSolves();
  NestedSolves(const NestedSolves&) = delete;
  NestedSolves& operator=(const NestedSolves&) = delete;

private:
  std::array<PetscLogEvent, 2> _events;
};

/// Start PETSc's default event log (what -log_view turns on): called once, after
/// PetscInitialize, by run_program.
void start_timing();

/// The split of `wall_time` (s, this rank's run so far) into mesh, assembly (the SNES residual
/// and tangent evaluations, and those outside SNES a TimedAssembly times), solve (the KSP solves and preconditioner set-ups: the
/// factorisations, those of SLEPc's spectral transformations too), stability,
/// output and other (the rest: set-up, scene analysis, time stepping's own work), each the
/// largest over the ranks; and the peak resident memory of the ranks (MiB: the sum over
/// ranks, and the largest one): {"time_split": {...}, "peak_memory_MiB": {...}}. Collective.
nlohmann::json time_split(MPI_Comm comm, double wall_time);

} // namespace gelx
