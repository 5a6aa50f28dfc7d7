#pragma once
/// @file strip.h
/// The strip of inverse design (thesis §5.2.1): a bilayer whose upper layer's prestretch is
/// the design, per slab along its length, and the objective of the shape it settles into
/// (forms/design_strip.py). Shared by the design scene and its tests.

#include <array>
#include <dolfinx/fem/Function.h>
#include <gelx/io/mesh.h>
#include <gelx/solvers/adjoint.h>
#include <gelx/solvers/newton.h>
#include <gelx/systems/boundary.h>
#include <gelx/systems/forms.h>
#include <gelx/systems/problem.h>
#include <memory>
#include <mpi.h>
#include <vector>

namespace gelx::scenes
{

struct DesignStripGeometry
{
  double length = 10, width = 1, thickness = 1;  ///< along x, y, z
  std::array<std::size_t, 3> cells{20, 2, 2};    ///< hexahedra along x, y, z
  int slabs = 10; ///< design parameters: the upper layer's prestretch in slabs along x
};

/// The strip [0, length] x [0, width] x [0, thickness], compressible neo-Hookean (Eq. 3.1,
/// G and K), clamped at x = 0. Its cells carry the axial stretch s of their stress-free state,
/// F0 = diag(s, s^-1/2, s^-1/2): in the upper layer (z > thickness/2) s is design parameter k
/// on slab k (length/slabs long), in the lower layer 1. s < 1 in the upper layer curls the
/// strip up, by a curvature of about 3 (1 - s) / (2 thickness) for small misfits (Timoshenko's
/// bimetal with equal layers). The objective (forms/design_strip.py) is the distance to a
/// target displacement field, 1/2 int |u - u_target|^2 dX, plus a Tikhonov term
/// regularisation/2 int (s - 1)^2 dX.
class DesignStrip
{
public:
  DesignStrip(MPI_Comm comm, const DesignStripGeometry& geometry, double G, double K,
              double regularisation = 0);

  NonlinearProblem& problem() { return *_problem; }
  std::shared_ptr<dolfinx::fem::Function<double>> displacement() const { return _u; }
  std::shared_ptr<dolfinx::fem::Function<double>> stretch() const { return _s; }
  std::shared_ptr<dolfinx::fem::Function<double>> target() const { return _u_target; }
  const TaggedMesh& mesh() const { return _mesh; }
  const DesignStripGeometry& geometry() const { return _geometry; }
  FormBinding& forms() { return _forms; }

  /// The design parameter of the cell with midpoint X: its slab in the upper layer, -1 in the
  /// lower (fixed at s = 1).
  int slab_of(const double* X) const;
  /// s per slab (upper layer), 1 in the lower layer.
  void set_slabs(const std::vector<double>& stretch);
  /// The equilibrium at the slab stretches `stretch`, by load steps from the stress-free
  /// s = 1 (u = 0). Throws ConvergenceError when the path fails. Collective.
  void solve_from_rest(NewtonSolver& newton, const std::vector<double>& stretch);

  /// The adjoint gradient of the objective on `system` (this problem or a decorator of it).
  std::unique_ptr<AdjointGradient> adjoint(NonlinearSystem& system) const;

private:
  DesignStripGeometry _geometry;
  TaggedMesh _mesh;
  std::shared_ptr<dolfinx::fem::Function<double>> _u, _u_target, _s;
  FormBinding _forms;
  std::unique_ptr<DirichletConditions> _bcs;
  std::unique_ptr<NonlinearProblem> _problem;
};

} // namespace gelx::scenes
