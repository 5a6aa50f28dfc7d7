#include <gelx/io/program.h>
#include <gelx/io/checkpoint.h>
#include <gelx/io/sources.h>
#include <gelx/solvers/path.h>
#include <gelx/common/petsc_utils.h>
#include <gelx/common/timing.h>

#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <dolfinx/common/log.h>
#include <hdf5.h>
#include <iostream>
#include <petscsys.h>
#include <slepcsys.h>
#include <sstream>

namespace gelx
{
namespace
{
/// What failed in HDF5's last error, as " (REASON writing FILE)", from the innermost entry of
/// its error stack that names them (a full disk: "No space left on device"); "" when none.
/// dolfinx's own message says only which HDF5 call failed ("Failed to close HDF5 dataset.").
std::string hdf5_failure()
{
  std::string found;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* entry, void* data) -> herr_t
      {
        const std::string desc = entry->desc ? entry->desc : "";
        auto quoted = [&](const std::string& key)
        {
          const auto at = desc.find(key + " = '");
          if (at == std::string::npos)
            return std::string();
          const auto start = at + key.size() + 4;
          return desc.substr(start, desc.find('\'', start) - start);
        };
        const std::string reason = quoted("error message"), file = quoted("filename");
        auto& text = *static_cast<std::string*>(data);
        if (text.empty() && !reason.empty())
          text = " (" + reason + (file.empty() ? "" : " writing " + file) + ")";
        return 0;
      },
      &found);
  return found;
}

/// The parameters that belong to the run, not to the scene: a restart may set them.
bool is_run_parameter(const std::string& name)
{
  return name == "output" || name == "checkpoint_every" || name == "restart"
         || name == "stop_after_steps";
}

/// With --restart DIR: DIR's newest checkpoint, whose scene parameters `parameters` takes
/// over, with --output DIR; an empty path for a new run. Throws InputError when DIR has no
/// checkpoint or the command line sets a scene parameter to another value than the
/// checkpoint's.
std::filesystem::path restart_checkpoint(Parameters& parameters)
{
  const std::string folder = parameters.text("restart");
  if (folder.empty())
    return {};
  const std::filesystem::path checkpoint
      = Checkpoints::newest(std::filesystem::path(folder) / "checkpoint");
  if (checkpoint.empty())
    throw InputError("--restart " + folder + ": no complete checkpoint in " + folder
                     + "/checkpoint");
  const nlohmann::json saved = Checkpoints::read_record(checkpoint).at("run").at("parameters");
  const nlohmann::json given = parameters.to_json();
  for (const std::string& name : parameters.given())
  {
    if (name == "output" && given.at(name) != folder)
      throw InputError("--restart " + folder + " continues the run in " + folder
                       + ": --output may not name another folder");
    const nlohmann::json there = saved.value(name, nlohmann::json());
    if (!is_run_parameter(name) && given.at(name) != there)
      throw InputError("--restart continues a run with the parameters of its checkpoint: --"
                       + name + " may not be changed (" + there.dump() + " there)");
  }
  for (const auto& [name, value] : saved.items())
    if (!is_run_parameter(name))
      parameters.set(name, value.is_string() ? value.get<std::string>() : value.dump());
  parameters.set("output", folder);
  return checkpoint;
}
} // namespace

Run::Run(MPI_Comm comm, std::string scene, const Parameters& parameters,
         std::filesystem::path checkpoint)
    : _comm(comm), _scene(std::move(scene)), _parameters(parameters),
      _start(std::chrono::steady_clock::now()), _restart_from(std::move(checkpoint)),
      _checkpoints(std::make_unique<Checkpoints>(
          comm, std::filesystem::path(parameters.text("output")) / "checkpoint"))
{
  // The solver options the run was started with (the command line's, before the scene sets
  // its defaults): a checkpoint keeps them, so that a restart continues with the same
  // solvers (the restart's own command line wins)
  _given_petsc_options = petsc_options();
  if (_restart_from.empty())
    return;
  _restart_record = Checkpoints::read_record(_restart_from);
  const nlohmann::json saved
      = _restart_record.at("run").value("petsc_options", nlohmann::json::object());
  for (const auto& [option, value] : saved.items())
  {
    const std::string flag = "-" + option;
    PetscBool given;
    GELX_PETSC(PetscOptionsHasName(nullptr, nullptr, flag.c_str(), &given));
    if (!given)
    {
      const std::string text = value.is_null() ? "" : value.get<std::string>();
      GELX_PETSC(PetscOptionsSetValue(nullptr, flag.c_str(),
                                      value.is_null() ? nullptr : text.c_str()));
      _given_petsc_options[option] = value;
    }
  }
}

