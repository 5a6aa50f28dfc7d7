"""Work-precision benchmark of the pyramid scene: the slope of l_c/L against d/H and l_c/L at
d/H = 0.5 (on the least-squares line through all steps, which averages the steps of one node
spacing that the measured width takes), against wall time, over mesh levels (hexahedra per
pyramid block edge, tip graded by 3 levels), for Q1-P0 and Q2-Q1 elements, at 1 and 2 ranks, and the quarter cell against the
half cell (the quarter and its mirror image) on one level. The error is measured against the
value extrapolated from the three finest Q1-P0 levels (Richardson, with the observed order).

usage: bench.py BUILD_DIR OUTPUT_DIR [--quick] [--reuse]
(--quick: the two coarsest levels of each order only, a check that the benchmark runs;
--reuse: keep the runs already in OUTPUT_DIR, e.g. after adding a level)
"""
import csv
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from studies import richardson, run_scene  # noqa: E402  (demos/studies.py)

build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
quick, reuse = "--quick" in sys.argv[3:], "--reuse" in sys.argv[3:]
D_MAX, TIP_LEVELS = 0.5, 3

# (order, cells, ranks, domain): every level at 2 ranks; 1 rank where it costs under ~2 minutes
RUNS = [(1, 1, 2, "quarter"), (1, 2, 2, "quarter"), (1, 3, 2, "quarter"), (1, 4, 2, "quarter"),
        (1, 5, 2, "quarter"), (2, 1, 2, "quarter"), (2, 2, 2, "quarter"), (1, 3, 2, "half"),
        (1, 1, 1, "quarter"), (1, 2, 1, "quarter"), (1, 3, 1, "quarter"), (2, 1, 1, "quarter")]
if quick:
    RUNS = [r for r in RUNS if r[1] <= 2 and r[2] == 2]


def run(order, cells, ranks, domain):
    s = run_scene(build, "pyramid", out / f"q{order}_cells{cells}_np{ranks}_{domain}", ranks,
                  ["--order", str(order), "--cells", str(cells), "--domain", domain,
                   "--tip_levels", str(TIP_LEVELS), "--d_max", str(D_MAX),
                   "--extrapolate", "false"], reuse)
    return {"order": order, "cells": cells, "ranks": ranks, "domain": domain,
            "dofs": s["num_dofs"], "hexahedra": s["num_cells"], "wall_time": s["wall_time"],
            "slope": s["slope_lc_vs_d"],
            "width": s["slope_lc_vs_d"] * D_MAX + s["intercept_lc_vs_d"],
            "force": s["final_force"], "area_ratio": s["area_ratio"]}


out.mkdir(parents=True, exist_ok=True)
rows = [run(*r) for r in RUNS]
references = {}
finest = sorted((r for r in rows if r["order"] == 1 and r["ranks"] == 2
                 and r["domain"] == "quarter"),
                key=lambda r: r["cells"])[-3:]
for key in ("slope", "width"):
    references[key] = richardson([1 / r["cells"] for r in finest], [r[key] for r in finest])
for r in rows:
    for key in ("slope", "width"):
        r[f"{key}_error"] = abs(r[key] / references[key][0] - 1)
    # What the scene reports as slope_lc_vs_d_extrapolated (--extrapolate): the first-order
    # Richardson limit of this level and the next coarser one
    coarser = [c for c in rows if (c["order"], c["ranks"], c["domain"], c["cells"])
               == (r["order"], r["ranks"], r["domain"], r["cells"] - 1)]
    r["slope_two_level"] = (r["cells"] * r["slope"] - (r["cells"] - 1) * coarser[0]["slope"]
                            if coarser else float("nan"))
    r["slope_two_level_error"] = abs(r["slope_two_level"] / references["slope"][0] - 1)

with open(out / "work_precision.csv", "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)

print(f"pyramid to d/H = {D_MAX}, tip graded by {TIP_LEVELS} levels; reference: Richardson "
      f"extrapolation of the Q1-P0 levels {[r['cells'] for r in finest]} at 2 ranks")
for key, (value, order) in references.items():
    print(f"  {key}: reference {value:.4f} (observed order {order:.2f})")
print("| element | cells | domain | ranks | dofs | wall time (s) | slope | error | l_c/L at 0.5 "
      "| error | two-level slope | error |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for r in rows:
    element = "Q1-P0" if r["order"] == 1 else "Q2-Q1"
    print(f"| {element} | {r['cells']} | {r['domain']} | {r['ranks']} | {r['dofs']} | "
          f"{r['wall_time']:.1f} | "
          f"{r['slope']:.4f} | {100 * r['slope_error']:.2f} % | {r['width']:.4f} | "
          f"{100 * r['width_error']:.2f} % | {r['slope_two_level']:.4f} | "
          f"{100 * r['slope_two_level_error']:.2f} % |")

fig, axes = plt.subplots(1, 2, figsize=(10, 4))
for ax, key, label in zip(axes, ("slope", "width"), ("slope of l_c/L against d/H",
                                                      "l_c/L at d/H = 0.5")):
    for order, marker in ((1, "o"), (2, "s")):
        for ranks, style in ((1, "--"), (2, "-")):
            sel = sorted((r for r in rows if r["order"] == order and r["ranks"] == ranks
                          and r["domain"] == "quarter"),
                         key=lambda r: r["cells"])
            if sel:
                ax.loglog([r["wall_time"] for r in sel],
                          [max(r[f"{key}_error"], 1e-5) for r in sel], marker + style,
                          label=f"{'Q1-P0' if order == 1 else 'Q2-Q1'}, {ranks} rank(s)")
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("relative error against the extrapolated value")
    ax.set_title(label)
    ax.grid(alpha=0.3, which="both")
    for r in rows:
        if r["domain"] == "half":
            ax.loglog(r["wall_time"], max(r[f"{key}_error"], 1e-5), "k^", ms=8,
                      label=f"half cell, Q1-P0, cells {r['cells']}")
    ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(out / "work_precision.png", dpi=120)
print(f"wrote {out / 'work_precision.csv'} and {out / 'work_precision.png'}")

# Against what a user would write instead: a plain dolfinx model of the pyramid (P2-P1
# tetrahedra, 11,452 unknowns, ../shared/NOTES.md) stalls at d/H = 0.34. gelx's time from
# start-up to d/H = 0.34 and to 0.8 at 1 rank, on the mesh of about that size (3 cells) and on
# the default mesh (4 cells): the first step's `elapsed` at or past each d/H in steps.csv
print("\n| cells | unknowns | ranks | time to d/H = 0.34 (s) | time to d/H = 0.8 (s) |")
print("| --- | --- | --- | --- | --- |")
for cells in ([2] if quick else [3, 4]):
    folder = out / f"to_0.8_cells{cells}_np1"
    s = run_scene(build, "pyramid", folder, 1,
                  ["--cells", str(cells), "--d_max", "0.8", "--extrapolate", "false"], reuse)
    steps = list(csv.DictReader(open(folder / "steps.csv")))
    reached = [next(float(r["elapsed"]) for r in steps if float(r["d_over_H"]) >= d - 1e-12)
               for d in (0.34, 0.8)]
    print(f"| {cells} | {s['num_unknowns']} | 1 | {reached[0]:.1f} | {reached[1]:.1f} |")
