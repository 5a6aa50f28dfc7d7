#pragma once
/// @file strip.h
/// The strip of inverse design (thesis §5.2.1): a bilayer whose upper layer's prestretch (its
/// stretch and, optionally, its direction) is the design, per slab along its length, and the
/// objective of the shape it settles into (forms/design_strip.py). Shared by the design scene
/// and its tests.

#include "centreline.h"

#include <array>
#include <functional>
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
  double length = 10, width = 1, thickness = 1; ///< along x, y, z
  std::array<std::size_t, 3> cells{20, 2, 2};   ///< hexahedra along x, y, z
  int slabs = 10; ///< the upper layer's prestretch is designed in slabs along x
  /// Whether the prestretch's direction is designed too (an angle per slab after the stretches:
  /// parameters s_0..s_{n-1}, a_0..a_{n-1}); otherwise only the stretches, the angle fixed.
  bool design_angle = false;
  /// Whether the lower layer is designed too, its parameters after the upper layer's (else it
  /// is stress free): with both layers free the strip can curl without shortening its
  /// centreline (one layer shorter, the other longer), as a target of given arc length needs.
  bool design_lower = false;
  /// When set, the far end x = length is clamped too: its displacement at X when
  /// solve_from_rest's load is t (a rigid motion; from 0 at t = 0), and at t = 1 after it.
  std::function<std::array<double, 3>(double t, const std::array<double, 3>& X)> far_end;
  int parameters_per_layer() const { return design_angle ? 2 * slabs : slabs; }
  int num_parameters() const { return (design_lower ? 2 : 1) * parameters_per_layer(); }
};

/// The strip [0, length] x [0, width] x [0, thickness], compressible neo-Hookean (Eq. 3.1, G and
/// K), clamped at x = 0 (and, with far_end, at x = length). Its cells carry the prestretch of
/// forms/design_strip.py: the stretch s of their stress-free state along the in-plane direction at
/// angle a from x. In the upper layer (z > thickness/2), slab k (length/slabs long) has s = p_k
/// and, with design_angle, a = p_{slabs + k}; the lower layer is stress free (s = 1), or, with
/// design_lower, designed likewise by the next parameters_per_layer() ones. s < 1 in the upper
/// layer curls the strip up, by a curvature of about 3 (1 - s) / (2 thickness) for small misfits
/// (Timoshenko's bimetal with equal layers); a != 0 twists it as it curls, into a helix. The
/// objective (DesignObjective) is the distance to a target displacement field, 1/2 int |u -
/// u_target|^2 dX, or the distance of the centreline's curvature and twist to a helix's
/// (centreline_objective()), plus a Tikhonov term regularisation/2 int (s - 1)^2 dX and, if asked,
/// a multiple of the elastic energy int psi dX.
enum class DesignObjective
{
  placement, ///< the distance to the target displacement (a form: forms/design_strip.py)
  centreline ///< the detector's curvature and twist against a helix's (sampled)
};

class DesignStrip
{
public:
  DesignStrip(MPI_Comm comm, const DesignStripGeometry& geometry, double G, double K,
              double regularisation = 0);

  NonlinearProblem& problem() { return *_problem; }
  std::shared_ptr<dolfinx::fem::Function<double>> displacement() const { return _u; }
  /// The design field (stretch, angle) per cell.
  std::shared_ptr<dolfinx::fem::Function<double>> prestretch() const { return _prestretch; }
  std::shared_ptr<dolfinx::fem::Function<double>> target() const { return _u_target; }
  const TaggedMesh& mesh() const { return _mesh; }
  const DesignStripGeometry& geometry() const { return _geometry; }
  FormBinding& forms() { return _forms; }

  /// The design parameter that sets component c (0 stretch, 1 angle) of the cell with
  /// midpoint X, -1 where none does (a layer or an angle that is not designed).
  int parameter_of(const double* X, int component) const;
  /// The design p (num_parameters() values); the angle `angle` where it is not designed.
  void set_design(const std::vector<double>& p, double angle = 0);
  /// The equilibrium of `system` (this problem or a decorator of it) at the design p, along
  /// the path from the stress-free state (its unknowns 0, the stretches 1, the far end, if
  /// clamped, at rest): load steps, arc length past a fold (follow_homotopy, options prefix
  /// `rest_`). Throws ConvergenceError when the path fails. Collective.
  void solve_from_rest(NonlinearSystem& system, NewtonSolver& newton,
                       const std::vector<double>& p, double angle = 0);

  /// Whether the reference position Z along the strip is in the span where its helix is
  /// measured: the middle 80 %, away from the clamp's and the free end's boundary layers
  /// (the detector's mean in demos/design, and the centreline objective)
  bool measured(double Z) const { return measured(Z, 0, _geometry.length); }
  /// The same rule for a helix on [from, to] (each side of a perversion)
  static bool measured(double Z, double from, double to)
  {
    return Z >= from + 0.1 * (to - from) && Z <= to - 0.1 * (to - from);
  }
  /// The length of that span
  double measured_length() const { return 0.8 * _geometry.length; }

  /// The adjoint gradient of an objective on `system` (this problem or a decorator of it);
  /// the centreline's against the helix of curvature `curvature` and twist `twist`. It sets
  /// the objective form's placement_weight (1 for the placement, 0 for the centreline), so
  /// one strip serves one objective at a time. `energy_weight` times the elastic energy
  /// int psi dX is added to either.
  std::unique_ptr<AdjointGradient> adjoint(NonlinearSystem& system,
                                           DesignObjective objective = DesignObjective::placement,
                                           double curvature = 0, double twist = 0,
                                           double energy_weight = 0);

  /// The helix detector's rates as an objective (UFL cannot write it: it reads a few nodal
  /// values): J = 1/2 sum_k h [(kappa_k - curvature)^2 + (tau_k - twist)^2] over the node
  /// layers k in the middle 80 % of the strip (h their spacing; the clamp's and the free
  /// end's boundary layers left out, as the detector's mean), kappa_k and tau_k the
  /// curvature and twist of CentrelineRates at the samples of centreline(). Its dJ/du is
  /// exact: a dual number through CentrelineRates per sampled value, then the samples'
  /// linear dependence on the nodes (a centre the mean of its layer's nodes, a width vector
  /// the difference of two nodes).
  std::pair<std::function<double()>, std::function<void(Vec)>>
  centreline_objective(double curvature, double twist) const;

  /// The strip deformed by u (the displacement, or the target), its centreline sampled at
  /// every node layer x = const: the centroid of the section's nodes and the width vector of
  /// the interface z = thickness/2 (the deformed positions of its edges y = 0 and y = width),
  /// for analyse_centreline. Collective.
  CentrelineSamples centreline(const dolfinx::fem::Function<double>& u) const;

private:
  /// f(n, layer, edge) for every owned node n of the displacement's space: its node layer
  /// x = const and whether it is the interface's edge y = 0 (edge 0), y = width (edge 1) or
  /// neither (-1)
  void for_each_owned_node(const std::function<void(std::int32_t, int, int)>& f) const;
  int node_layers() const { return 2 * _geometry.cells[0] + 1; } // Q2 nodes
  DesignStripGeometry _geometry;
  TaggedMesh _mesh;
  std::shared_ptr<dolfinx::fem::Function<double>> _u, _u_target, _prestretch;
  FormBinding _forms;
  std::unique_ptr<DirichletConditions> _bcs;
  std::unique_ptr<NonlinearProblem> _problem;
};

} // namespace gelx::scenes