Run::~Run() = default;

ResultsWriter& Run::results(std::shared_ptr<const dolfinx::mesh::Mesh> mesh, const Units& units)
{
  if (_results)
    return *_results;
  std::optional<ResultsProgress> keep;
  if (_restart_from.empty())
    forget_old_checkpoints();
  else
    keep = _restart_record.at("run").value("results", ResultsProgress{});
  _results
      = std::make_unique<ResultsWriter>(_comm, _parameters.text("output"), mesh, keep, units);
  // The run's scene file: what --scene needs to run it again, to the last digit on as many
  // ranks. The folder and the restart are where a run goes, not what it computes.
  const nlohmann::json versions = software_versions();
  std::ostringstream scene;
  scene << "# gelx-" << _scene << ", gelx " << versions["gelx"].get<std::string>() << ", dolfinx "
        << versions["dolfinx"].get<std::string>() << ", PETSc "
        << versions["petsc"].get<std::string>() << ", " << dolfinx::MPI::size(_comm)
        << " MPI rank(s). Run it again with\n#   ./gelx run SCENE --scene scene.txt --np "
        << dolfinx::MPI::size(_comm) << "\n# (SCENE the folder in demos/ that builds gelx-"
        << _scene << "; the scene's own solver defaults are not listed: it sets them again)\n"
        << _parameters.scene_file({"output", "restart"})
        << "# What the run was computed from, by content (SHA-256): --scene refuses a program "
           "built\n# from other forms, or an input file that has changed\n";
  for (const auto& [path, hash] : run_sources())
    scene << "source " << path << " = " << hash << "\n";
  _results->write_text("scene.txt", scene.str());
  return *_results;
}

PathState Run::start_path(NonlinearSystem& system)
{
  if (_path_system)
    throw std::logic_error("Run::start_path: a run checkpoints one path");
  _path_system = &system;
  if (_restart_from.empty())
  {
    forget_old_checkpoints();
    return PathState{};
  }
  PathState state = Checkpoints::read(_comm, _restart_from, system);
  summary.update(_restart_record.at("run").at("summary"));
  return state;
}

StepObserver Run::checkpoints()
{
  return [this](const StepRecord& step, PathState& state)
  {
    const int every = _parameters.integer("checkpoint_every");
    if (every == 0 || step.step % every != 0)
      return;
    if (!_path_system)
      throw std::logic_error("Run::checkpoints: the path was not started with start_path");
    nlohmann::json record = {{"parameters", _parameters.to_json()},
                             {"petsc_options", _given_petsc_options},
                             {"sources", run_sources()},
                             {"summary", summary}};
    if (_results)
      record["results"] = _results->progress();
    _checkpoints->write(*_path_system, state, record);
  };
}

void Run::forget_old_checkpoints()
{
  if (!_old_checkpoints_forgotten)
    _checkpoints->clear();
  _old_checkpoints_forgotten = true;
}

double Run::elapsed() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - _start).count();
}

nlohmann::json Run::local_record() const
{
  nlohmann::json record = summary;
  record["wall_time"] = elapsed();
  record["petsc_options"] = petsc_options();
  record["sources"] = run_sources();
  if (!_restart_from.empty())
    record["restarted_from"] = {{"step", _restart_record.at("path").at("step")},
                                {"ranks", _restart_record.at("ranks")}};
  return record;
}

void Run::finish(const std::string& status)
{
  if (!_results)
    return;
  nlohmann::json record = local_record();
  record.update(time_split(_comm, record["wall_time"]));
  _results->write_summary(_scene, status, _parameters, record);
}

void Run::finish_alone(const std::string& status) noexcept
{
  if (!_results)
    return;
  try
  {
    _results->write_summary(_scene, status, _parameters, local_record());
  }
  catch (...) // a full disk: nothing more can be saved
  {
  }
}

