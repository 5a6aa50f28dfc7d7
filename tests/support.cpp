#include "support.h"

#include <cmath>
#include <cstdio>
#include <dolfinx/common/MPI.h>
#include <dolfinx/common/log.h>
#include <gelx/io/mesh.h>
#include <gelx/common/petsc_utils.h>
#include <slepcsys.h>

namespace gelx::test
{

TaggedBox tagged_box(MPI_Comm comm, std::array<double, 3> L, std::array<std::size_t, 3> n)
{
  return tagged_box(comm, L, n, dolfinx::mesh::CellType::tetrahedron);
}

TaggedBox tagged_box(MPI_Comm comm, std::array<double, 3> L, std::array<std::size_t, 3> n,
                     dolfinx::mesh::CellType cell)
{
  TaggedMesh box = box_mesh(comm, L, n, cell);
  return {box.mesh, box.facet_tags};
}

Checks::Checks(MPI_Comm comm) : _root(dolfinx::MPI::rank(comm) == 0)
{
  // dolfinx logs at INFO level by default; the checks are what a test run should show
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING;
}

void Checks::require(const std::string& what, bool ok)
{
  ok ? ++_passed : ++_failed;
  if (_root)
    std::printf("%s  %s\n", ok ? "PASS" : "FAIL", what.c_str());
}

void Checks::relative(const std::string& what, double value, double reference, double tol)
{
  const double err = std::abs(value - reference) / std::abs(reference);
  char line[512];
  std::snprintf(line, sizeof line, "%s: %.12g (reference %.12g, relative error %.2e, tol %.1e)",
                what.c_str(), value, reference, err, tol);
  require(line, err <= tol);
}

void Checks::absolute(const std::string& what, double value, double reference, double tol)
{
  const double err = std::abs(value - reference);
  char line[512];
  std::snprintf(line, sizeof line, "%s: %.12g (reference %.12g, error %.2e, tol %.1e)",
                what.c_str(), value, reference, err, tol);
  require(line, err <= tol);
}

int Checks::finish() const
{
  if (_root)
    std::printf("%d passed, %d failed\n", _passed, _failed);
  return _failed > 0 ? 1 : 0;
}

gelx::StepObserver NewtonTolerance::observer()
{
  return [this](const gelx::StepRecord& step, gelx::PathState&)
  {
    const auto& r = step.newton;
    _worst = std::max(_worst, r.residual / std::max(1e-12, 1e-10 * r.residual0));
    ++_steps;
  };
}

void NewtonTolerance::check(Checks& checks, const std::string& what) const
{
  char line[256];
  std::snprintf(line, sizeof line,
                "%s: every Newton solve met |R| <= max(1e-12, 1e-10 |R0|) (%d steps, worst %.3g "
                "of it)",
                what.c_str(), _steps, _worst);
  checks.require(line, _steps > 0 && _worst <= 1);
}

int run_checks(int argc, char* argv[],
               const std::function<void(MPI_Comm, Checks&)>& checks_of)
{
  SlepcInitialize(&argc, &argv, nullptr, nullptr); // PETSc, and SLEPc for eigenproblems
  int status;
  {
    Checks checks(PETSC_COMM_WORLD);
    checks_of(PETSC_COMM_WORLD, checks);
    status = checks.finish();
  }
  SlepcFinalize();
  return status;
}

} // namespace gelx::test
