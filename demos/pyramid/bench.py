"""Work-precision benchmark of the pyramid scene: the slope of l_c/L against d/H fitted to
d/H = 0.8, with the patch's corner located by the contact level set and by the gap's 3/2 law
(both from one run: `slope_lc_vs_d`, `slope_lc_vs_d_gap_law`), against wall time, over mesh
levels (hexahedra per pyramid block edge, tip graded by 3 levels), Q1-P0 and Q2-Q1, at 1 rank.
The error is measured against the level set's slope on the five finest Q1-P0 levels
extrapolated to h = 0 at first order; the gap law's mean over them is reported beside it. Then gelx's time to d/H = 0.34 and 0.8 on the 3- and 4-cell meshes, against
a plain dolfinx model that stalls at 0.34.

usage: bench.py BUILD_DIR OUTPUT_DIR [--quick] [--reuse]
(--quick: the coarsest levels only, a check that the benchmark runs; --reuse: keep the runs
already in OUTPUT_DIR, e.g. after adding a level)
"""
import csv
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from fields import read_table  # noqa: E402  (demos/fields.py)
from studies import run_scene  # noqa: E402  (demos/studies.py)

build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
quick, reuse = "--quick" in sys.argv[3:], "--reuse" in sys.argv[3:]
D_MAX, TIP_LEVELS = 0.8, 3
ESTIMATORS = {"level_set": "slope_lc_vs_d", "gap_law": "slope_lc_vs_d_gap_law"}

# (order, cells): Q1-P0 to 8 cells, Q2-Q1 on 1 cell (its 2-cell mesh needed four cut-backs near
# d/H = 0.11 and had reached 0.15 after 20 minutes, README.md)
RUNS = [(1, cells) for cells in range(1, 9)] + [(2, 1)]
if quick:
    RUNS = [(1, 1), (1, 2), (1, 3), (2, 1)]


def folder(order, cells):
    return out / f"q{order}_cells{cells}_np1_quarter"


def run(order, cells):
    s = run_scene(build, "pyramid", folder(order, cells), 1,
                  ["--order", str(order), "--cells", str(cells), "--domain", "quarter",
                   "--tip_levels", str(TIP_LEVELS), "--d_max", str(D_MAX),
                   "--extrapolate", "false"], reuse)
    row = {"order": order, "cells": cells, "dofs": s["num_dofs"], "wall_time": s["wall_time"]}
    row.update({name: s[key] for name, key in ESTIMATORS.items()})
    return row


out.mkdir(parents=True, exist_ok=True)
rows = [run(*r) for r in RUNS]
# The reference: the level set's slope extrapolated to h = 0 by a least-squares line in
# h = 1/cells through the five finest Q1-P0 levels. Its corner is resolved to a fraction of
# the node spacing, so it converges at first order at best, and irregularly (differences
# 0.0058, 0.0042, 0.0034, 0.0043 from 4 to 8 cells): a three-level Richardson fit through such
# differences is ill-conditioned. The gap law's mean over the same levels is printed beside.
finest = sorted((r for r in rows if r["order"] == 1), key=lambda r: r["cells"])[-5:]
reference, rate = np.polynomial.polynomial.polyfit(
    [1 / r["cells"] for r in finest], [r["level_set"] for r in finest], 1)
misfit = max(abs(r["level_set"] - reference - rate / r["cells"]) for r in finest)
gap_law_mean = np.mean([r["gap_law"] for r in finest])
for r in rows:
    for name in ESTIMATORS:
        r[f"{name}_error"] = r[name] / reference - 1
    # What the scene reports as slope_lc_vs_d_extrapolated (--extrapolate): the first-order
    # Richardson limit of this level's and the next coarser one's level-set slopes
    coarser = [c for c in rows if (c["order"], c["cells"]) == (r["order"], r["cells"] - 1)]
    r["two_level"] = (r["cells"] * r["level_set"] - (r["cells"] - 1) * coarser[0]["level_set"]
                      if coarser else float("nan"))
    r["two_level_error"] = r["two_level"] / reference - 1

with open(out / "work_precision.csv", "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)

print(f"pyramid to d/H = {D_MAX}, tip graded by {TIP_LEVELS} levels, 1 rank; reference: the "
      f"level set's slope on the Q1-P0 levels {[r['cells'] for r in finest]} extrapolated to "
      f"h = 0 at first order: {reference:.4f} (largest misfit {misfit:.4f}); the gap law's mean "
      f"slope on them: {gap_law_mean:.4f}")
print("| element | cells | dofs | wall time (s) | slope, level set | error | slope, gap law "
      "| error | two-level slope | error |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for r in rows:
    element = "Q1-P0" if r["order"] == 1 else "Q2-Q1"
    print(f"| {element} | {r['cells']} | {r['dofs']} | {r['wall_time']:.1f} | "
          f"{r['level_set']:.4f} | {100 * r['level_set_error']:+.2f} % | "
          f"{r['gap_law']:.4f} | {100 * r['gap_law_error']:+.2f} % | "
          f"{r['two_level']:.4f} | {100 * r['two_level_error']:+.2f} % |")

fig, ax = plt.subplots(figsize=(6, 4.5))
for order, marker in ((1, "o"), (2, "s")):
    sel = sorted((r for r in rows if r["order"] == order), key=lambda r: r["cells"])
    element = "Q1-P0" if order == 1 else "Q2-Q1"
    for name, style, label in (("level_set", "--", "level set"), ("gap_law", "-", "gap's 3/2 law"),
                               ("two_level", ":", "two-level Richardson (level set)")):
        points = [(r["wall_time"], abs(r[f"{name}_error"])) for r in sel
                  if r[f"{name}_error"] == r[f"{name}_error"]]
        if points:
            ax.loglog(*zip(*points), marker + style, label=f"{element}, {label}")
ax.axhline(0.01, color="k", lw=0.8, alpha=0.5)
ax.set_xlabel("wall time (s), 1 rank")
ax.set_ylabel("|slope / reference - 1|")
ax.set_title(f"slope of l_c/L against d/H, fitted to d/H = {D_MAX}")
ax.grid(alpha=0.3, which="both")
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(out / "work_precision.png", dpi=120)
print(f"wrote {out / 'work_precision.csv'} and {out / 'work_precision.png'}")

# Against what a user would write instead: a plain dolfinx model of the pyramid (P2-P1
# tetrahedra, 11,452 unknowns, ../shared/NOTES.md) stalls at d/H = 0.34. gelx's time from
# start-up to d/H = 0.34 and to 0.8 at 1 rank, on the mesh of about that size (3 cells) and on
# the default mesh (4 cells): the first step's `elapsed` at or past each d/H in steps.csv
print("\n| cells | dofs | ranks | time to d/H = 0.34 (s) | time to d/H = 0.8 (s) |")
print("| --- | --- | --- | --- | --- |")
for r in rows:
    if r["order"] == 1 and r["cells"] in (3, 4):
        steps = read_table(folder(1, r["cells"]) / "steps.csv")
        reached = [next(float(s["elapsed"]) for s in steps if float(s["d_over_H"]) >= d - 1e-12)
                   for d in (0.34, 0.8)]
        print(f"| {r['cells']} | {r['dofs']} | 1 | {reached[0]:.1f} | {reached[1]:.1f} |")
