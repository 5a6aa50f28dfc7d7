#pragma once
/// @file arclength.h
/// Arc-length continuation of R(x, lambda) = 0 through limit points: the bordered system (one
/// more unknown, the load factor) solved by SNES, and the path it follows.

#include <gelx/solvers/buckling.h>
#include <gelx/solvers/path.h>
#include <functional>
#include <mpi.h>
#include <petscksp.h>
#include <string>

namespace gelx
{

/// A system R(x; lambda) = 0 bordered with the arc-length condition
///   c(x, lambda) = (|x - x0|^2 + psi^2 (lambda - l0)^2 - ds^2) / (2 ds) = 0:
/// the next point lies a distance ds from the last one (x0, l0) in the norm
/// |x|^2 + psi^2 lambda^2 (psi = 0: the cylindrical constraint of Crisfield), so that the path
/// length s is the sum of the steps and a step moves the load by at most ds / psi. Its
/// unknowns are [x; lambda] (lambda owned by the last rank); the load enters the wrapped system
/// through `set_load(lambda)`, and f = dR/dlambda is a central difference of its residual
/// (exact for loads linear in lambda). Newton on the bordered system, started from a predictor
/// on the sphere, converges to the intersection near it: through limit points, where lambda
/// turns back, and, started along a bifurcating mode, onto the crossing branch.
///
/// Why a shell: the tangent [[K, f], [g_x^T, g_l]], g = ((x - x0), psi^2 (lambda - l0)) / ds,
/// is a MATSHELL, and its exact inverse a PCSHELL that eliminates lambda (the bordering
/// algorithm): two solves with one factorisation of K (K a = r_x, K b = f;
/// dlambda = (r_l - g_x.a) / (g_l - g_x.b), dx = a - dlambda b).
/// An assembled bordered matrix would carry a dense row and column into the factorisation, and
/// K is what -PREFIX_ksp_* and -PREFIX_pc_* configure (MUMPS LU by default, or AMG); the SNES's
/// own KSP (prefix PREFIX_bordered_) only applies the shell.
class ArcLengthSystem : public NonlinearSystem
{
public:
  ArcLengthSystem(NonlinearSystem& inner, std::function<void(double)> set_load,
                  const std::string& prefix);
  ~ArcLengthSystem() override;
  ArcLengthSystem(const ArcLengthSystem&) = delete;
  ArcLengthSystem& operator=(const ArcLengthSystem&) = delete;

  /// The constraint of the next step: the last point (x0, l0) in the wrapped system's layout,
  /// the step ds and the load's weight psi.
  void set_constraint(Vec x0, double l0, double ds, double psi);
  /// The state (x, lambda) into one vector of this system's layout, and back.
  void pack(Vec x, double lambda, Vec bordered) const;
  double load_factor() const { return _lambda; }
  /// f = dR/dlambda at the current state, in the wrapped system's layout. Collective.
  void load_derivative(Vec f);
  /// Assemble the wrapped system's tangent K at the current state.
  void assemble_tangent();
  /// Solve K y = b with K as last assembled.
  void solve_tangent(Vec b, Vec y);

  Vec unknowns() override { return _x; }
  /// Passes x to the wrapped system and lambda to set_load.
  void unknowns_changed() override;
  void residual(Vec r) override;
  /// Assembles K, f and the constraint's gradient (K is factorised at the first application
  /// of the inverse, where the bordered KSPSolve times it); A (from create_matrix) applies
  /// the bordered tangent.
  void tangent(Mat A) override;
  Vec create_vector() const override;
  Mat create_matrix() const override;
  bool admissible() const override { return _inner.admissible(); }
  std::vector<PetscInt> prescribed_rows() const override { return _inner.prescribed_rows(); }
  void commit() override { _inner.commit(); }
  NonlinearProblem& problem() override { return _inner.problem(); }
  const std::vector<PetscInt>& unknown_of_problem_dof() const override
  {
    return _inner.unknown_of_problem_dof();
  }
  /// Move x along (-K^-1 f, 1), the direction that keeps the wrapped residual to first order,
  /// onto the sphere |x - x0|^2 + psi^2 (lambda - l0)^2 = ds^2 (the root nearest x). The
  /// Newton step satisfies the linearised condition only; without this the condition's
  /// second-order remainder, not the forces, decides the last iteration (measured on the
  /// buckling column's nearly linear straight path: 25 corrector iterations in 11 steps
  /// against 15 with it).
  bool project(Vec x) override;
  /// Make the SNES's linear solver the shell preconditioner (NewtonSolver calls it).
  void configure(SNES snes) const override;

  NonlinearSystem& inner() { return _inner; }
  /// The wrapped system's tangent at the last tangent() or assemble_tangent() (for eigenvalues).
  Mat inner_tangent() const { return _K; }
  /// Its number of negative eigenvalues, read from its factors (factored_negative_eigenvalues:
  /// for an LDL^T factorisation).
  int tangent_negative_eigenvalues() const;

  /// For the shell's C callbacks.
  void apply_tangent(Vec v, Vec y) const;
  void apply_inverse(Vec r, Vec z) const;

private:
  /// Split a vector of this layout into its x part (into `x`) and lambda (returned, on all
  /// ranks); and join them.
  double split(Vec v, Vec x) const;
  void join(Vec x, double lambda, Vec v) const;

