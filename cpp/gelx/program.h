#pragma once
/// @file program.h
/// The frame every gelx program shares: parameters, PETSc start-up, one-line errors.

#include "parameters.h"
#include <functional>
#include <mpi.h>
#include <string>

namespace gelx
{

/// Run a gelx program.
///
/// Reads the scene parameters (plus `--output DIR`, declared here) from the command line,
/// starts PETSc with what remains (the options database), echoes the parameters, and runs
/// `body`. Every error ends as one line `NAME: error: ...` on stderr and exit code 1; `--help`
/// prints the parameter table and exits 0. Input errors are found on every rank before any
/// collective call, so no rank is left waiting.
int run_program(int argc, char* argv[], const std::string& name, Parameters& parameters,
                const std::function<void(MPI_Comm)>& body);

} // namespace gelx
