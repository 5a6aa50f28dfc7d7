"""A run's scene.txt replays it to the last digit: run a scene with non-default parameters and
PETSc options, run it again from nothing but the first run's scene.txt (--scene), and require
every number of steps.csv and summary.json to be the same string, wall-clock times (elapsed)
and memory aside (same binary, options and one rank: the same floating-point operations; at several ranks
the order of MPI reductions varies from run to run). The file must name
every parameter that --help lists (but --output and --restart, which say where a run goes).
A control run from the same file with one parameter changed after it on the command line
must differ: the comparison can fail, and the command line overrides the file.

usage: replay.py MPIEXEC RANKS EXE OUT_DIR CHANGE_NAME CHANGE_VALUE [scene options...]
"""
import csv
import json
import pathlib
import re
import subprocess
import sys

from checks import Checks

mpiexec, ranks, exe, out, change_name, change_value = sys.argv[1:7]
options = sys.argv[7:]
out = pathlib.Path(out)
checks = Checks()
TIMES = re.compile(r"(^|_)(wall_time|time|timing|memory|elapsed)($|_)")


def run(name, *args):
    folder = out / name
    p = subprocess.run([mpiexec, "-np", ranks, exe, "--output", str(folder), *args],
                       capture_output=True, text=True)
    checks.require(f"{name}: exit code {p.returncode}", p.returncode == 0)
    if p.returncode != 0:
        print(p.stderr[-2000:])
        checks.finish()
    return folder


def numbers(folder):
    """Every value of steps.csv and summary.json but times, memory and the output folder"""
    with open(folder / "steps.csv") as f:
        rows = [{k: v for k, v in r.items() if not TIMES.search(k)} for r in csv.DictReader(f)]
    summary = json.loads((folder / "summary.json").read_text())

    def strip(d):
        return {k: strip(v) if isinstance(v, dict) else v for k, v in d.items()
                if not TIMES.search(k) and k != "output"}
    return rows, strip(summary)


first = run("first", *options)
scene = (first / "scene.txt").read_text()
print(scene)
listed = set(re.findall(r"^(\w+) = ", scene, re.M))
help_text = subprocess.run([exe, "--help"], capture_output=True, text=True).stdout
declared = set(re.findall(r"^\s+--(\w+)", help_text, re.M)) - {"output", "restart"}
checks.require(f"scene.txt sets all {len(declared)} parameters of --help but output and "
               f"restart (missing: {sorted(declared - listed)}, extra: {sorted(listed - declared)})",
               listed == declared)
petsc = [o for o in options if o.startswith("-") and not o.startswith("--")]
checks.require(f"scene.txt holds the PETSc options given {petsc}",
               all(re.search(rf"^{re.escape(o)}\b", scene, re.M) for o in petsc))
replay = run("replay", "--scene", str(first / "scene.txt"))
rows, summary = numbers(first)
replay_rows, replay_summary = numbers(replay)
checks.require(f"replay: steps.csv's {len(rows)} rows, every column but times, are the same "
               f"strings", rows == replay_rows and len(rows) > 0)
differing = sorted(k for k in summary if summary[k] != replay_summary.get(k))
checks.require(f"replay: summary.json is the same but for times (differing: {differing})",
               not differing)
control = run("control", "--scene", str(first / "scene.txt"), f"--{change_name}", change_value)
control_rows, control_summary = numbers(control)
checks.require(f"control with --{change_name} {change_value} after the file: steps.csv differs",
               control_rows != rows)
checks.require(f"control: summary.json's parameters say {change_name} = "
               f"{control_summary['parameters'][change_name]}",
               str(control_summary["parameters"][change_name]) == change_value)
checks.finish()
