"""Read the XDMF/HDF5 output of a block run with h5py and the XML parser (demos/fields.py),
independently of dolfinx, and check its step count, mesh size, fields and the displacement of
the top face.

usage: xdmf_readback.py OUTPUT_DIR
"""
import csv
import json
import math
import pathlib
import sys

import numpy as np

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import FieldSeries  # noqa: E402  (demos/fields.py)

out = pathlib.Path(sys.argv[1])
summary = json.loads((out / "summary.json").read_text())
prm = summary["parameters"]
checks = Checks()

series = FieldSeries(out)
X, cells = series.mesh(-1)
checks.require(f"topology holds {cells.shape[0]} cells of {cells.shape[1]} nodes; summary says "
               f"{summary['num_cells']} tetrahedra",
               cells.shape[0] == summary["num_cells"] and cells.shape[1] == 4)
checks.require(f"geometry holds {X.shape[0]} nodes, topology refers to {int(cells.max()) + 1}",
               X.shape[0] == int(cells.max()) + 1)
times = series.times
checks.require(f"{len(times)} steps in fields.xdmf; summary and steps.csv say "
               f"{summary['steps']}", len(times) == summary["steps"])
with open(out / "steps.csv") as f:
    rows = list(csv.DictReader(f))
checks.require(f"steps.csv has {len(rows)} rows", len(rows) == summary["steps"])
checks.absolute("time of the last step", times[-1], 1.0, 1e-12)
checks.require(f"every step holds the same fields: {series.names(-1)}",
               all(series.names(k) == series.names(-1) for k in range(len(times)))
               and {"displacement", "cauchy_stress_vm", "energy_density"} <= set(series.names(-1)))

# The top face z = H was moved rigidly: u = R(twist) X - X in the plane, u_z = (stretch - 1) H.
# The vertex values are the Dirichlet values up to round-off.
u = series.field("displacement", -1)
H, stretch, twist = prm["height"], prm["stretch"], math.radians(prm["twist"])
top = np.abs(X[:, 2] - H) < 1e-9 * H
c, s = math.cos(twist), math.sin(twist)
expected = np.column_stack([c * X[:, 0] - s * X[:, 1] - X[:, 0],
                            s * X[:, 0] + c * X[:, 1] - X[:, 1],
                            np.full(len(X), (stretch - 1) * H)])
error = np.abs(u[top] - expected[top]).max()
# 1e-10: the values are interpolated from the P2 solution at the vertices, exact up to round-off
checks.absolute(f"max |u - u_prescribed| over the {top.sum()} top nodes at t = 1", error, 0.0,
                1e-10)
bottom = np.abs(X[:, 2]) < 1e-9 * H
checks.absolute("max |u| over the clamped bottom nodes", np.abs(u[bottom]).max(), 0.0, 1e-14)
checks.finish()
