#pragma once
/// @file petsc_utils.h
/// PETSc error codes as exceptions, and defaults in the options database that never override
/// what the user passed.

#include <exception>
#include <petscksp.h>
#include <stdexcept>
#include <string>

namespace gelx
{

/// Throws std::runtime_error naming the PETSc call when `ierr` is non-zero.
void petsc_check(PetscErrorCode ierr, const char* call);

/// Wrap a PETSc call: GELX_PETSC(VecNorm(x, NORM_2, &n));
#define GELX_PETSC(call) ::gelx::petsc_check((call), #call)

/// Run the body of a PETSc callback: PETSc is C and must not be unwound through, so an
/// exception becomes an error code and is kept in `error` for the caller of the PETSc solve
/// to rethrow.
template <typename Body>
PetscErrorCode guarded_callback(std::exception_ptr& error, Body&& body)
{
  try
  {
    body();
    return 0;
  }
  catch (...)
  {
    error = std::current_exception();
    return PETSC_ERR_USER;
  }
}

/// Set option `-<prefix><name>` to `value` unless it is already set (on the command line,
/// in PETSC_OPTIONS or an options file), so that scene defaults never override the user.
void set_default_option(const std::string& prefix, const std::string& name,
                        const std::string& value = "");

/// Whether set_default_option set `option` (its name without the dash): a default that a
/// user's other choices may leave unread (MUMPS for an iterative solve) is no mistake.
bool is_default_option(const std::string& option);

/// Make a direct solve (MUMPS LU) the default of the linear solver with options `prefix`:
/// robust for the problem sizes of the scenes; `-<prefix>ksp_type gmres -<prefix>pc_type gamg`
/// etc. select an iterative one.
void default_to_direct_solver(const std::string& prefix);

/// A KSP reading options with `prefix`, a direct solve by default (default_to_direct_solver).
KSP create_linear_solver(MPI_Comm comm, const std::string& prefix);

/// Value of a real option `-<prefix><name>`, or `fallback` when unset.
double real_option(const std::string& prefix, const std::string& name, double fallback);

/// Value of an integer option `-<prefix><name>`, or `fallback` when unset.
int int_option(const std::string& prefix, const std::string& name, int fallback);

/// Value of a string option `-<prefix><name>`, or `fallback` when unset.
std::string string_option(const std::string& prefix, const std::string& name,
                          const std::string& fallback);

} // namespace gelx
