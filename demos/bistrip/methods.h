#pragma once
/// @file methods.h
/// The bistrip's path from end distance L to the final one, followed by one of the scene's
/// methods (analysis.h): the first-order viscous flow (gelx::DampedDynamics), the equation of
/// motion (gelx::InertialDynamics) or arc-length continuation (gelx::ArcLength). What differs
/// between the methods is here; what is recorded along the path is the same for all
/// (path_record.h).

#include "analysis.h"
#include "bistrip.h"
#include "path_record.h"

#include <gelx/io/program.h>

namespace gelx::scenes
{

/// Step 5 of the scene: with --bonding quench or ramp a leg 0 at L first (the flow), then the
/// end from L to a.end_distance on a smooth-step ramp (leg 1), and with --return_distance back
/// out (leg 2); every step into `record`, each method's summary into run.summary ("dynamics",
/// "inertial_dynamics", "arclength_steps" ...). Throws ConvergenceError when the method gives
/// up before the final end distance. Collective.
void follow_path(Run& run, Bistrip& strip, const BistripParameters& p, const BistripAnalysis& a,
                 PathRecord& record);

} // namespace gelx::scenes
