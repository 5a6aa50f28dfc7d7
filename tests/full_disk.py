"""A disk that fills up in mid-run loses nothing completed and corrupts nothing.

The scene runs three times on a disk that fills up (tests/full_disk.c, preloaded: the
process may write BUDGET bytes in all into the work folder, then every write there fails with
ENOSPC), at budgets of 30, 55 and 80 % of the bytes the same run writes on a roomy disk (run
first, and measured by the same library), so that the disk fills while different files are
written. Each must end with exit code 1 and one line on stderr that names the cause ("No
space left on device"); its steps.csv must hold, as a table that parses, the first rows of
the uninterrupted run, and its fields.xdmf only steps whose data reads back, with those rows'
times; a summary.json, if it fitted, must say "failed". Its newest complete checkpoint,
continued with --restart on a roomy disk, must end as the uninterrupted run did (the same
rows, the quantities to 1e-10: the same operations from the same state, as
tests/restart.py's same-rank restart).

Seen to fail (2026-12-03) on the code before: steps.csv was written through an unchecked
stream and, with the disk full, replaced by a truncated copy; HDF5 printed its 70-line stack.

usage: full_disk.py DISK_LIBRARY WORK_DIR SCENE_BINARY [scene options...]
"""
import json
import os
import pathlib
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import FieldSeries, read_table  # noqa: E402  (demos/fields.py)

library, work, binary = sys.argv[1], pathlib.Path(sys.argv[2]), sys.argv[3]
options = sys.argv[4:]
COLUMNS = ["t", "axial_force", "torque", "strain_energy"]
SAME_RTOL = 1e-10
checks = Checks()
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)


def run(out, budget=None, extra=()):
    """The scene at 1 rank into `out`, on a disk of `budget` bytes (None: roomy); returns the
    completed process and the bytes it wrote into the work folder"""
    report = work / "written.txt"  # a line per process (mpirun's too) of the bytes it wrote
    report.unlink(missing_ok=True)
    env = dict(os.environ, LD_PRELOAD=library, GELX_DISK_FOLDER=str(work),
               GELX_DISK_REPORT=str(report), GELX_DISK_BYTES=str(budget or 10**15))
    p = subprocess.run(["mpirun", "--quiet", "-x", "LD_PRELOAD", "-x", "GELX_DISK_FOLDER",
                        "-x", "GELX_DISK_REPORT", "-x", "GELX_DISK_BYTES", "-np", "1", binary,
                        "--output", str(out), *extra, *options],
                       capture_output=True, text=True, timeout=600, env=env)
    return p, sum(int(line) for line in report.read_text().split())


def rows_of(folder):
    return read_table(folder / "steps.csv")


def table(rows):
    return np.array([[float(r[c]) for c in COLUMNS] for r in rows]).reshape(-1, len(COLUMNS))


reference_run, written = run(work / "roomy")
reference = work / "roomy"
ref_rows = rows_of(reference)
ref_summary = json.loads((reference / "summary.json").read_text())
checks.require(f"the run on a roomy disk completed ({len(ref_rows)} steps, {written} bytes "
               f"written)", reference_run.returncode == 0 and len(ref_rows) >= 5)

for share in (0.30, 0.55, 0.80):
    budget = int(share * written)
    name = f"disk of {budget} bytes ({share:.0%})"
    out = work / f"full_{share:.2f}"
    p, _ = run(out, budget)
    lines = [line for line in p.stderr.splitlines() if line.strip()]
    checks.require(f"{name}: exit code {p.returncode}, stderr {lines!r}: one line naming the "
                   f"full disk", p.returncode == 1 and len(lines) == 1
                   and "No space left on device" in lines[0])

    # What it completed: rows of the uninterrupted run, and field steps that read back
    try:
        rows = rows_of(out)
        kept = table(rows)
    except (OSError, ValueError, KeyError) as e:
        checks.require(f"{name}: steps.csv reads as a table ({e})", False)
        continue
    complete = [int(c.name.split("_")[1]) for c in (out / "checkpoint").glob("step_*")
                if (c / "state.json").is_file()] if (out / "checkpoint").is_dir() else []
    newest = max(complete, default=0)
    same = newest <= len(rows) < len(ref_rows) \
        and np.allclose(kept, table(ref_rows[:len(rows)]), rtol=1e-12, atol=0)
    checks.require(f"{name}: steps.csv holds {len(rows)} rows, the uninterrupted run's first, "
                   f"and at least those of its newest complete checkpoint (step {newest})", same)
    try:
        fields = FieldSeries(out)
        for k in range(len(fields.times)):
            fields.mesh(k)
            fields.field("displacement", k)
        readable = f"{len(fields.times)} steps, each read back"
        times_ok = np.allclose(fields.times, table(ref_rows[:len(fields.times)])[:, 0],
                               rtol=1e-12) and len(fields.times) in (len(rows), len(rows) + 1)
    except (OSError, ValueError, KeyError, AttributeError, ET.ParseError) as e:
        readable, times_ok = f"unreadable ({type(e).__name__}: {e})", False
    checks.require(f"{name}: fields.xdmf: {readable}, at the times of the rows (as many as "
                   f"the rows, or one step ahead of them)", times_ok)
    if (out / "summary.json").is_file():
        status = json.loads((out / "summary.json").read_text())["status"]
        checks.require(f"{name}: summary.json says {status!r}", status.startswith("failed"))
    else:
        print(f"{name}: no summary.json (it did not fit)")

    # Its newest complete checkpoint continues to the uninterrupted run's end
    restarted = work / f"restarted_{share:.2f}"
    shutil.copytree(out, restarted)
    p, _ = run(restarted, extra=["--restart", str(restarted)])
    summary = json.loads((restarted / "summary.json").read_text())
    step = summary.get("restarted_from", {}).get("step", 0)
    checks.require(f"{name}: the restart from its checkpoint of step {step} completed (exit "
                   f"code {p.returncode}, {p.stderr.strip()[-200:]!r})",
                   p.returncode == 0 and summary["status"] == "completed" and step > 0)
    rows = rows_of(restarted)
    checks.require(f"{name}: restarted: {len(rows)} rows (uninterrupted: {len(ref_rows)})",
                   len(rows) == len(ref_rows))
    if len(rows) == len(ref_rows):
        difference = np.abs(table(rows) - table(ref_rows)).max(axis=0)
        scale = np.abs(table(ref_rows)).max(axis=0)
        checks.require(f"{name}: restarted: columns {COLUMNS} differ by at most "
                       f"{(difference / scale).max():.1e} of their largest values (tol "
                       f"{SAME_RTOL:.0e})", np.all(difference <= SAME_RTOL * scale))
    for key in ("axial_force", "torque"):
        checks.relative(f"{name}: restarted: {key}", summary[key], ref_summary[key], SAME_RTOL)
checks.finish()
