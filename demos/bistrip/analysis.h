#pragma once
/// @file analysis.h
/// What the bistrip scene does with the strip (bistrip.h): the path's end distances, its
/// method, the imperfection, the outputs and the searches at the final distance; the scene
/// parameters of section "analysis".

#include "bistrip.h"

#include <string>

namespace gelx
{
class Parameters;
}

namespace gelx::scenes
{

struct BistripAnalysis
{
  double end_distance = 90;  ///< final end-to-end distance (mm)
  /// After end_distance, drive the end back out to this distance (mm; 0: no return leg): the
  /// stretching back of thesis Fig. 3.9
  double return_distance = 0;
  double output_every = 10;  ///< output every this much of end travel (mm)
  int modes = 5;             ///< buckling modes to compute
  int seed_mode = 1;         ///< the mode seeded as the imperfection
  /// Amplitude of the seeded mode (mm; largest component 1): the thesis' *IMPERFECTION
  /// "1, 1e-3" in its length unit, the cm of Table 3.1
  double imperfection = 0.01;
  /// The shortening of the eigen-buckling's perturbation load (mm): small, so that the
  /// tangent is still linear in it
  double probe_shortening = 0.1;
  double min_frame_turns = 0.25; ///< a helical segment's frame turns at least this much
  /// How the path is followed: "dynamics" (damped quasi-static dynamics, the first-order
  /// flow), "inertia" (the equation of motion, generalised-alpha), "explicit" (the same by
  /// central differences) or "arclength"
  /// (continuation in the end shortening, to compare where it gets through)
  std::string method = "dynamics";
  int max_steps = 2000; ///< arc-length steps at most
  /// The imperfection: "mode" (the seed_mode-th buckling mode) or "random" (a smooth random
  /// shape of the centreline with `harmonics` sines along it, Bistrip::random_imperfection)
  std::string seed = "mode";
  /// How A's prestretch is there: "instant" (bonded carrying all of it, thesis Table 3.1);
  /// for a pre-compressed A, whose bonded state is unstable from the start, a leg 0 at end
  /// distance L first (damped dynamics, options -bonding_dynamics_): "quench" (bonded with
  /// all of it, the strip left to buckle) or "ramp" (built up log-linearly)
  std::string bonding = "instant";
  int harmonics = 60;
  /// Amplitude (mm) of a random imperfection added to the seeded mode (0: none). A
  /// mirror-symmetric mode keeps a deterministic path symmetric to round-off; this breaks the
  /// symmetry by a stated amount, as round-off does in explicit dynamics
  double noise = 0;
  /// The generator's seed of the random imperfection (--seed random, or --noise)
  int random_seed = 1;
  /// After the path, the first-order flow c M u' + R(u) = 0 at c = 1/s with the end held,
  /// for this long (s; 0: none): a gradient flow from where the path ended, which keeps the
  /// perversions of a metastable state and lets a transient one go, settling towards a static
  /// equilibrium (options -settle_dynamics_)
  double settle_time = 0;
  /// Equilibria to seek by deflation at the final end distance, besides the path's (0: none)
  int equilibria = 0;
  /// The deflation's guesses: the path's state plus or minus each buckling mode at this
  /// amplitude (mm, the mode's largest component)
  double guess_amplitude = 3;

  /// Bind the members to scene parameters (section "analysis"), the current values as their
  /// defaults.
  void bind(Parameters& prm);
  /// Throws gelx::InputError on a combination that does not apply to the strip `p`.
  void check(const BistripParameters& p) const;
};

} // namespace gelx::scenes
