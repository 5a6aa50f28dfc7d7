#include "analysis.h"

#include <gelx/io/parameters.h>

namespace gelx::scenes
{

void BistripAnalysis::bind(Parameters& prm)
{
  prm.bind("analysis", "end_distance", end_distance, "final end-to-end distance (mm)",
           Parameters::positive);
  prm.bind("analysis", "return_distance", return_distance,
           "after end_distance, drive the end back to this distance (mm; 0: no return)",
           Parameters::non_negative);
  prm.bind("analysis", "output_every", output_every, "output every this much end travel (mm)",
           Parameters::positive);
  prm.bind("analysis", "modes", modes, "buckling modes to compute",
           Parameters::at_least_one);
  prm.bind("analysis", "seed_mode", seed_mode, "the buckling mode seeded as imperfection",
           Parameters::at_least_one);
  prm.bind("analysis", "seed", seed, "imperfection: mode (a buckling mode) or random",
           Parameters::one_of({"mode", "random"}));
  prm.bind("analysis", "bonding", bonding,
           "instant (A bonded with its prestretch), quench (then left to buckle at L) or ramp "
           "(the prestretch built up at L first)",
           Parameters::one_of({"instant", "quench", "ramp"}));
  prm.bind("analysis", "harmonics", harmonics, "sines along the strip of --seed random",
           Parameters::at_least_one);
  prm.bind("analysis", "noise", noise,
           "amplitude of a random imperfection added to the seeded mode (mm; 0: none)",
           Parameters::non_negative);
  prm.bind("analysis", "random_seed", random_seed,
           "the generator's seed of the random imperfection (--seed random or --noise)",
           Parameters::at_least_one);
  prm.bind("analysis", "imperfection", imperfection,
           "amplitude of the seeded mode (mm, its largest component 1)",
           Parameters::non_negative);
  prm.bind("analysis", "probe_shortening", probe_shortening,
           "the eigen-buckling's perturbation: an end shortening (mm)", Parameters::positive);
  prm.bind("analysis", "method", method,
           "path: dynamics (first-order flow), inertia (equation of motion, implicit), "
           "explicit (equation of motion, central differences) or arclength",
           Parameters::one_of({"dynamics", "inertia", "explicit", "arclength"}));
  prm.bind("analysis", "max_steps", max_steps, "arc-length steps at most",
           Parameters::at_least_one);
  prm.bind("analysis", "settle_time", settle_time,
           "after the path, the first-order flow at c = 1/s with the end held this long "
           "(s; 0: none): towards a static equilibrium without leaving a metastable state",
           Parameters::non_negative);
  prm.bind("analysis", "equilibria", equilibria,
           "equilibria to seek by deflation at the final end distance (0: none)",
           Parameters::non_negative);
  prm.bind("analysis", "guess_amplitude", guess_amplitude,
           "deflation's guesses: the path's state +- each mode at this amplitude (mm)",
           Parameters::positive);
  prm.bind("analysis", "min_frame_turns", min_frame_turns,
           "turns of the frame below which a stretch of one twist sign is noise",
           Parameters::positive);
}

void BistripAnalysis::check(const BistripParameters& p) const
{
  // At L a run with a bonding leg is that leg alone: the strip left to buckle at L
  if (p.ends == "clamped" && end_distance >= p.L && !(end_distance == p.L && bonding != "instant"))
    throw InputError("end_distance must be below L (or equal to it with --bonding quench or "
                     "ramp: the bonding leg alone)");
  if (return_distance > 0 && (return_distance <= end_distance || return_distance > p.L))
    throw InputError("return_distance must lie in (end_distance, L]");
  if (equilibria > 0 && seed != "mode")
    throw InputError("equilibria need the buckling modes for guesses: --seed mode");
  if (bonding != "instant" && (seed != "random" || method == "arclength"))
    throw InputError("--bonding " + bonding + " needs --seed random and a method in time "
                     "(dynamics, inertia or explicit)");
  if ((return_distance > 0 || settle_time > 0) && method == "arclength")
    throw InputError("return_distance and settle_time need --method dynamics, inertia or "
                     "explicit");
  if (noise > 0 && seed != "mode")
    throw InputError("--noise adds to a seeded mode: --seed mode");
  if (seed_mode > modes)
    throw InputError("seed_mode must be one of the computed modes (1 .. modes)");
}

} // namespace gelx::scenes
