"""The bistrip's settle leg (--settle_time): after a fast inertial path (20 slabs, 300 -> 280 mm
in 0.05 s, held 0.05 s), the first-order flow at c = 1/s with the end held, a gradient flow.

- before it the strip still moves: the path's last state is off equilibrium, |R| / |f_int| above
  1e-7 (measured 1.4e-5: an inertial state carries inertial forces);
- after it the strip is at rest in a static equilibrium, |R| / |f_int| <= 1e-9 (measured 8e-14):
  what --equilibria's static Newton solve and the metastable states of section 3.3 need;
- the flow holds the end: every settle row at the path's last end distance (1e-12 mm) and the
  end force's work unchanged over the leg (1e-12 relative);
- a gradient flow only lowers the energy: the strain energy SE_A + SE_B falls or stays at every
  settle output (to 1e-12 of SE, round-off), and the flow dissipates what it loses.
A settle leg that did not run, or ran the inertial integrator again, fails the first two (the
residual stays at the path's); one that moved the end fails the third.

usage: bistrip_settle.py OUTPUT_DIR
"""
import csv
import json
import pathlib
import sys

from checks import Checks

out = pathlib.Path(sys.argv[1])
summary = json.loads((out / "summary.json").read_text())
rows = list(csv.DictReader(open(out / "steps.csv")))
checks = Checks()
checks.require(f"the run completed ({summary['status']})", summary["status"] == "completed")
path = [r for r in rows if r["leg"] == "1"]
settle = [r for r in rows if r["leg"] == "3"]
checks.require(f"{len(path)} outputs of the path (leg 1), {len(settle)} of the settle leg (3)",
               len(path) > 0 and len(settle) > 0)
if not path or not settle:
    checks.finish()
before = float(path[-1]["static_residual"])
checks.require(f"the path ends off equilibrium: |R| / |f_int| = {before:.3g} > 1e-7",
               before > 1e-7)
checks.absolute("after the settle leg: |R| / |f_int|", float(settle[-1]["static_residual"]), 0.0,
                1e-9)
d = float(path[-1]["end_distance"])
for r in settle:
    checks.absolute(f"settle step {r['step']}: the end held at the path's {d} mm",
                    float(r["end_distance"]), d, 1e-12)
checks.relative("the end force's work over the settle leg", float(settle[-1]["work"]),
                float(path[-1]["work"]), 1e-12)
energy = [float(r["strain_energy_A"]) + float(r["strain_energy_B"]) for r in path[-1:] + settle]
rises = [b - a for a, b in zip(energy, energy[1:])]
checks.require(f"the strain energy never rises over the flow: largest change "
               f"{max(rises):.3g} mJ of SE = {energy[0]:.6g} mJ (drop {energy[0] - energy[-1]:.3g})",
               max(rises) <= 1e-12 * energy[0])
checks.require(f"the flow dissipated energy ({summary['settle_dynamics']['dissipated_energy']:.3g} "
               f"mJ)", summary["settle_dynamics"]["dissipated_energy"] > 0)
checks.finish()
