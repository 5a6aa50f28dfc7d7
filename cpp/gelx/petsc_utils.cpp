#include "petsc_utils.h"
#include "parameters.h"

#include <set>

namespace gelx
{

void petsc_check(PetscErrorCode ierr, const char* call)
{
  if (ierr == 0)
    return;
  const char* text = nullptr;
  PetscErrorMessage(ierr, &text, nullptr);
  throw std::runtime_error(std::string("PETSc call failed: ") + call + ": "
                           + (text ? text : "unknown error"));
}

namespace
{
std::set<std::string>& defaults_set()
{
  static std::set<std::string> names;
  return names;
}
} // namespace

void set_default_option(const std::string& prefix, const std::string& name,
                        const std::string& value)
{
  const std::string option = "-" + prefix + name;
  PetscBool is_set = PETSC_FALSE;
  GELX_PETSC(PetscOptionsHasName(nullptr, nullptr, option.c_str(), &is_set));
  if (!is_set)
  {
    GELX_PETSC(PetscOptionsSetValue(nullptr, option.c_str(),
                                    value.empty() ? nullptr : value.c_str()));
    defaults_set().insert(prefix + name);
  }
}

bool is_default_option(const std::string& option) { return defaults_set().count(option) > 0; }

void set_linear_solver_defaults(const std::string& prefix)
{
  const std::string set = string_option(prefix, "linear_solver", "direct");
  // the Krylov sets: a restart long enough for the few hundred iterations of a hard tangent,
  // and a bound that makes a preconditioner that fails show as a failed step, not an hour
  auto krylov = [&](const char* type)
  {
    set_default_option(prefix, "ksp_type", type);
    set_default_option(prefix, "ksp_gmres_restart", "200");
    set_default_option(prefix, "ksp_rtol", "1e-10");
    set_default_option(prefix, "ksp_max_it", "2000");
  };
  if (set == "direct")
  {
    set_default_option(prefix, "ksp_type", "preonly");
    set_default_option(prefix, "pc_type", "lu");
    set_default_option(prefix, "pc_factor_mat_solver_type", "mumps");
  }
  else if (set == "amg")
  {
    krylov("gmres");
    set_default_option(prefix, "pc_type", "gamg");
  }
  else if (set == "fieldsplit")
  {
    // FGMRES: the Schur complement's inner solves make the preconditioner vary slightly
    krylov("fgmres");
    set_default_option(prefix, "pc_type", "fieldsplit");
    set_default_option(prefix, "pc_fieldsplit_type", "schur");
    set_default_option(prefix, "pc_fieldsplit_schur_fact_type", "full");
    set_default_option(prefix, "pc_fieldsplit_schur_precondition", "selfp");
    set_default_option(prefix, "fieldsplit_u_ksp_type", "preonly");
    set_default_option(prefix, "fieldsplit_u_pc_type", "gamg");
    set_default_option(prefix, "fieldsplit_p_ksp_type", "preonly");
    set_default_option(prefix, "fieldsplit_p_pc_type", "jacobi");
  }
  else
    throw InputError("-" + prefix + "linear_solver " + set
                     + ": unknown option set (direct, amg, fieldsplit)");
}

KSP create_linear_solver(MPI_Comm comm, const std::string& prefix)
{
  set_linear_solver_defaults(prefix);
  KSP ksp;
  GELX_PETSC(KSPCreate(comm, &ksp));
  GELX_PETSC(KSPSetOptionsPrefix(ksp, prefix.c_str()));
  GELX_PETSC(KSPSetFromOptions(ksp));
  return ksp;
}

double real_option(const std::string& prefix, const std::string& name, double fallback)
{
  PetscReal value = fallback;
  GELX_PETSC(PetscOptionsGetReal(nullptr, prefix.c_str(), ("-" + name).c_str(), &value,
                                 nullptr));
  return value;
}

int int_option(const std::string& prefix, const std::string& name, int fallback)
{
  PetscInt value = fallback;
  GELX_PETSC(PetscOptionsGetInt(nullptr, prefix.c_str(), ("-" + name).c_str(), &value,
                                nullptr));
  return static_cast<int>(value);
}

std::string string_option(const std::string& prefix, const std::string& name,
                          const std::string& fallback)
{
  char value[256];
  PetscBool found = PETSC_FALSE;
  GELX_PETSC(PetscOptionsGetString(nullptr, prefix.c_str(), ("-" + name).c_str(), value,
                                   sizeof(value), &found));
  return found ? std::string(value) : fallback;
}

} // namespace gelx
