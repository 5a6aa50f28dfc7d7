"""Physics of the pyramid's apex that holds whatever the mesh, checked on two pyramid runs that
load to d/H = d_max and unload back to 0 (--unload) in equal steps, with moduli G and s G.

1. Self-similarity. A sharp apex against a flat plane has no length scale of its own: at small
   indentation the solution is self-similar, so the force grows as f = C G d^2 and the contact
   width as l_c = c d (a straight line through the origin). On the loading half (d/H <= d_max,
   far below the base and period) the log-log slopes of f and l_c against d must be 2 and 1,
   and the least-squares line l_c/L = a d/H + b must pass through the origin. Tolerances: the
   patch grows one node at a time, which makes f/(G d^2) oscillate by about +-5% about its mean
   on the graded apex mesh; over a factor 16 in d (ln 16 = 2.8) that moves the fitted slopes by
   at most about 0.1/2.8 = 0.035, and the far field adds O(d/H); 0.05 on both slopes. A mesh
   that does not resolve the patch (one node in contact: f grows like the apex node's spring,
   f ~ d) gives a force slope near 1.3 and fails, as does any length scale in the contact law.
   The intercept within 2% of a d_max (measured 0.5%).
2. Unloading. Frictionless contact of an elastic body stores no history: every unloading step
   must reproduce the loading step at the same d, force and contact nodes, to the Newton
   tolerance (|R| <= 1e-10 |R0|; 1e-8 of the largest force), and at d = 0 the force must vanish
   (1e-8 of the largest force) with at most the apex node left touching the plane.
3. f = G f(G = 1): for an incompressible law the moduli scale the energy and leave the kinematic
   constraint alone, so the s G run carries s times the force at every step with the same widths
   (1e-8 of the largest force and of L: the Newton tolerance with two digits of margin).

usage: pyramid_apex.py OUTPUT_G OUTPUT_sG
"""
import json
import pathlib
import sys

import numpy as np

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)


def load(folder):
    folder = pathlib.Path(folder)
    rows = read_table(folder / "steps.csv")
    columns = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    return json.loads((folder / "summary.json").read_text()), columns


(s1, a), (s2, b) = load(sys.argv[1]), load(sys.argv[2])
checks = Checks()
for folder in sys.argv[1:3]:
    checks.newton_tolerance(read_table(pathlib.Path(folder) / "steps.csv"),
                            f"{folder}: every step")
p1, p2 = s1["parameters"], s2["parameters"]
checks.require(f"runs {s1['status']} and {s2['status']}, unloading, G = {p1['G']} and {p2['G']}",
               s1["status"] == s2["status"] == "completed" and p1["unload"] and p2["unload"]
               and p2["G"] != p1["G"])

d, f, width = a["d_over_H"], a["force"], a["contact_width_over_L"]
top = int(np.argmax(d))
loading = slice(0, top + 1)
checks.absolute("the path turns at d/H = d_max", d[top], p1["d_max"], 1e-12)

# 1. Self-similarity on the loading half
slope_f = np.polyfit(np.log(d[loading]), np.log(f[loading]), 1)[0]
slope_w = np.polyfit(np.log(d[loading]), np.log(width[loading]), 1)[0]
a_fit, b_fit = np.polyfit(d[loading], width[loading], 1)
c = f[loading] / (p1["G"] * (d[loading] * p1["L"] / np.sqrt(2)) ** 2)
print(f"f/(G d^2) over {top + 1} loading steps: {c.min():.4f} ... {c.max():.4f} "
      f"(mean {c.mean():.4f})")
checks.absolute("log-log slope of the force against d (self-similar: 2)", slope_f, 2.0, 0.05)
checks.absolute("log-log slope of the contact width against d (self-similar: 1)", slope_w, 1.0,
                0.05)
checks.absolute(f"line l_c/L = {a_fit:.4f} d/H + b: b / (a d_max)", b_fit / (a_fit * p1["d_max"]),
                0.0, 0.02)

# 2. Unloading retraces loading
f_max = f.max()
worst_force, same_nodes = 0.0, True
for k in range(top + 1, len(d) - 1):
    match = int(np.argmin(np.abs(d[loading] - d[k])))
    if abs(d[match] - d[k]) > 1e-12:
        checks.require(f"unloading step at d/H = {d[k]} has a loading step at the same d", False)
    worst_force = max(worst_force, abs(f[k] - f[match]) / f_max)
    same_nodes = same_nodes and a["active_nodes"][k] == a["active_nodes"][match]
checks.absolute("unloading: largest |f_unload - f_load| / f_max at equal d", worst_force, 0.0,
                1e-8)
checks.require("unloading: the same number of nodes in contact as on loading at every d",
               same_nodes)
checks.absolute("back at d = 0", d[-1], 0.0, 1e-12)
checks.absolute("force at d = 0 / f_max", f[-1] / f_max, 0.0, 1e-8)
checks.require(f"nodes in contact at d = 0: {int(a['active_nodes'][-1])} (at most the apex)",
               a["active_nodes"][-1] <= 1)

# 3. The force scales with G
scale = p2["G"] / p1["G"]
checks.require(f"both runs took the same {len(d)} steps", len(b["force"]) == len(d))
checks.absolute(f"largest |f(sG) - s f(G)| / (s f_max), s = {scale}",
                np.abs(b["force"] - scale * f).max() / (scale * f_max), 0.0, 1e-8)
checks.absolute("largest |l_c(sG) - l_c(G)| / L", np.abs(b["contact_width_over_L"] - width).max(),
                0.0, 1e-8)
checks.finish()
