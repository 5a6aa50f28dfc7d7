"""Check a buckling run (demos/buckling, clamped-free column) against Euler and the elastica.

- the first critical load against pi^2 EI/(2L)^2 within 2% (the issue's bound at slenderness
  >= 50; shear and the cross-section's Poisson effect are O((r/L)^2) ~ 1e-4 here, the rest is
  discretisation);
- the perfect column: the tangent's eigenvalue changes sign between two points that bracket the
  critical load, and the branch followed after switching carries the elastica's load at its
  final deflection within 1% (beyond beam theory, axial shortening and shear are O((r/L)^2);
  measured 0.06% at d/L = 0.33), after deflecting past d/L = 0.3: the switch left the
  straight path;
- the imperfect column (mode 1 seeded with 0.01 tx) within 2% of the elastica at d/L >= 0.3
  (the imperfection's own effect is about 0.3% there) and below it at small deflection,
  where an imperfect column carries less than the perfect one.

usage: post_buckling.py OUTPUT_DIR
"""
import csv
import json
import pathlib
import sys

from checks import Checks

out = pathlib.Path(sys.argv[1])
s = json.loads((out / "summary.json").read_text())
rows = list(csv.DictReader(open(out / "steps.csv")))
checks = Checks()
P_cr = s["critical_loads_over_euler"][0]
checks.require(f"slenderness {s['slenderness']:.1f} >= 50", s["slenderness"] >= 50)
checks.relative("first critical load / Euler load", P_cr, 1.0, 0.02)
lo, hi = s["bifurcation_bracket"]
checks.require(f"bifurcation detected between {lo / P_cr:.4f} and {hi / P_cr:.4f} P_cr",
               lo <= P_cr <= hi)
branch = [r for r in rows if r["path"] == "branch"]
checks.require(f"{len(branch)} points on the switched branch, the last at d/L = "
               f"{s['branch_deflection_over_L']:.4f} >= 0.3", s["branch_deflection_over_L"] >= 0.3)
checks.relative("switched branch: P/P_cr at its last point against the elastica",
                s["branch_load_over_critical"], s["elastica_at_branch_end"], 0.01)
checks.require("switched branch: every point within 1% of the elastica",
               all(abs(float(r["axial_force_over_euler"]) / float(r["elastica_load_over_euler"])
                       - 1) <= 0.01 for r in branch))
checks.relative("imperfect column: P/P_cr at its last point against the elastica",
                s["imperfect_load_over_critical"], s["elastica_at_imperfect_end"], 0.02)
imperfect = [r for r in rows if r["path"] == "imperfect"]
first = imperfect[0]
checks.require(f"imperfect column below the elastica at d/L = "
               f"{float(first['deflection_over_L']):.2e}",
               float(first["axial_force_over_euler"]) < float(first["elastica_load_over_euler"]))
eigen = list(csv.DictReader(open(out / "eigenvalues.csv")))
checks.require(f"{len(eigen)} modes in eigenvalues.csv, in increasing order",
               all(float(a["critical_load_over_euler"]) <= float(b["critical_load_over_euler"])
                   for a, b in zip(eigen, eigen[1:])))
checks.finish()
