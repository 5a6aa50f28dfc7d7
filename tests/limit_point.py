"""Check an inflation run (demos/inflation) against the closed form of the inflated
incompressible neo-Hookean shell, p/G as a function of the inner stretch, computed here from the
run's radii A and B (closed_forms.shell_pressure_over_G; its maximum where its slope vanishes;
the scene's load factor is p/G): the arc-length path passed the pressure maximum, and the
maximum pressure and its stretch are within 1% (the issue's bound: the discretisation, P2 on a
faceted P1 surface at h = 0.125 A, and the compressibility K/G = 1000 each shift the peak by a
few 1e-3; measured 4.0e-3 and 2.1e-4); the falling branch's last point within 2% of the closed
form at its stretch (measured 5.5e-3).

usage: limit_point.py OUTPUT_DIR
"""
import csv
import json
import pathlib
import sys

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from closed_forms import shell_pressure_maximum, shell_pressure_over_G  # noqa: E402  (demos/closed_forms.py)

out = pathlib.Path(sys.argv[1])
s = json.loads((out / "summary.json").read_text())
rows = list(csv.DictReader(open(out / "steps.csv")))
p = s["parameters"]
A, B = p["A"], p["B"]
stretch_at_max, p_max = shell_pressure_maximum(A, B)
checks = Checks()
checks.require(f"{s['steps']} arc-length steps, a limit point among them",
               any(r["limit_point"] == "true" for r in rows))
checks.relative("maximum pressure p_max / G", s["p_max_over_G"], p_max, 0.01)
checks.relative("inner stretch at the maximum", s["stretch_at_p_max"], stretch_at_max, 0.01)
last = rows[-1]
checks.require(f"the falling branch reached {float(last['pressure_over_G']) / s['p_max_over_G']:.3f}"
               " of the maximum", float(last["pressure_over_G"]) < 0.81 * s["p_max_over_G"])
stretch = float(last["inner_stretch"])
checks.relative(f"pressure on the falling branch at stretch {stretch:.4f}",
                float(last["pressure_over_G"]), shell_pressure_over_G(stretch, A, B), 0.02)
checks.finish()
