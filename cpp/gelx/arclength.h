#pragma once
/// @file arclength.h
/// Arc-length continuation (Riks / Crisfield) of R(u, lambda) = 0 through limit points.

#include "buckling.h"
#include "problem.h"
#include <cmath>
#include <functional>
#include <mpi.h>
#include <petscksp.h>
#include <string>

namespace gelx
{

/// One converged point of the equilibrium path.
struct PathPoint
{
  int step = 0;
  double load_factor = 0;   ///< lambda
  double arc_length = 0;    ///< path length s up to this point
  int iterations = 0;       ///< corrector iterations
  int cutbacks = 0;         ///< arc-length halvings before this point converged
  bool limit_point = false; ///< lambda passed an extremum since the previous point
  double stability = NAN;   ///< eigenvalue of the tangent nearest zero (with -arclength_stability)
  bool bifurcation = false; ///< stability changed sign without a load extremum
};

/// Follows R(u, lambda) = 0 with the constraint |du|^2 + psi^2 dlambda^2 = ds^2 per step
/// (psi = 0: cylindrical, Crisfield).
///
/// The load factor enters the residual through `set_load_factor` (e.g. the pressure constant
/// of a form); dR/dlambda is computed by a central difference of the residual, exact for loads
/// linear in lambda. Each corrector iteration solves K a = -R and K b = -dR/dlambda with one
/// factorisation (the two-solve form of the bordered system) and picks the root of the
/// constraint closest to the previous direction, which carries the path through limit points.
/// The predictor follows the previous step's direction. Step lengths adapt to the iteration
/// count and are halved after a failed corrector.
///
/// Options, prefix `arclength_`: ds (first arc length), ds_max, ds_min, psi, max_it,
/// target_it (iterations per step the adaptation aims at), rtol (|R| <= rtol |dR/dlambda|),
/// monitor, stability (1: compute the tangent eigenvalue nearest zero at every point, to detect
/// bifurcations; see lowest_tangent_eigenpair); the linear solver reads `-arclength_ksp_*`, `-arclength_pc_*` (default MUMPS LU).
class ArcLength
{
public:
  ArcLength(MPI_Comm comm, NonlinearProblem& problem,
            std::function<void(double)> set_load_factor, const std::string& prefix = "arclength_");
  ~ArcLength();
  ArcLength(const ArcLength&) = delete;
  ArcLength& operator=(const ArcLength&) = delete;

  /// Continue from the current (converged) u at load factor `lambda0` until `stop(point)`
  /// returns true or `max_steps` steps are taken; `on_point` sees every converged point.
  /// Throws ConvergenceError when the arc length falls below ds_min.
  void run(double lambda0, int max_steps, const std::function<void(const PathPoint&)>& on_point,
           const std::function<bool(const PathPoint&)>& stop);

  /// Branch switching at a bifurcation (call after run() stopped just past one): the first
  /// predictor of the next run() leaves the current state along the tangent's eigenvector
  /// nearest zero, the mode of the crossing branch, with the load factor held, instead of
  /// along the path. The corrector's constraint keeps the iterate a distance ds away from the
  /// current state, so it cannot fall back onto the primary path, which moves little in u near
  /// the bifurcation, and converges on the secondary branch (psi = 0, a cylindrical
  /// constraint, suits this). Returns the eigenvalue (the state's stability).
  double switch_branch();

private:
  void load_derivative(double lambda, Vec f);
  MPI_Comm _comm;
  NonlinearProblem& _problem;
  std::function<void(double)> _set_load;
  std::string _prefix;
  KSP _ksp = nullptr;
  Mat _K = nullptr;
  Vec _R = nullptr, _f = nullptr, _a = nullptr, _b = nullptr, _du = nullptr, _du_prev = nullptr,
      _u0 = nullptr, _tmp = nullptr, _branch = nullptr;
  bool _switch_branch = false;
};

/// The vertex of the parabola through three points (s_i, lambda_i): where a limit point
/// bracketed by them lies. Returns (s, lambda) at the vertex.
std::pair<double, double> parabola_vertex(const double s[3], const double lambda[3]);

} // namespace gelx