  NonlinearSystem& _inner;
  std::function<void(double)> _set_load;
  MPI_Comm _comm;
  bool _last_rank;
  PetscInt _n; ///< owned entries of the wrapped system's vector
  Vec _x = nullptr;
  double _lambda = 0;
  // The constraint and its gradient (g, g_l) at the last tangent()
  Vec _x0 = nullptr, _g = nullptr;
  double _l0 = 0, _ds = 0, _psi = 0, _g_l = 0;
  // The tangent: K, f, b = K^-1 f, and the solver of K
  Mat _K = nullptr;
  KSP _ksp = nullptr;
  Vec _f = nullptr, _b = nullptr, _work = nullptr, _work2 = nullptr;
  mutable bool _factorised = false; ///< K of the last tangent() factorised, b solved
};

/// Follows the path R(x, lambda) = 0 by pseudo-arc-length continuation: per step a tangent
/// predictor (K t = -f, oriented along the previous step) of length ds, then Newton on the
/// bordered system (ArcLengthSystem, SNES with prefix PREFIX, by default `arclength_`). Step
/// lengths adapt to the iteration count and are halved after a failed corrector, and after one
/// that converged behind the last point (where the path would retrace itself).
///
/// gelx options (prefix PREFIX): ds (first arc length), ds_max, ds_min, psi, target_it
/// (iterations per step the adaptation aims at), rtol (|R| <= rtol |dR/dlambda|, the force
/// scale of the load), stability: how each point's stability is tracked to detect
/// bifurcations (StepRecord::bifurcation) —
///   none (default);
///   eigenvalue: the tangent's eigenvalue nearest zero (SLEPc shift-invert,
///     lowest_tangent_eigenpair: one more factorisation and an eigensolve per point), whose
///     sign change marks a crossing; it also gives the crossing mode (switch_branch) and how
///     far the point is from one; but it sees one eigenvalue, so two crossing together (a
///     double bifurcation, or two within one step) cancel in its sign;
///   inertia: the number of negative eigenvalues of the tangent, read from the LDL^T
///     factorisation the next predictor makes anyway (K is then factorised by MUMPS's
///     Cholesky, default_to_symmetric_factorisation): free, and it counts every crossing;
///     it needs a symmetric tangent (no contact rows, which are not symmetric).
/// PETSc's: -PREFIX_snes_* (max_it 15, the basic line search, i.e. full corrector steps, by
/// default), -PREFIX_ksp_*, -PREFIX_pc_* for K.
class ArcLength
{
public:
  ArcLength(MPI_Comm comm, NonlinearSystem& system, std::function<void(double)> set_load,
            const std::string& prefix = "arclength_");

  /// Continue from the current (converged) state of the system at `state.load` (each step
  /// sets the load first) until `stop(record)` returns true or the path has `max_steps` steps
  /// (state.step). A continued path (state.step > 0) first asks `stop` about its last point,
  /// from the state (no Newton report, no limit-point or bifurcation flags), so that a run
  /// restarted from its final checkpoint takes no extra step. Throws ConvergenceError when
  /// the arc length falls below ds_min; the state then holds the last point.
  void run(PathState& state, int max_steps, const std::vector<StepObserver>& observers,
           const std::function<bool(const StepRecord&)>& stop);

  /// The first arc length and the load's weight when the options (-PREFIX_ds, -PREFIX_psi)
  /// do not set them: by default 0.05 and 0, which suit a load factor and unknowns of order
  /// one; a driver that knows its path's scale sets its own.
  void set_default_scale(double ds, double psi)
  {
    _default_ds = ds;
    _default_psi = psi;
  }

  /// Branch switching at a bifurcation (call after run() stopped just past one): the next
  /// predictor leaves the current state along the tangent's eigenvector nearest zero, the mode
  /// of the crossing branch, with the load held; the corrector's hyperplane, a distance ds away
  /// along that mode, keeps it off the primary path. Returns the eigenvalue (the state's
  /// stability). For systems whose unknowns are the problem's.
  double switch_branch(PathState& state);

private:
  /// Unit tangent at the current state, oriented along state.direction (or toward increasing
  /// lambda on a new path): into `t`, returns t_l. Leaves dR/dlambda in _load.
  double tangent_direction(const PathState& state, double psi, Vec t);
  /// Whether the current state lies ahead of the last point (x0, l0) along the predictor's
  /// direction (t, t_l): its step has a positive component along it, in the arc length's
  /// metric (load weighted by psi).
  bool ahead_of(Vec x0, double l0, Vec t, double t_l, double psi);

  MPI_Comm _comm;
  NonlinearSystem& _system;
  ArcLengthSystem _bordered;
  NewtonSolver _newton;
  std::string _prefix;
  OwnedVec _load;              ///< dR/dlambda at the last point
  bool _switch_pending = false; ///< the next predictor follows state.direction (switch_branch)
  double _default_ds = 0.05, _default_psi = 0;
};

/// The vertex of the parabola through three points (s_i, lambda_i): where a limit point
/// bracketed by them lies. Returns (s, lambda) at the vertex.
std::pair<double, double> parabola_vertex(const double s[3], const double lambda[3]);

} // namespace gelx
