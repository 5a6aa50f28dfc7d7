"""A run killed with SIGKILL in the middle of its path keeps every completed step readable.

The scene runs under mpirun; once steps.csv holds KILL_AFTER rows, mpirun and every rank get
SIGKILL (tests/killing.py; no handler can run: what is on disk is all that is left). Then:
- fields.xdmf parses, and every step it names has its mesh and all its fields in HDF5, each
  dataset of the shape the index declares and with finite values (demos/fields.py);
- steps.csv holds whole rows only, as many as fields.xdmf has steps, and the times agree;
- no summary.json claims the run completed.

usage: fault_kill.py RANKS KILL_AFTER TIME_COLUMN OUTPUT_DIR SCENE_BINARY [scene options...]
"""
import json
import math
import pathlib
import shutil
import sys

from checks import Checks
from killing import run_until

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import FieldSeries, read_table  # noqa: E402  (demos/fields.py)

ranks, kill_after, time_column, out = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
command = ["mpirun", "-np", ranks] + sys.argv[5:6] + ["--output", out] + sys.argv[6:]
out = pathlib.Path(out)
shutil.rmtree(out, ignore_errors=True)
checks = Checks()


def rows_written():
    try:
        return len(read_table(out / "steps.csv"))
    except FileNotFoundError:
        return 0


still_running = run_until(command, lambda: rows_written() >= kill_after)
checks.require(f"killed while running, after {rows_written()} rows of steps.csv "
               f"(asked: {kill_after})", still_running and rows_written() >= kill_after)

series = FieldSeries(out)
steps = len(series.times)
finite = True
for k in range(steps):
    x, cells = series.mesh(k)
    finite = finite and all(math.isfinite(v) for v in x.ravel())
    for name in series.names(k):
        values = series.field(name, k)  # raises when a dataset is missing or truncated
        finite = finite and bool((abs(values) < float("inf")).all())
checks.require(f"fields.xdmf: {steps} steps, each with its mesh and fields "
               f"{series.names(-1) if steps else []} complete in HDF5 and finite", finite)

rows = read_table(out / "steps.csv")
whole = all(None not in r.values() and None not in r and len(r) == len(rows[0]) for r in rows)
checks.require(f"steps.csv: {len(rows)} whole rows", whole and len(rows) >= kill_after)
checks.require(f"steps.csv rows ({len(rows)}) = fields.xdmf steps ({steps})", len(rows) == steps)
times = [float(r[time_column]) for r in rows]
checks.require("the steps' times agree: " + ", ".join(f"{t:.4g}" for t in times[:6]) + " ...",
               len(times) == steps and all(abs(a - b) <= 1e-12 * max(1, abs(a))
                                           for a, b in zip(times, series.times)))
summary = out / "summary.json"
status = json.loads(summary.read_text())["status"] if summary.exists() else "no summary"
checks.require(f"no summary claims completion: {status}", status != "completed")
checks.finish()
