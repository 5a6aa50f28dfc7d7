#include "program.h"
#include "load_stepping.h"

#include <cstdio>
#include <dolfinx/common/log.h>
#include <iostream>
#include <slepcsys.h>

namespace gelx
{

int run_program(int argc, char* argv[], const std::string& name, Parameters& parameters,
                const std::function<void(MPI_Comm)>& body)
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

  int status = 0;
  if (!input_error.empty())
  {
    if (rank == 0)
      std::cerr << name << ": error: " << input_error << std::endl;
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
    try
    {
      body(PETSC_COMM_WORLD);
    }
    catch (const InputError& e) // raised identically on every rank
    {
      if (rank == 0)
        std::cerr << name << ": error: " << e.what() << std::endl;
      status = 1;
    }
    catch (const ConvergenceError& e) // collective: every rank sees the same failed solve
    {
      if (rank == 0)
        std::cerr << name << ": error: " << e.what()
                  << " (results of the completed steps are kept)" << std::endl;
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
