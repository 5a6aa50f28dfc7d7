#include <gelx/common/timing.h>

#include <gelx/common/petsc_utils.h>

#include <algorithm>
#include <array>
#include <map>
#include <sys/resource.h>

namespace gelx
{
namespace
{
const std::array<std::string, 3> gelx_stages = {"mesh", "output", "stability"};

PetscLogStage stage_id(const std::string& name)
{
  static std::map<std::string, PetscLogStage> registered;
  if (!registered.count(name))
    GELX_PETSC(PetscLogStageRegister(name.c_str(), &registered[name]));
  return registered.at(name);
}

/// gelx's assembly event (TimedAssembly), registered at its first use
PetscLogEvent assembly_event()
{
  static const PetscLogEvent id = []
  {
    PetscClassId gelx_class;
    GELX_PETSC(PetscClassIdRegister("gelx", &gelx_class));
    PetscLogEvent event;
    GELX_PETSC(PetscLogEventRegister("GelxAssembly", gelx_class, &event));
    return event;
  }();
  return id;
}

/// The time of PETSc event `id` (s) over every stage but gelx's own
double event_time(PetscLogEvent id)
{
  PetscStageLog log;
  GELX_PETSC(PetscLogGetStageLog(&log));
  double time = 0;
  for (int s = 0; s < log->numStages; ++s)
  {
    if (std::find(gelx_stages.begin(), gelx_stages.end(), log->stageInfo[s].name)
        != gelx_stages.end())
      continue;
    PetscEventPerfInfo info;
    GELX_PETSC(PetscLogEventGetPerfInfo(s, id, &info));
    time += info.time;
  }
  return time;
}

/// The same for the event named `event` (0 if no package the run used registered it)
double event_time(const char* event)
{
  PetscLogEvent id;
  GELX_PETSC(PetscLogEventGetId(event, &id));
  return id < 0 ? 0 : event_time(id);
}

/// The time spent in gelx stage `name` so far (s; 0 if never pushed)
double stage_time(const std::string& name)
{
  PetscStageLog log;
  GELX_PETSC(PetscLogGetStageLog(&log));
  const PetscLogStage s = stage_id(name);
  return log->stageInfo[s].used ? log->stageInfo[s].perfInfo.time : 0.0;
}
} // namespace

TimedStage::TimedStage(const std::string& name) { GELX_PETSC(PetscLogStagePush(stage_id(name))); }

TimedStage::~TimedStage() { PetscLogStagePop(); }

TimedAssembly::TimedAssembly() { GELX_PETSC(PetscLogEventBegin(assembly_event(), 0, 0, 0, 0)); }

TimedAssembly::~TimedAssembly() { PetscLogEventEnd(assembly_event(), 0, 0, 0, 0); }

NestedSolves::NestedSolves()
{
  for (std::size_t i = 0; i < _events.size(); ++i)
  {
    GELX_PETSC(PetscLogEventGetId(i == 0 ? "KSPSolve" : "PCSetUp", &_events[i]));
    if (_events[i] >= 0)
      GELX_PETSC(PetscLogEventDeactivatePush(_events[i]));
  }
}

NestedSolves::~NestedSolves()
{
  for (PetscLogEvent event : _events)
    if (event >= 0)
      PetscLogEventDeactivatePop(event);
}

void start_timing() { GELX_PETSC(PetscLogDefaultBegin()); }

nlohmann::json time_split(MPI_Comm comm, double wall_time)
{
  // Events are inclusive, so only events that do not nest are added: PETSc 3.18 logs a
  // preconditioner's set-up (the factorisation) outside KSPSolve (measured with -log_view:
  // PCSetUp 8.3 s, KSPSolve 1.3 s for the bistrip); a nested preconditioner (fieldsplit)
  // would count its blocks' set-up twice
  std::map<std::string, double> split
      = {{"assembly", event_time("SNESFunctionEval") + event_time("SNESJacobianEval")
                          + event_time(assembly_event())},
         {"solve", event_time("KSPSolve") + event_time("PCSetUp")}};
  double accounted = split["assembly"] + split["solve"];
  for (const std::string& name : gelx_stages)
    accounted += split[name] = stage_time(name);
  split["other"] = wall_time - accounted;
  nlohmann::json json;
  for (auto& [name, seconds] : split)
  {
    MPI_Allreduce(MPI_IN_PLACE, &seconds, 1, MPI_DOUBLE, MPI_MAX, comm);
    json[name] = seconds;
  }
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  double peak = usage.ru_maxrss / 1024.0, total = peak; // ru_maxrss: KiB on Linux
  MPI_Allreduce(MPI_IN_PLACE, &peak, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_DOUBLE, MPI_SUM, comm);
  return {{"time_split", json},
          {"peak_memory_MiB", {{"sum_over_ranks", total}, {"largest_rank", peak}}}};
}

} // namespace gelx
