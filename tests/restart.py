"""A run killed with SIGKILL in mid-path and continued with --restart ends as the uninterrupted
run ended: the same quantities, the same rows of steps.csv, one fields.xdmf step per row with
the same final displacement, and no step lost or written twice.

The scene runs under mpirun at the reference run's rank count; once steps.csv holds KILL_AFTER
rows mpirun and every rank get SIGKILL (tests/killing.py). Two copies of what it left are then continued with
`--restart DIR` alone: one at the same rank count, which must reproduce the reference to
1e-10 (the same partition and the same operations from the same state: the reference's path
from the checkpoint on, up to the round-off of a different order of MPI messages), and one at
OTHER_RANKS, whose partition numbers the unknowns differently, within OTHER_RTOL (the Newton
tolerances; see tests/CMakeLists.txt). Also: a restart may not change a scene parameter, and
a folder without a checkpoint cannot be restarted; a row cut short by a kill (its newline not
written) is not read as a row, and a restart drops it.

usage: restart.py REFERENCE_DIR KILL_AFTER OTHER_RANKS OTHER_RTOL QUANTITIES COLUMNS WORK_DIR
                  SCENE_BINARY [scene options...]
QUANTITIES and COLUMNS: comma-separated keys of summary.json and columns of steps.csv to compare;
the first of COLUMNS is the path's time (strictly increasing along steps.csv).
"""
import json
import pathlib
import shutil
import subprocess
import sys
import time

import numpy as np

from checks import Checks
from killing import run_until

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import FieldSeries, read_table  # noqa: E402  (demos/fields.py)

reference = pathlib.Path(sys.argv[1])
kill_after, other_ranks, other_rtol = int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
quantities, columns = sys.argv[5].split(","), sys.argv[6].split(",")
work, binary, options = pathlib.Path(sys.argv[7]), sys.argv[8], sys.argv[9:]
RUN_PARAMETERS = {"output", "restart", "checkpoint_every"}  # not the scene's
SAME_RTOL = 1e-10
checks = Checks()
ref_summary = json.loads((reference / "summary.json").read_text())
ranks = ref_summary["mpi_ranks"]


def mpirun(ranks, args):
    return ["mpirun", "-np", str(ranks), binary] + args


def rows_of(folder):
    return read_table(folder / "steps.csv")


def number(text):
    """A cell of steps.csv as a number (a flag as 0 or 1)."""
    return {"false": 0.0, "true": 1.0}.get(text) if text in ("false", "true") else float(text)


def rows_written(folder):
    try:
        return len(read_table(folder / "steps.csv"))
    except FileNotFoundError:
        return 0


def per_step_files(folder):
    """The per-step files (step_<k>.*) outside fields/ and checkpoint/, relative to folder."""
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("step_*")
                  if p.is_file() and p.relative_to(folder).parts[0] not in ("fields", "checkpoint"))


def by_position(x, values):
    """Nodes sorted by their coordinates (rounded to 1e-9 of the extent), and their values:
    the nodes of another partition in the same order."""
    key = np.round(x / (1e-9 * np.abs(x).max())).astype(np.int64)
    order = np.lexsort(key.T[::-1])
    return x[order], values[order]


# 1. Kill a run in mid-path
killed = work / "killed"
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
start = time.monotonic()
still_running = run_until(mpirun(ranks, ["--output", str(killed)] + options),
                          lambda: rows_written(killed) >= kill_after)
print(f"killed run: {time.monotonic() - start:.1f} s")
checks.require(f"killed at {ranks} ranks while running, after {rows_written(killed)} rows of "
               f"steps.csv (asked: {kill_after}; the reference has {len(rows_of(reference))})",
               still_running and rows_written(killed) >= kill_after)
# A kill in the middle of an append leaves a row without its newline (tables grow by
# appending): readers skip it, and the restarts below drop it with the rows past the checkpoint
whole = rows_written(killed)
with open(killed / "steps.csv", "a") as f:
    f.write((killed / "steps.csv").read_text().splitlines()[-1][:20])
checks.require(f"a row cut short at its 20th byte is not read: {rows_written(killed)} rows "
               f"(before it: {whole})", rows_written(killed) == whole)

# 2. What a restart refuses: a folder with no checkpoint, a changed scene parameter (the first
#    number among them, doubled)
changed = next(name for name, value in ref_summary["parameters"].items()
               if name not in RUN_PARAMETERS and isinstance(value, (int, float))
               and not isinstance(value, bool) and value != 0)
for what, args, expect in [
        ("no checkpoint", ["--restart", str(work / "no-such-run")], "no complete checkpoint"),
        (f"--{changed} changed", ["--restart", str(killed), f"--{changed}",
                                  str(2 * ref_summary["parameters"][changed])],
         f"--{changed} may not be changed")]:
    p = subprocess.run([binary] + args, capture_output=True, text=True)
    lines = p.stderr.splitlines()
    checks.require(f"restart with {what}: exit code {p.returncode}, stderr {lines!r}",
                   p.returncode == 1 and len(lines) == 1 and expect in lines[0])

