#pragma once
/// @file path.h
/// What load stepping and arc-length continuation share: the explicit state of a path, the
/// record of one step, and the observers that see every step.

#include <gelx/common/petsc_utils.h>
#include <gelx/solvers/newton.h>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <nlohmann/json.hpp>
#include <petscvec.h>
#include <stdexcept>
#include <vector>

namespace gelx
{

/// The path could not be followed: a step failed at the smallest allowed size.
class ConvergenceError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// A PETSc vector owned by one C++ object.
struct VecDestroyer
{
  void operator()(Vec v) const { VecDestroy(&v); }
};
using OwnedVec = std::unique_ptr<_p_Vec, VecDestroyer>;
/// A copy of `v` (same layout and values) that the caller owns. Collective.
OwnedVec copy_of(Vec v);

/// The last completed point of a path, which a failed attempt returns to: the system's
/// unknowns and its history (NonlinearSystem::save_history). The history matters because a
/// failed attempt's iterates commit theirs: a contact node that one of them pressed onto the
/// plane would stay held there, at a point where it is off it (measured on the crease's
/// self-contact: every shorter attempt then started from that jump and failed). Collective.
class CompletedPoint
{
public:
  explicit CompletedPoint(NonlinearSystem& system)
      : _system(system), _unknowns(system.create_vector()), _history(system.create_vector())
  {
  }
  /// Keep the system's current state
  void save()
  {
    GELX_PETSC(VecCopy(_system.unknowns(), _unknowns.get()));
    GELX_PETSC(VecZeroEntries(_history.get()));
    _system.save_history(_history.get());
  }
  /// Set the system back to the kept state
  void restore()
  {
    _system.set_state(_unknowns.get());
    _system.load_history(_history.get());
  }
  Vec unknowns() const { return _unknowns.get(); }

private:
  NonlinearSystem& _system;
  OwnedVec _unknowns, _history;
};

/// Where a path is: with the system's unknowns, everything a driver needs to take the next
/// step, so that a path can be saved after any step and continued from it (checkpoint.h).
struct PathState
{
  int step = 0;          ///< steps completed
  double load = 0;       ///< load factor of the last completed step (t, or lambda)
  double step_size = 0;  ///< size of the next step (dt, or ds); 0: the driver's first step
  double arc_length = 0; ///< path length s so far (arc-length)
  int cutbacks = 0;      ///< step cut-backs so far
  /// Arc-length: the direction of the last step in the unknowns (dx/ds, null before the first)
  /// and in the load (dlambda/ds)
  OwnedVec direction;
  double load_direction = 0;
  double stability = NAN; ///< the tangent's eigenvalue nearest zero at the last point, if tracked
  int negative_eigenvalues = -1; ///< the tangent's negative eigenvalues there (inertia), if tracked
  /// What the scene accumulates along the path (curves for fits, extrema): its observers keep
  /// it here so that a restart continues it
  nlohmann::json scene = nlohmann::json::object();
  /// A driver's own state beyond the scalars above, in the unknowns' layout (dynamics: the
  /// velocity, the acceleration, the previous step's state) and as numbers (its energy
  /// accounts): a checkpoint stores both, so that the driver continues exactly
  std::map<std::string, OwnedVec> vectors;
  nlohmann::json driver = nlohmann::json::object();
};

/// One completed step.
struct StepRecord
{
  int step = 0;
  double load = 0;          ///< load factor reached
  double step_size = 0;     ///< dt or ds taken
  double arc_length = 0;    ///< path length s up to this point (arc-length)
  NewtonReport newton;      ///< the converged solve
  int cutbacks = 0;         ///< failed attempts before this step converged
  double wall_time = 0;     ///< seconds spent on this step, failed attempts included
  bool limit_point = false; ///< the load passed an extremum since the previous point
  double stability = NAN;   ///< the tangent's eigenvalue nearest zero (when tracked)
  int negative_eigenvalues = -1; ///< the tangent's negative eigenvalues (inertia; when tracked)
  /// The stability changed by more than a limit point explains: the eigenvalue nearest zero
  /// changed sign, or the number of negative eigenvalues changed, while the tangent's load
  /// component kept its sign (with it changing, by more than one eigenvalue)
  bool bifurcation = false;
};

/// The columns every path's steps.csv shares: the step's number, its Newton solve (iterations,
/// linear iterations, final and first residual), cut-backs and wall time. A scene adds its
/// load and quantities.
inline nlohmann::json step_columns(const StepRecord& s)
{
  return {{"step", s.step},
          {"newton_iterations", s.newton.iterations},
          {"linear_iterations", s.newton.linear_iterations},
          {"newton_residual", s.newton.residual},
          {"newton_residual0", s.newton.residual0},
          {"cutbacks", s.cutbacks},
          {"wall_time", s.wall_time}};
}

/// The columns of a point's stability, as far as the path tracks it (null where it does not):
/// the tangent's eigenvalue nearest zero, its number of negative eigenvalues, and whether a
/// bifurcation was passed since the previous point.
inline nlohmann::json stability_columns(const StepRecord& s)
{
  auto tracked = [](bool is, auto value) { return is ? nlohmann::json(value) : nlohmann::json(); };
  return {{"stability", tracked(!std::isnan(s.stability), s.stability)},
          {"negative_eigenvalues", tracked(s.negative_eigenvalues >= 0, s.negative_eigenvalues)},
          {"bifurcation", s.bifurcation}};
}

/// Sees every completed step with the path's state after it (write output there: a step
/// reported is complete; keep what must survive a restart in state.scene).
using StepObserver = std::function<void(const StepRecord&, PathState&)>;

} // namespace gelx
