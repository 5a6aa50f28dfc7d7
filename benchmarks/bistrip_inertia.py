"""The bistrip's inertial path, 30 -> 9 cm, against its goal: a converged perversion count in at
most 10 minutes on 2 cores (issue #29).

The default strip (w = 5 mm, mode 1 seeded) on 40 Q2 slabs (the count at T = 0.3 s is the same
on 80, demos/bistrip/README.md "With inertia") is driven by `--method inertia` with the
scene's defaults (the smooth step over 1 s, TSALPHA2 at fixed steps of 1 ms), and again at
half the step: the count is converged in the time step where the two agree. Per run: wall
time, steps, time per step, the time split (assembly, solve, ...), and the perversion count and
positions at 23.3 cm (passed on the way in) and at 9 cm. Time a quiet machine: both cores are
used (2 ranks). A run folder holding a completed run is reused.

usage: bistrip_inertia.py BUILD OUT [--np N]     (./gelx bench bistrip_inertia)
"""
import csv
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)
from studies import run_scene  # noqa: E402  (demos/studies.py)

build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
ranks = int(sys.argv[sys.argv.index("--np") + 1]) if "--np" in sys.argv else 2
GOAL = 600.0  # s
THESIS_DISTANCE = 233.0  # mm: Fig. 3.3
STEPS = {"1 ms": [], "0.5 ms": ["-inertial_dt", "5e-4"]}

rows = []
for label, options in STEPS.items():
    folder = out / ("dt_" + label.replace(" ", "").replace(".", "p"))
    summary = run_scene(build, "bistrip", folder, ranks,
                        ["--nz", "40", "--end_distance", "90", "--output_every", "5",
                         "--method", "inertia", *options], reuse=True)
    outputs = [r for r in read_table(folder / "steps.csv") if r["perversions"] != ""]
    passing = min(outputs, key=lambda r: abs(float(r["end_distance"]) - THESIS_DISTANCE))
    steps = int(outputs[-1]["step"])
    rows.append({"time_step": label, "wall_time": summary["wall_time"], "steps": steps,
                 "time_per_step": summary["wall_time"] / steps,
                 **{f"{k}_time": v for k, v in summary["time_split"].items()},
                 "end_distance_near_233": float(passing["end_distance"]),
                 "perversions_near_233": int(passing["perversions"]),
                 "positions_near_233": passing["perversion_positions"],
                 "perversions_90": int(outputs[-1]["perversions"]),
                 "positions_90": outputs[-1]["perversion_positions"]})

with open(out / "bistrip_inertia.csv", "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
print(f"bistrip 30 -> 9 cm with inertia, 40 slabs, {ranks} ranks:")
for r in rows:
    split = ", ".join(f"{k[:-5]} {r[k]:.0f} s" for k in r if k.endswith("_time")
                      and k not in ("wall_time",))
    print(f"  dt {r['time_step']:>6}: {r['wall_time']:7.1f} s, {r['steps']} steps, "
          f"{r['time_per_step']:.3f} s a step ({split}); perversions "
          f"{r['perversions_near_233']} at {r['end_distance_near_233']:.1f} mm "
          f"[{r['positions_near_233']}], {r['perversions_90']} at 90 mm [{r['positions_90']}]")
converged = {(r["perversions_near_233"], r["perversions_90"]) for r in rows}
verdict = "converged" if len(converged) == 1 else "NOT converged"
print(f"the counts are {verdict} in the time step; the goal: a converged count in "
      f"{GOAL:.0f} s: {'met' if len(converged) == 1 and rows[0]['wall_time'] <= GOAL else 'not met'} "
      f"(the 1 ms run took {rows[0]['wall_time']:.0f} s)")
