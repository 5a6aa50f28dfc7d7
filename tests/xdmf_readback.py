"""Read the XDMF/HDF5 output of a block run with h5py and the XML parser (demos/fields.py),
independently of dolfinx, and check its step count, mesh size, fields and the displacement of
the top face; and from steps.csv, the work-energy identity: the top face's work (axial force
and torque) equals the stored energy at every step.

usage: xdmf_readback.py OUTPUT_DIR
"""
import json
import math
import pathlib
import sys

import numpy as np

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import FieldSeries, read_table  # noqa: E402  (demos/fields.py)

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
rows = read_table(out / "steps.csv")
checks.require(f"steps.csv has {len(rows)} rows", len(rows) == summary["steps"])
# The direct solve is one preonly iteration a Newton iteration, the predictor's included (it
# was left out: 2 linear for 3 Newton iterations)
unequal = [r["step"] for r in rows if r["linear_iterations"] != r["newton_iterations"]]
checks.require(f"linear_iterations = newton_iterations at every step of the direct solve "
               f"(not at steps {unequal})", not unequal)
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

# Work and energy: at equilibrium (no dissipation) the stored energy is the work of the top
# face's loads, E(t) = int_0^t (F_z (stretch - 1) H + M_z twist) dt', from the columns
# axial_force, torque and energy (the energy assembled over the cells, the force and moment
# from the reactions: independent computations). The power is smooth in t, so its
# interpolating polynomial through the steps (t = 0 included, P = 0 there) integrates it to
# ~1e-6 (measured 3e-6 at the worst step, where the trapezoidal rule errs by 1e-2): 3e-5,
# ten times that. With the twist's work left out, or taken per degree, it fails by O(1)
t = np.array([0.0] + [float(r["t"]) for r in rows])
power = np.array([0.0] + [float(r["axial_force"]) * (stretch - 1) * H + float(r["torque"]) * twist
                          for r in rows])
energy = np.array([0.0] + [float(r["strain_energy"]) for r in rows])
checks.require(f"{len(rows)} steps, enough to integrate the power (>= 4)", len(rows) >= 4)
antiderivative = np.polyint(np.polyfit(t, power, len(t) - 1))
work = np.polyval(antiderivative, t) - np.polyval(antiderivative, 0.0)
for k in range(1, len(t)):
    checks.relative(f"t = {t[k]:.3f}: the loads' work against the stored energy", work[k],
                    energy[k], 3e-5)
checks.finish()
