"""Open a run's fields.xdmf with ParaView itself (pvbatch, tests/paraview_probe.py) and check
that it is what a user should see: ONE unstructured grid (not a multiblock of copies) with the
mesh's node and cell counts, exactly the arrays the scene promises, each with its centring and
components, and every time step, each array's values at the first and last step equal to
the HDF5 data read independently with h5py (demos/fields.py), and their values at the nodes and
cells ParaView names by coordinates (the least and greatest x + 2y + 3z) equal the HDF5 values at
the node or cell of those coordinates. Fails when pvbatch is missing.

usage: paraview_dataset.py OUTPUT_DIR [--file fields.xdmf] [--steps-csv] ARRAY...
  ARRAY   an array the scene writes; NAME_* stands for the outputs of a stress tensor: NAME
          itself (nine components, which ParaView must take as a tensor, equal to the six
          component arrays) and NAME_xx, _yy, _zz, _yz, _xz, _xy, von Mises _vm and pressure _p
  --steps-csv   the time steps are the rows of the folder's steps.csv (one field step per row)
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys

import numpy as np

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import FieldSeries, read_table  # noqa: E402  (demos/fields.py)

TENSOR_OUTPUTS = ["xx", "yy", "zz", "yz", "xz", "xy", "vm", "p"]

cli = argparse.ArgumentParser()
cli.add_argument("output", type=pathlib.Path)
cli.add_argument("arrays", nargs="+")
cli.add_argument("--file", default="fields.xdmf")
cli.add_argument("--steps-csv", action="store_true")
args = cli.parse_args()
tensors = [a[:-2] for a in args.arrays if a.endswith("_*")]
expected = [f"{t}_{c}" for t in tensors for c in TENSOR_OUTPUTS] + tensors \
    + [a for a in args.arrays if not a.endswith("_*")]
checks = Checks()

pvbatch = shutil.which("pvbatch")
if pvbatch is None:
    checks.require("ParaView's pvbatch is installed (tools/install-deps installs paraview)", False)
    checks.finish()
xdmf = args.output / args.file
run = subprocess.run([pvbatch, str(pathlib.Path(__file__).with_name("paraview_probe.py")),
                      str(xdmf)], capture_output=True, text=True, timeout=300)
lines = [line for line in run.stdout.splitlines() if line.startswith("PROBE ")]
checks.require(f"pvbatch read {xdmf} (exit code {run.returncode})",
               run.returncode == 0 and len(lines) == 1)
if not lines:
    print(run.stdout[-2000:], run.stderr[-2000:])
    checks.finish()
probe = json.loads(lines[0][len("PROBE "):])

series = FieldSeries(xdmf.parent)
x, cells = series.mesh(-1)
print(f"ParaView's reader: {probe['reader']}")
checks.require(f"ParaView's time steps {len(probe['times'])} equal the index's {len(series.times)}"
               f" to the last digit", probe["times"] == series.times)
if args.steps_csv:
    rows = read_table(args.output / "steps.csv")
    checks.require(f"one time step per row of steps.csv ({len(rows)})",
                   len(probe["times"]) == len(rows))
for label, step in (("first", 0), ("last", -1)):
    seen = probe["steps"][label]
    checks.require(f"{label} step: one data set, a {seen['class']}",
                   seen["class"] == "vtkUnstructuredGrid")
    if seen["class"] != "vtkUnstructuredGrid":
        continue
    checks.require(f"{label} step: {seen['points']} points and {seen['cells']} cells, the mesh "
                   f"has {len(x)} nodes and {len(cells)} cells",
                   (seen["points"], seen["cells"]) == (len(x), len(cells)))
    checks.require(f"{label} step: arrays {sorted(seen['arrays'])} are exactly {sorted(expected)}",
                   sorted(seen["arrays"]) == sorted(expected))
    checks.require(f"{label} step: ParaView takes {seen['tensors']} as tensors, the scene "
                   f"writes {tensors}", sorted(seen["tensors"]) == sorted(tensors))
    for tensor in tensors:
        # the tensor row by row: xx xy xz / yx yy yz / zx zy zz
        whole = series.field(tensor, step).reshape(-1, 9)
        for c, k in zip(TENSOR_OUTPUTS, (0, 4, 8, 5, 2, 1)):
            checks.absolute(f"{label} step: {tensor}'s component {k} against {tensor}_{c}",
                            np.abs(whole[:, k] - series.field(f"{tensor}_{c}", step).ravel()).max(),
                            0.0, 0.0)
    for name in sorted(set(expected) & set(seen["arrays"])):
        values = series.field(name, step)
        values = values.reshape(len(values), -1)
        a = seen["arrays"][name]
        checks.require(f"{label} step: {name} is {a['components']}-component at each "
                       f"{a['centre']}, as stored ({values.shape[1]} per {series.centre(name, step)})",
                       (a["components"], a["centre"]) == (values.shape[1], series.centre(name, step)))
        # Both sides read the same float64 data: equal to round-off of the min/max reduction
        scale = max(np.abs(values).max(), 1e-300)
        deviation = max(np.abs(np.array(a["min"]) - values.min(axis=0)).max(),
                        np.abs(np.array(a["max"]) - values.max(axis=0)).max())
        checks.absolute(f"{label} step: {name}'s range in ParaView against h5py, over its scale "
                        f"{scale:.3g}", deviation / scale, 0.0, 1e-14)
    # Values where they belong: at the nodes and cells ParaView names by their coordinates,
    # the HDF5 data's at the node or cell found here by the same coordinates (a reader that
    # permuted the nodes or the cells, or mixed up components, keeps the ranges but fails)
    centroids = x[cells].mean(axis=1)
    for place, seen_at in sorted(seen["named"].items()):
        where = place.split()[0]
        candidates = x if where == "Node" else centroids
        index = int(np.argmin(np.linalg.norm(candidates - seen_at["xyz"], axis=1)))
        distance = np.linalg.norm(candidates[index] - seen_at["xyz"])
        # ParaView's reader keeps the points in single precision: 1e-6 of the mesh's size
        # (measured 1.2e-8 on the block's cells), far below any node spacing
        size = np.ptp(x, axis=0).max()
        checks.absolute(f"{label} step: the {place} {where.lower()} at {np.round(seen_at['xyz'], 4)}"
                        f" is one of the mesh's, over its size", distance / size, 0.0, 1e-6)
        for name in sorted(set(expected) & set(seen_at["values"])):
            if series.centre(name, step) != where:
                continue
            values = series.field(name, step)
            stored = values.reshape(len(values), -1)[index]
            error = np.abs(np.array(seen_at["values"][name]) - stored).max()
            scale = max(np.abs(values).max(), 1e-300)
            checks.absolute(f"{label} step: {name} at the {place} {where.lower()} in ParaView "
                            f"against h5py, over its scale", error / scale, 0.0, 1e-14)
checks.finish()
