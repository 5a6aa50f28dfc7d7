"""The cost of the tools for instabilities on the column of the buckling scene and on the
snapping shell of the inflation scene, one rank.

- arc-length: `gelx-buckling --ends clamped-clamped` (the straight path with the stability
  eigenvalue, branch switching, the imperfect column), time per arc-length step;
- damped dynamics: `gelx-buckling-dynamics` (the imperfect clamped-clamped column shortened
  past buckling, BDF2), time per accepted time step and for the whole path;
- deflated continuation: `gelx-buckling --ty 1.2 --base sliding --diagram true` (the perfect
  clamped-free column's bifurcation diagram to 1.6 P_cr1), time per diagram point and in all;
- inertia against the eigenvalue: the scene's paths (to d/L = 0.05) with each stability test
  on the straight path (`-straight_arclength_stability`), time per arc-length step.
Load stepping has no path of its own on the column; the snapping shell
(`gelx-inflation-snap`: a Mooney-Rivlin shell inflated past its pressure maximum) times load
stepping, damped dynamics and arc-length on one problem, per path point (load stepping's
points up to where it fails, its failed attempts included). Time a quiet machine.

usage: instabilities.py BUILD OUT     (./gelx bench instabilities)
"""
import json
import pathlib
import subprocess
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)
from studies import MPI_ENV  # noqa: E402  (demos/studies.py)

build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])


def run(program, folder, options, demo="buckling"):
    """Run one program on one rank; its summary.json, its steps.csv rows and the wall time."""
    start = time.perf_counter()
    subprocess.run([str(build / "demos" / demo / program), "--output", str(out / folder)]
                   + options, check=True, stdout=subprocess.DEVNULL, env=MPI_ENV)
    seconds = time.perf_counter() - start
    summary = json.loads((out / folder / "summary.json").read_text())
    rows = read_table(out / folder / "steps.csv")
    return summary, rows, seconds


table = []
s, rows, seconds = run("gelx-buckling", "arclength", ["--ends", "clamped-clamped"])
table.append(("arc-length (clamped-clamped: straight, branch, imperfect)", s["arclength_steps"],
              s["arclength_steps"] * s["time_per_arclength_step"], seconds))
s, rows, seconds = run("gelx-buckling-dynamics", "dynamics", [])
table.append(("damped dynamics (clamped-clamped, imperfect)", s["dynamics"]["steps"],
              s["wall_time"], seconds))
for test in ("eigenvalue", "inertia"):
    s, rows, seconds = run("gelx-buckling", f"straight_{test}",
                           ["--ty", "1.2", "--base", "sliding", "--max_deflection", "0.05",
                            "-straight_arclength_stability", test])
    straight = [r for r in rows if r["path"] == "straight"]
    table.append((f"arc-length, stability by {test} (ty/tx 1.2; {len(straight)} straight)",
                  s["arclength_steps"], s["arclength_steps"] * s["time_per_arclength_step"],
                  seconds))
s, rows, seconds = run("gelx-buckling", "diagram", ["--ty", "1.2", "--base", "sliding",
                                                    "--diagram", "true"])
table.append((f"deflated continuation ({s['diagram_branches']} branches to 1.6 P_cr1)",
              s["diagram_points"], s["diagram_time"], seconds))

s, rows, seconds = run("gelx-inflation-snap", "snap", [], demo="inflation")
for method, name, points in (("load_stepping", "load stepping (the shell, to its maximum)",
                              s["load_stepping"]["steps"]),
                             ("dynamics", "damped dynamics (the shell, through the snap)",
                              s["dynamics"]["steps"]),
                             ("arclength", "arc-length (the shell, through both extrema)",
                              s["arclength"]["steps"])):
    table.append((name, points, points * s[method]["time_per_step"], seconds))

print(f"{'path':62s} {'points':>7s} {'s (path)':>9s} {'s/point':>8s} {'s (run)':>8s}")
for name, points, path_seconds, run_seconds in table:
    print(f"{name:62s} {points:7d} {path_seconds:9.1f} {path_seconds / points:8.3f} "
          f"{run_seconds:8.1f}")
