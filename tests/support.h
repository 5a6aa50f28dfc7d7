#pragma once
/// @file support.h
/// What the verification programs share: a tagged box mesh and number checks that count
/// failures and print every measured value next to its reference.

#include <array>
#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/cell_types.h>
#include <dolfinx/mesh/MeshTags.h>
#include <functional>
#include <gelx/systems/boundary.h>
#include <gelx/solvers/path.h>
#include <memory>
#include <mpi.h>
#include <string>

namespace gelx::test
{

/// Tags of the faces of a box [0, L0] x [0, L1] x [0, L2].
enum BoxFace : int
{
  x_min = 1,
  x_max = 2,
  y_min = 3,
  y_max = 4,
  z_min = 5,
  z_max = 6
};

struct TaggedBox
{
  std::shared_ptr<dolfinx::mesh::Mesh> mesh;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> facets;
};

/// Tetrahedral mesh of the box with n cells along each edge and its faces tagged (BoxFace).
TaggedBox tagged_box(MPI_Comm comm, std::array<double, 3> L, std::array<std::size_t, 3> n);

/// The same with a chosen cell type (tetrahedron or hexahedron).
TaggedBox tagged_box(MPI_Comm comm, std::array<double, 3> L, std::array<std::size_t, 3> n,
                     dolfinx::mesh::CellType cell);

using gelx::component_range;

/// Records checks; the program's exit code is the failure count (0 = all passed).
class Checks
{
public:
  explicit Checks(MPI_Comm comm);
  /// |value - reference| <= tol * |reference|
  void relative(const std::string& what, double value, double reference, double tol);
  /// |value - reference| <= tol
  void absolute(const std::string& what, double value, double reference, double tol);
  /// A condition with its measured description.
  void require(const std::string& what, bool ok);
  /// Prints "N passed, M failed" and returns the exit code.
  int finish() const;

private:
  bool _root;
  int _passed = 0, _failed = 0;
};

/// The final Newton residuals of a path against the tolerance that the tests' own tolerances
/// rest on ("the state is exact to |R| <= 1e-10 |R0|"): |R| <= max(1e-12, 1e-10 |R0|), the
/// NewtonSolver defaults, at every step. observer() records the steps, check() asserts the
/// worst, so that a changed solver default cannot leave a test's justification silently void.
class NewtonTolerance
{
public:
  gelx::StepObserver observer();
  void check(Checks& checks, const std::string& what) const;

private:
  double _worst = 0; ///< largest |R| / max(1e-12, 1e-10 |R0|) over the steps
  int _steps = 0;
};

/// The body of a verification program: initialise PETSc and SLEPc, run `checks_of(comm, checks)` with
/// print the tally, finalise; returns the exit code.
int run_checks(int argc, char* argv[],
               const std::function<void(MPI_Comm, Checks&)>& checks_of);

} // namespace gelx::test
