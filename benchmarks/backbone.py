"""The solver backbone against the code before it, side by side in one run.

The scenes' paths were rebuilt on PETSc SNES (NewtonSolver), explicit path states and
composable systems. This builds the last commit before that (BASELINE) in a folder of its own,
runs every FEM scene with the same scene options on both builds, alternating old and new, and
prints per scene the steps, the Newton iterations per step and the wall time of each, with
the new/old ratios. The goal: no scene more than 10 % slower, none with more Newton iterations
per step. Time a quiet machine: both cores are used (2 ranks).

usage: backbone.py BUILD OUT     (./gelx bench backbone)
"""
import json
import pathlib
import subprocess
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)
from studies import MPI_ENV  # noqa: E402  (demos/studies.py)

BASELINE = "1930b15"  # the last commit before the SNES backbone
ROOT = pathlib.Path(__file__).resolve().parents[1]
# scene: (options for both, options only the old code knew), the scenes' defaults otherwise
CASES = {
    "block": ([], ["-newton_monitor", "0"]),
    "pyramid": (["--cells", "3", "--d_max", "0.5", "--extrapolate", "false"],
                ["-newton_monitor", "0"]),
    "inflation": ([], ["-newton_monitor", "0", "-arclength_monitor", "0"]),
    "buckling": ([], []),
    "fiber_gel": ([], ["-newton_monitor", "0"]),
}
# Newton iterations per row: `newton_iterations`, named `iterations` in the paths' rows of a
# baseline from before 2026-12-04
ITERATIONS = ("newton_iterations", "iterations")
REPEATS = 2


def baseline_build(out):
    """Check out BASELINE beside the repository and build the scenes there."""
    source, build = out / "baseline-source", out / "baseline-build"
    if not source.exists():
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(source),
                        BASELINE], check=True)
    subprocess.run(["cmake", "-S", str(source), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                    "-DGELX_PYTHON=/usr/bin/python3"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", str(build), "-j2", "--target"]
                   + [f"gelx-{scene}" for scene in CASES], check=True, stdout=subprocess.DEVNULL)
    return build


def run(build, scene, folder, options):
    """Wall time of one run on 2 ranks, its steps and its Newton iterations."""
    exe = build / "demos" / scene / f"gelx-{scene}"
    start = time.perf_counter()
    subprocess.run(["mpirun", "-np", "2", str(exe), "--output", str(folder)] + options,
                   check=True, stdout=subprocess.DEVNULL, env=MPI_ENV)
    seconds = time.perf_counter() - start
    status = json.loads((folder / "summary.json").read_text())["status"]
    rows = read_table(folder / "steps.csv")
    iterations = sum(int(next(r[k] for k in ITERATIONS if k in r)) for r in rows)
    return {"seconds": seconds, "steps": len(rows), "iterations": iterations, "status": status}


def main():
    build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    builds = {"old": baseline_build(out), "new": build}
    rows = []
    for scene, (common, old_only) in CASES.items():
        best = {}
        for repeat in range(REPEATS):
            for code in ("old", "new"):
                options = common + (old_only if code == "old" else [])
                r = run(builds[code], scene, out / f"{scene}-{code}", options)
                if code not in best or r["seconds"] < best[code]["seconds"]:
                    best[code] = r
        rows.append((scene, best["old"], best["new"]))
    lines = ["| scene | steps old / new | Newton its per step old / new | wall s old / new "
             "(best of %d) | time new/old |" % REPEATS, "| --- | --- | --- | --- | --- |"]
    for scene, old, new in rows:
        lines.append(f"| {scene} | {old['steps']} / {new['steps']} | "
                     f"{old['iterations'] / old['steps']:.2f} / "
                     f"{new['iterations'] / new['steps']:.2f} | "
                     f"{old['seconds']:.1f} / {new['seconds']:.1f} | "
                     f"{new['seconds'] / old['seconds']:.2f} |")
        for code, r in (("old", old), ("new", new)):
            if r["status"] != "completed":
                lines.append(f"|  | {code}: {r['status']} | | | |")
    table = "\n".join(lines)
    print(table)
    (out / "table.md").write_text(table + "\n")


if __name__ == "__main__":
    main()
