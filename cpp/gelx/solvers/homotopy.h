#pragma once
/// @file homotopy.h
/// From one equilibrium to another along a homotopy that may pass folds.

#include <gelx/solvers/load_stepping.h>
#include <gelx/solvers/newton.h>
#include <gelx/solvers/path.h>

#include <functional>
#include <string>

namespace gelx
{

/// Carries `system` from its equilibrium at t = 0 to one at t = 1, `apply_load(t)` setting what
/// changes along the way (a design, a material, loads). Load steps (LoadStepper with `options`)
/// while they converge. When one fails for good, the path has a fold ahead: no equilibrium near
/// the last one exists beyond its t (a shape that snaps). From the last completed step the path
/// is then followed by arc length in t (ArcLength, options prefix `prefix`) through its folds
/// until it passes t = 1, and Newton at t = 1, started between the two points around it, lands
/// on it. The equilibrium reached is the one the path connects to the start: past the two folds
/// of an S, the branch that a slow increase of t snaps onto at the first; in general not
/// necessarily a stable one.
///
/// The arc length's scale, unless -PREFIX_ds and -PREFIX_psi set it: the load's weight psi is
/// the load steps' mean rate |x(t) - x(0)| / t, so that t and the unknowns count alike, and the
/// first arc length 0.02 psi. -PREFIX_max_steps bounds the arc-length steps (default 200).
/// `observe` (if not null) sees every completed step of either kind and the landing. Throws
/// ConvergenceError when no load step completed (no scale), the arc length falls below its
/// minimum, the path does not pass t = 1 within max_steps, or the landing fails. Collective.
void follow_homotopy(NonlinearSystem& system, NewtonSolver& newton, LoadSteppingOptions options,
                     const std::function<void(double)>& apply_load, const StepObserver& observe,
                     const std::string& prefix);

} // namespace gelx