int run_program(int argc, char* argv[], const std::string& name, Parameters& parameters,
                const std::function<void(Run&)>& body)
{
  const std::string scene = name.rfind("gelx-", 0) == 0 ? name.substr(5) : name;
  parameters.add("output", "output", ("results/" + scene).c_str(), "folder for the results");
  parameters.add("output", "checkpoint_every", 1,
                 "write a checkpoint of the path every N steps (0: none)",
                 [](int v) { return v >= 0 ? "" : "must not be negative"; });
  parameters.add("output", "stop_after_steps", 0,
                 "end the run, as a success, after this many steps of all its legs (0: run to "
                 "the end; a restart counts its own steps): a quick check that a command runs",
                 [](int v) { return v >= 0 ? "" : "must not be negative"; });
  parameters.add("output", "restart", "",
                 "continue the run in this results folder from its newest checkpoint, with its "
                 "parameters");
  std::vector<std::string> rest;
  bool help = false;
  std::string input_error;
  std::filesystem::path checkpoint;
  try
  {
    rest = parameters.parse(argc, argv, &help);
    checkpoint = restart_checkpoint(parameters);
    if (!checkpoint.empty())
      expect_sources(Checkpoints::read_record(checkpoint).at("run").value("sources", Sources{}),
                     "the checkpoint's run", name);
    else
      expect_sources(parameters.recorded_sources(), "the scene file's run", name);
  }
  catch (const InputError& e)
  {
    input_error = e.what();
    rest = {argv[0]};
  }

  std::vector<char*> petsc_argv;
  for (auto& a : rest)
    petsc_argv.push_back(a.data());
  int petsc_argc = static_cast<int>(petsc_argv.size());
  petsc_argv.push_back(nullptr); // MPI reads argv up to a null entry
  char** petsc_args = petsc_argv.data();
  SlepcInitialize(&petsc_argc, &petsc_args, nullptr, nullptr);
  // HDF5 prints its whole error stack by default; the one line of the error is ours
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  start_timing();
  // dolfinx logs at INFO level by default; warnings and errors are what a user needs
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING;
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  auto error_line = [&](const std::string& what)
  {
    if (rank == 0)
      std::cerr << name << ": error: " << what << std::endl;
  };

  int status = 0;
  if (!input_error.empty())
  {
    error_line(input_error);
    status = 1;
  }
  else if (help)
  {
    if (rank == 0)
      std::cout << "usage: " << name << " [--name value ...] [--scene FILE] [PETSc options]\n"
                << parameters.table(true);
  }
  else
  {
    if (rank == 0)
      std::cout << name << " parameters:\n" << parameters.table(false) << std::flush;
    Run run(PETSC_COMM_WORLD, scene, parameters, checkpoint);
    set_step_budget(parameters.integer("stop_after_steps"));
    try
    {
      body(run);
      if (const std::string unused = unused_options(); !unused.empty())
        throw InputError("no solver object read the option(s) " + unused
                         + " (misspelt, or for an object this run does not have)");
      run.finish("completed");
    }
    catch (const StepBudgetSpent& e) // on every rank at the same step; options the rest of
    {                                // the run would read are not checked
      run.finish(std::string("completed: ") + e.what());
      if (rank == 0)
        std::cout << name << ": " << e.what() << std::endl;
    }
    catch (const InputError& e) // raised identically on every rank
    {
      run.finish(std::string("failed: ") + e.what());
      error_line(e.what());
      status = 1;
    }
    catch (const ConvergenceError& e) // collective: every rank sees the same failed solve
    {
      run.finish(std::string("failed: ") + e.what());
      error_line(std::string(e.what()) + " (results of the completed steps are kept)");
      status = 1;
    }
    catch (const std::exception& e) // possibly on one rank only: stop them all
    {
      const std::string what = e.what() + hdf5_failure();
      std::cerr << name << ": error: " << what << std::endl;
      run.finish_alone("failed: " + what);
      MPI_Abort(PETSC_COMM_WORLD, 1);
    }
  }
  SlepcFinalize();
  return status;
}

} // namespace gelx
