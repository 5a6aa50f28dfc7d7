#include "program.h"
#include "path.h"
#include "petsc_utils.h"

#include <cstdio>
#include <dolfinx/common/log.h>
#include <iostream>
#include <petscsys.h>
#include <slepcsys.h>
#include <sstream>

namespace gelx
{
namespace
{
/// Every option in PETSc's database, as {name: value} (value null for a bare flag): the
/// solver choices in effect, the scene's defaults included, read back rather than retyped.
nlohmann::json petsc_options()
{
  char* all = nullptr;
  PetscOptionsGetAll(nullptr, &all);
  std::istringstream words(all ? all : "");
  PetscFree(all);
  nlohmann::json options = nlohmann::json::object();
  std::string word, name;
  auto is_name = [](const std::string& w)
  { return w.size() > 1 && w[0] == '-' && !std::isdigit(w[1]) && w[1] != '.'; };
  while (words >> word)
  {
    if (is_name(word))
      options[name = word.substr(1)] = nullptr;
    else if (!name.empty())
      options[name] = options[name].is_null() ? word : options[name].get<std::string>() + " " + word;
  }
  return options;
}

/// The options no solver object read (a mistyped or misplaced option), "" when none.
std::string unused_options()
{
  PetscInt n = 0;
  char **names = nullptr, **values = nullptr;
  PetscOptionsLeftGet(nullptr, &n, &names, &values);
  std::string list;
  for (PetscInt i = 0; i < n; ++i)
    if (!is_default_option(names[i]))
      list += (list.empty() ? "-" : ", -") + std::string(names[i]);
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
  return list;
}
} // namespace

Run::Run(MPI_Comm comm, std::string scene, const Parameters& parameters)
    : _comm(comm), _scene(std::move(scene)), _parameters(parameters),
      _start(std::chrono::steady_clock::now())
{
}

ResultsWriter& Run::results(std::shared_ptr<const dolfinx::mesh::Mesh> mesh)
{
  if (!_results)
    _results = std::make_unique<ResultsWriter>(_comm, _parameters.text("output"), mesh);
  return *_results;
}

double Run::elapsed() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - _start).count();
}

void Run::finish(const std::string& status)
{
  if (!_results)
    return;
  nlohmann::json record = summary;
  record["wall_time"] = elapsed();
  record["petsc_options"] = petsc_options();
  _results->write_summary(_scene, status, _parameters, record);
}

int run_program(int argc, char* argv[], const std::string& name, Parameters& parameters,
                const std::function<void(Run&)>& body)
{
  const std::string scene = name.rfind("gelx-", 0) == 0 ? name.substr(5) : name;
  parameters.add("output", "output", ("results/" + scene).c_str(), "folder for the results");
  std::vector<std::string> rest;
  bool help = false;
  std::string input_error;
  try
  {
    rest = parameters.parse(argc, argv, &help);
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
    Run run(PETSC_COMM_WORLD, scene, parameters);
    try
    {
      body(run);
      if (const std::string unused = unused_options(); !unused.empty())
        throw InputError("no solver object read the option(s) " + unused
                         + " (misspelt, or for an object this run does not have)");
      run.finish("completed");
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
      std::cerr << name << ": error: " << e.what() << std::endl;
      MPI_Abort(PETSC_COMM_WORLD, 1);
    }
  }
  SlepcFinalize();
  return status;
}

} // namespace gelx
