"""Read the XDMF/HDF5 output of a block run with h5py and the XML parser, independently of
dolfinx, and check its step count, mesh size and the displacement of the top face.

usage: xdmf_readback.py OUTPUT_DIR
"""
import csv
import json
import math
import pathlib
import sys

import numpy as np

from checks import Checks
from xdmf_fields import XdmfOutput

out = pathlib.Path(sys.argv[1])
summary = json.loads((out / "summary.json").read_text())
prm = summary["parameters"]
checks = Checks()

xdmf = XdmfOutput(out)
cells_dims = xdmf.mesh_grid.find("Topology/DataItem").get("Dimensions").split()
checks.require(f"topology holds {cells_dims[0]} cells of {cells_dims[1]} nodes; summary says "
               f"{summary['num_cells']} tetrahedra",
               int(cells_dims[0]) == summary["num_cells"] and int(cells_dims[1]) == 4)

steps = xdmf.steps("displacement")
times = [float(g.find("Time").get("Value")) for g in steps]
checks.require(f"{len(steps)} displacement steps in fields.xdmf; summary and steps.csv say "
               f"{summary['steps']}", len(steps) == summary["steps"])
with open(out / "steps.csv") as f:
    rows = list(csv.DictReader(f))
checks.require(f"steps.csv has {len(rows)} rows", len(rows) == summary["steps"])
checks.absolute("time of the last step", times[-1], 1.0, 1e-12)

# The top face z = H was moved rigidly: u = R(twist) X - X in the plane, u_z = (stretch - 1) H.
# The vertex values are the Dirichlet values up to round-off.
X = xdmf.geometry()
highest_node = int(xdmf.topology().max())
checks.require(f"geometry holds {X.shape[0]} nodes, topology refers to {highest_node + 1}",
               X.shape[0] == highest_node + 1)
_, u = xdmf.field("displacement")
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
