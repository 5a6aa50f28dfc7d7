#pragma once
/// @file design.h
/// Inverse design: the design parameters that minimise an objective of an equilibrium, by
/// PETSc TAO with gradients from the adjoint (adjoint.h).

#include <gelx/solvers/adjoint.h>
#include <gelx/solvers/newton.h>
#include <gelx/solvers/path.h>

#include <dolfinx/fem/Function.h>
#include <functional>
#include <memory>
#include <petscmat.h>
#include <petsctao.h>
#include <string>
#include <vector>

namespace gelx
{

/// One iterate of a DesignOptimizer.
struct DesignIterate
{
  int iteration = 0;
  double objective = 0;
  /// The norm of the gradient TAO judges convergence by (the projected gradient of a
  /// bound-constrained method: zero at an optimum on a bound)
  double gradient_norm = 0;
  std::vector<double> parameters; ///< p, on every rank
  int forward_solves = 0;         ///< so far: equilibria solved (Newton solves, path steps)
  int newton_iterations = 0;      ///< so far, over all forward solves
  int adjoint_solves = 0;         ///< so far
  double forward_time = 0;        ///< so far, in the forward solves (s)
  double adjoint_time = 0;        ///< so far, in the adjoint solves and gradients (s)
  double wall_time = 0;           ///< so far (s)
};

/// Minimises J(u(p), s(p)) over n design parameters p, u the equilibrium of a NonlinearSystem
/// at the design field s(p) = s_fixed + T p: parameter k sets component c of the cells (dofs of
/// the DG0 design space, of one or more components) that `parameter_of(X, c)` maps to k at
/// their midpoint X; where it gives -1 the design keeps its value (e.g. a prestretch per slab
/// of one layer of a strip, the other layer fixed).
///
/// The optimiser is PETSc TAO, options prefix `prefix` (by default `design_`: -design_tao_type,
/// -design_tao_gatol, ...), by default BLMVM (bound-constrained limited-memory quasi-Newton),
/// with the bounds of set_bounds. Each evaluation of J and dJ/dp solves the equilibrium at s(p)
/// by Newton from the last one (the state of the previous evaluation); when that fails, from
/// the same state along the path that moves s from its last value to the new one (a design
/// change too large for one Newton solve): by load steps, and by arc length past a fold of
/// that path, where the shape snaps (follow_homotopy, options prefix PREFIXhomotopy_:
/// -design_homotopy_ds, ...); then the adjoint (AdjointGradient) gives
/// dJ/dp = T^T dJ/ds: one forward and one adjoint solve per evaluation, whatever n is.
///
/// The parameters are few (a pattern per slab, a handful of global numbers): rank 0 owns them
/// all, and TAO's vectors are of that layout.
class DesignOptimizer
{
public:
  DesignOptimizer(NonlinearSystem& system, NewtonSolver& newton, AdjointGradient& adjoint,
                  std::shared_ptr<dolfinx::fem::Function<double>> design, int num_parameters,
                  const std::function<int(const double* X, int component)>& parameter_of,
                  const std::string& prefix = "design_");
  ~DesignOptimizer();
  DesignOptimizer(const DesignOptimizer&) = delete;
  DesignOptimizer& operator=(const DesignOptimizer&) = delete;

  /// lower_k <= p_k <= upper_k (a prestretch must stay positive; a bound also keeps the line
  /// search's trial designs in the range where the forward solve is meaningful). The same
  /// values on every rank.
  void set_bounds(const std::vector<double>& lower, const std::vector<double>& upper);
  /// Minimise from p (every rank the same values), calling `observe` after every iterate (the
  /// start included: iteration 0) with the system at that iterate's equilibrium (its shape can
  /// be measured there). On return p holds the last iterate and the system its equilibrium.
  /// Returns TAO's converged reason (negative: it gave up). Throws ConvergenceError when an
  /// equilibrium cannot be found. Collective.
  int minimise(std::vector<double>& p, const std::function<void(const DesignIterate&)>& observe);

  /// J(p) and dJ/dp into `gradient` (TAO's layout): the forward solve, then the adjoint.
  /// For the TAO callback. Collective.
  double evaluate(Vec p, Vec gradient);
  /// For the TAO callback: report the iterate TAO accepted.
  void iterate_accepted();
  std::exception_ptr callback_error;

private:
  /// s = s_fixed + T p into the design Function (owned and ghost values)
  void set_design(Vec p);
  /// The equilibrium at the design now in the Function, from the last one
  void solve_forward();
  /// When Newton fails: from the last equilibrium along the path that carries the design from
  /// the last one to the new one (follow_homotopy)
  void solve_forward_by_steps();
  /// The forward solve at p, unless the last one was at p (TAO's last evaluation before an
  /// iterate is usually, not always, the iterate itself: a line search may end on another)
  void equilibrium_at(Vec p);

  NonlinearSystem& _system;
  NewtonSolver& _newton;
  AdjointGradient& _adjoint;
  std::shared_ptr<dolfinx::fem::Function<double>> _design;
  std::string _prefix;
  Tao _tao = nullptr;
  Mat _T = nullptr;              ///< design dofs (owned rows) x parameters (rank 0's columns)
  Vec _fixed = nullptr;          ///< s_fixed: the design's values where no parameter acts
  Vec _design_vec = nullptr;     ///< the design Function's values as a PETSc vector
  Vec _lower = nullptr, _upper = nullptr;
  /// The last equilibrium, its design field and its parameters
  OwnedVec _last_state, _last_design, _last_parameters;
  const std::function<void(const DesignIterate&)>* _observe = nullptr;
  DesignIterate _counts;
  double _start_time = 0;
};

} // namespace gelx
