#include <gelx/common/petsc_utils.h>
#include <gelx/io/parameters.h>
#include <petsc/private/kspimpl.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

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

void set_default_options(const std::string& prefix,
                         const std::vector<std::pair<std::string, std::string>>& options)
{
  for (const auto& [name, value] : options)
    set_default_option(prefix, name, value);
}

bool is_default_option(const std::string& option) { return defaults_set().count(option) > 0; }

namespace
{
/// The names (without the dash) of the options no object read, but the defaults
std::vector<std::string> unread_option_names()
{
  PetscInt n = 0;
  char **names = nullptr, **values = nullptr;
  PetscOptionsLeftGet(nullptr, &n, &names, &values);
  std::vector<std::string> unread;
  for (PetscInt i = 0; i < n; ++i)
    if (!is_default_option(names[i]))
      unread.push_back(names[i]);
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
  return unread;
}

std::string dashed_list(const std::vector<std::string>& names)
{
  std::string list;
  for (const auto& name : names)
    list += (list.empty() ? "-" : ", -") + name;
  return list;
}

/// Whether PETSc reads `option` only after a solve (views, converged reasons; a TS's or an
/// EPS's after the step's line), so that no check during a run may call it unread
bool read_after_solve(const std::string& option)
{
  return option.find("view") != std::string::npos
         || option.find("converged_reason") != std::string::npos;
}

/// Where the object-class part of an option name can start: "snes_" in "newton_snes_rtol"
const std::vector<std::string> solver_classes
    = {"snes_", "ksp_", "pc_", "mat_", "ts_", "eps_", "st_", "tao_"};

/// The prefixes (with their trailing '_', or "") of the solver objects that read an option:
/// for each option read, each prefix that a solver class follows in its name
std::set<std::string> prefixes_of_read_options()
{
  std::set<std::string> prefixes;
  const nlohmann::json options = petsc_options();
  for (const auto& option : options.items())
  {
    const std::string& name = option.key();
    PetscBool used = PETSC_FALSE;
    PetscOptionsUsed(nullptr, name.c_str(), &used); // the name without its dash
    if (!used)
      continue;
    for (std::size_t at = 0;;) // at the start and after each '_'
    {
      for (const auto& cls : solver_classes)
        if (name.compare(at, cls.size(), cls) == 0)
          prefixes.insert(name.substr(0, at));
      const std::size_t next = name.find('_', at);
      if (next == std::string::npos)
        break;
      at = next + 1;
    }
  }
  return prefixes;
}
} // namespace

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

std::string unused_options() { return dashed_list(unread_option_names()); }

std::string unread_options_of_set_up_solvers()
{
  const std::vector<std::string> unread = unread_option_names();
  if (unread.empty())
    return "";
  const std::set<std::string> prefixes = prefixes_of_read_options();
  std::vector<std::string> misspelt;
  for (const auto& name : unread)
  {
    if (read_after_solve(name))
      continue;
    for (const auto& prefix : prefixes)
      if (name.compare(0, prefix.size(), prefix) == 0
          && std::any_of(solver_classes.begin(), solver_classes.end(),
                         [&](const std::string& cls)
                         { return name.compare(prefix.size(), cls.size(), cls) == 0; }))
      {
        misspelt.push_back(name);
        break;
      }
  }
  return dashed_list(misspelt);
}

void refuse_unread_options_of(const std::string& prefix)
{
  const std::vector<std::string> read_when_set_up = {"snes_", "ksp_", "pc_", "ts_"};
  std::vector<std::string> misspelt;
  for (const auto& name : unread_option_names())
  {
    // `_test_` options are read when their test runs, within a solve
    if (name.compare(0, prefix.size(), prefix) != 0 || read_after_solve(name)
        || name.find("_test_") != std::string::npos)
      continue;
    for (const auto& cls : read_when_set_up)
      if (name.compare(prefix.size(), cls.size(), cls) == 0)
      {
        misspelt.push_back(name);
        break;
      }
  }
  if (!misspelt.empty())
    throw InputError("no solver object read the option(s) " + dashed_list(misspelt)
                     + " (misspelt? the solver of prefix '" + prefix + "' has read its options)");
}

void set_linear_solver_defaults(const std::string& prefix)
{
  // The Krylov sets: a restart long enough for the few hundred iterations of a hard tangent,
  // and a bound that makes a preconditioner that fails show as a failed step, not an hour.
  // FGMRES for fieldsplit: the Schur complement's inner solves make the preconditioner vary.
  using Options = std::vector<std::pair<std::string, std::string>>;
  const Options krylov = {{"ksp_gmres_restart", "200"}, {"ksp_rtol", "1e-10"},
                          {"ksp_max_it", "2000"}};
  const std::map<std::string, Options> sets = {
      {"direct",
       {{"ksp_type", "preonly"}, {"pc_type", "lu"}, {"pc_factor_mat_solver_type", "mumps"}}},
      {"amg", {{"ksp_type", "gmres"}, {"pc_type", "gamg"}}},
      {"fieldsplit",
       {{"ksp_type", "fgmres"},
        {"pc_type", "fieldsplit"},
        {"pc_fieldsplit_type", "schur"},
        {"pc_fieldsplit_schur_fact_type", "full"},
        {"pc_fieldsplit_schur_precondition", "selfp"},
        {"fieldsplit_u_ksp_type", "preonly"},
        {"fieldsplit_u_pc_type", "gamg"},
        {"fieldsplit_p_ksp_type", "preonly"},
        {"fieldsplit_p_pc_type", "jacobi"}}}};
  const std::string name = string_option(prefix, "linear_solver", "direct");
  const auto set = sets.find(name);
  if (set == sets.end())
    throw InputError("-" + prefix + "linear_solver " + name
                     + ": unknown option set (direct, amg, fieldsplit)");
  for (const auto& [option, value] : set->second)
    set_default_option(prefix, option, value);
  if (name != "direct")
    for (const auto& [option, value] : krylov)
      set_default_option(prefix, option, value);
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

void refactor_after_failure(KSP ksp)
{
  // A KSP holds one post-solve hook, and PETSc 3.18 offers no way to chain them: one already
  // there (SNES's Eisenstat-Walker forcing terms, -snes_ksp_ew, which it needs after every
  // solve) is left alone, and that KSP keeps PETSc's behaviour after a failed factorisation
  if (ksp->postsolve)
    return;
  const auto forget_failed_factor = [](KSP solved, Vec, Vec, void*) -> PetscErrorCode
  {
    KSPConvergedReason reason;
    PetscCall(KSPGetConvergedReason(solved, &reason));
    if (reason != KSP_DIVERGED_PC_FAILED)
      return 0;
    PC pc;
    PetscCall(KSPGetPC(solved, &pc));
    PetscBool factor;
    PetscCall(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &factor, PCLU,
                                        PCCHOLESKY, ""));
    if (factor)
      PetscCall(PCReset(pc)); // the next solve's PCSetUp factorises from the start
    return 0;
  };
  GELX_PETSC(KSPSetPostSolve(ksp, forget_failed_factor, nullptr));
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

std::string choice_option(const std::string& prefix, const std::string& name,
                          const std::string& fallback, const std::vector<std::string>& choices)
{
  const std::string value = string_option(prefix, name, fallback);
  if (std::find(choices.begin(), choices.end(), value) != choices.end())
    return value;
  std::string listed = choices.front();
  for (std::size_t k = 1; k < choices.size(); ++k)
    listed += (k + 1 == choices.size() ? " or " : ", ") + choices[k];
  throw InputError("-" + prefix + name + " " + value + ": must be " + listed);
}

} // namespace gelx
