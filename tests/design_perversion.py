"""The design scene's perversion between two clamps (demos/design --shape perversion, its
README's command stopped after a few iterations).

The target: a right-handed helix of 1 whole turn, a perversion at 10 mm, a left-handed helix
of 2 whole turns, radius R = 1.2 mm, on a 30 x 1 x 0.5 strip held by two clamps (the far one
where the target puts it: after whole turns, a translation). Checked:
- the detector on the target placement itself (built in closed form) finds one perversion, at
  10 mm within the samples' spacing (0.25 mm), the radius R within 5e-3 (central differences
  on samples 0.25 mm apart on a frame turning at omega = 1 / 1.59 mm: (omega ds)^2 / 6 = 4e-3;
  measured 1.7e-3) and the turns 1 and 2 within 3 % (the rate by central differences of
  chords, one-sided at the clamps and straddling the perversion's kink, integrated over the
  samples; measured 1.3 % and 0.8 % short): the measure is sound;
- the start (the narrow-strip theory per slab, its angle's sign flipped past 10 mm), carried
  from rest with the far clamp, forms one perversion within a slab (2 mm) of 10 mm and 1 and
  2 turns within 0.15: the strip between clamps makes the perversion where the hands change,
  as the bistrip does (measured 10.04; 1.013 and 1.971 turns); its radius is more than 10 %
  off (measured 0.84), so the design has work to do; with the angle left unflipped (one
  hand throughout) the strip cannot reach the clamps from rest (the path turned back at
  t = 0.45, measured), and the test fails;
- after the iterations the rms distance to the target has fallen by more than 10 % and the
  radius moved toward R (the adjoint gradient of the clamped strip points downhill: measured
  2.22 to 1.86 mm and 0.84 to 0.90 mm after 3), the perversion still within a slab of 10 mm.

usage: design_perversion.py RUN_DIR
"""
import json
import pathlib
import sys

from checks import Checks

run = pathlib.Path(sys.argv[1])
summary = json.loads((run / "summary.json").read_text())
checks = Checks()
R, at, slab = summary["target_radius"], 10.0, 2.0
checks.require(f"the run ended ({summary.get('status')})",
               summary.get("status") == "completed")
checks.require(f"the target has one perversion ({summary['target_perversions']})",
               summary["target_perversions"] == 1)
checks.absolute("the target's perversion", summary["target_perversion_position"], at, 0.25)
checks.relative("the target's helix radius (detector)", summary["target_helix_radius"], R, 5e-3)
checks.relative("the target's turns before", summary["target_helix_turns_before"], 1, 3e-2)
checks.relative("the target's turns after", summary["target_helix_turns_after"], 2, 3e-2)
checks.require(f"the start has one perversion ({summary['start_perversions']})",
               summary["start_perversions"] == 1)
checks.absolute("the start's perversion", summary["start_perversion_position"], at, slab)
checks.absolute("the start's turns before", summary["start_helix_turns_before"], 1, 0.15)
checks.absolute("the start's turns after", summary["start_helix_turns_after"], 2, 0.15)
start_error = abs(summary["start_helix_radius"] - R) / R
checks.require(f"the start's radius is more than 10 % off ({start_error:.3g})", start_error > 0.1)
checks.require(f"the rms distance fell by more than 10 % ({summary['rms_distance_start']:.4g} to "
               f"{summary['rms_distance']:.4g})",
               summary["rms_distance"] < 0.9 * summary["rms_distance_start"])
checks.require(f"the radius moved toward R ({summary['start_helix_radius']:.4g} to "
               f"{summary['helix_radius']:.4g}, R = {R})",
               abs(summary["helix_radius"] - R) < abs(summary["start_helix_radius"] - R))
checks.require(f"one perversion at the end ({summary['perversions']})",
               summary["perversions"] == 1)
checks.absolute("the perversion at the end", summary["perversion_position"], at, slab)
sys.exit(checks.finish())