# 3. Continue copies of it at the same and at another rank count, and compare
ref_rows, ref_fields = rows_of(reference), FieldSeries(reference)
for restart_ranks, rtol in [(ranks, SAME_RTOL), (other_ranks, other_rtol)]:
    name = f"np{ranks}_restarted_np{restart_ranks}"
    out = work / name
    shutil.copytree(killed, out)
    start = time.monotonic()
    p = subprocess.run(mpirun(restart_ranks, ["--restart", str(out)]), capture_output=True,
                       text=True)
    print(f"{name}: restart ran {time.monotonic() - start:.1f} s")
    summary = json.loads((out / "summary.json").read_text())
    restarted = summary.get("restarted_from", {}).get("step", 0)
    checks.require(f"{name}: exit code {p.returncode}, status {summary['status']!r}, "
                   f"{summary['mpi_ranks']} ranks, continued from step {restarted} of "
                   f"{len(ref_rows)}", p.returncode == 0 and summary["status"] == "completed"
                   and summary["mpi_ranks"] == restart_ranks and 0 < restarted < len(ref_rows))
    scene_parameters = {k: v for k, v in summary["parameters"].items() if k not in RUN_PARAMETERS}
    checks.require(f"{name}: the scene parameters are the reference's",
                   scene_parameters == {k: v for k, v in ref_summary["parameters"].items()
                                        if k not in RUN_PARAMETERS})
    for key in quantities:
        checks.relative(f"{name}: {key}", summary[key], ref_summary[key], rtol)

    # steps.csv: the rows up to the checkpoint are the killed run's, byte for byte (wall
    # times included, which no second computation reproduces): the restart did not recompute
    # them
    # (two lines above them: the units and the header)
    kept = (out / "steps.csv").read_text().splitlines()[:restarted + 2]
    checks.require(f"{name}: the {restarted} rows up to the checkpoint are the killed run's, "
                   "byte for byte", kept == (killed / "steps.csv").read_text().splitlines()
                   [:restarted + 2] and len(kept) == restarted + 2)

    # steps.csv: the reference's rows, each once, in order
    rows = rows_of(out)
    times = [float(r[columns[0]]) for r in rows]
    checks.require(f"{name}: steps.csv has {len(rows)} rows (reference {len(ref_rows)}), "
                   f"{columns[0]} strictly increasing",
                   len(rows) == len(ref_rows) and all(a < b for a, b in zip(times, times[1:])))
    if "step" in rows[0]:
        checks.require(f"{name}: steps.csv numbers its steps 1..{len(rows)}",
                       [int(r["step"]) for r in rows] == list(range(1, len(rows) + 1)))
    for column in columns:
        a = np.array([number(r[column]) for r in rows[:len(ref_rows)]])
        b = np.array([number(r[column]) for r in ref_rows[:len(rows)]])
        scale = np.abs(b).max()
        checks.require(f"{name}: steps.csv {column}: max difference {np.abs(a - b).max():.2e} "
                       f"(tol {rtol:.0e} x the column's largest value {scale:.4g})",
                       len(a) == len(b) and np.abs(a - b).max() <= rtol * scale)

    # fields.xdmf: one step per row, at the reference's times, with its displacements
    fields = FieldSeries(out)
    steps = len(fields.times)
    error = np.abs(np.array(fields.times) - np.array(ref_fields.times)).max() \
        if steps == len(ref_fields.times) else np.inf
    checks.require(f"{name}: fields.xdmf has {steps} steps (rows {len(rows)}), times "
                   f"differ from the reference's by {error:.2e}",
                   steps == len(rows) and error <= rtol * max(map(abs, fields.times)))
    same_nodes, difference, largest = True, 0.0, 0.0
    for k in range(min(steps, len(ref_fields.times))):
        x, u = by_position(fields.mesh(k)[0], fields.field("displacement", k))
        x_ref, u_ref = by_position(ref_fields.mesh(k)[0], ref_fields.field("displacement", k))
        same_nodes = same_nodes and x.shape == x_ref.shape \
            and np.abs(x - x_ref).max() <= 1e-9 * np.abs(x_ref).max()
        difference = max(difference, np.abs(u - u_ref).max() if same_nodes else np.inf)
        largest = max(largest, np.abs(u_ref).max())
    checks.require(f"{name}: displacement of every step at the reference's nodes: max difference "
                   f"{difference:.2e} (tol {rtol:.0e} x the largest |u| {largest:.4g})",
                   same_nodes and difference <= rtol * largest)
    meshes = sorted(p.name for p in (out / "fields").glob("mesh_*.h5"))
    checks.require(f"{name}: mesh files {meshes}: the killed run's and the restart's, which "
                   f"starts at step {restarted + 1}",
                   meshes == ["mesh_000001.h5", f"mesh_{restarted + 1:06d}.h5"])
    step_files = per_step_files(out)
    checks.require(f"{name}: {len(step_files)} per-step files, the reference's",
                   step_files == per_step_files(reference))
    kept = sorted(p.name for p in (out / "checkpoint").iterdir())
    checks.require(f"{name}: checkpoints kept: {kept}", kept == [
        f"step_{k:06d}" for k in (len(rows) - 1, len(rows))])
checks.finish()
