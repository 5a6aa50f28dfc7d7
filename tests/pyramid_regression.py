"""Check a short pyramid run (demos/pyramid, coarse mesh, d/H up to 0.3) against stored values
(tests/pyramid_reference.json, from a run of the same options, per element order; the apex
physics that any mesh must show is checked independently by pyramid_apex.py) and the contact's
invariants.

- the stored force, contact width, area ratio and fitted slope within 1e-6 relative: every step
  converges Newton to |R| <= 1e-10 |R0| with a direct solver, so reruns and other rank counts
  differ by round-off (measured below 1e-9), while a change of the physics, the mesh or the
  contact method moves them by far more;
- no node behind the substrate (an exact active set: 0 up to the 1e-10 release band of
  RigidPlaneContact);
- the width grows with the indentation at a slope within 8 % of the mesh-converged 0.8793
  (README), with the patch's corner located by the level set and by the gap's 3/2 law (these
  coarse meshes differ from it by 1.1 to 7.0 %); the force at d/H = 0.3 within 6 % (Q1-P0) and
  3.5 % (Q2-Q1) of the mesh-converged 5.00 uN, these meshes' measured errors being 4.5 % and
  2.1 %;
- the work-energy identity: the stored energy (the assembled Lagrangian) equals the substrate's
  work int f dd, integrated here from the steps' forces, at every step;
- the STL surface of the last step: the deformed pyramid's top lies on the substrate,
  z = t + H - d (to float32 round-off: STL stores single precision), and every triangle faces
  up, out of the body (the lateral faces' outward normals have n_z > 0 and keep it in contact).
- the contact fields of fields.xdmf at the last step, against the displacement field: the
  nodes with contact_status 1 lie on the substrate (x_z = X_z + u_z to 1e-9 H) with zero gap
  and compressive force (with Q1, whose candidates are all vertices, as many as steps.csv's
  active_nodes); every other candidate's contact_gap is the distance z_substrate - x_z to the
  substrate, to 1e-9 H (the gap is computed by the contact code, x from the output
  displacement).

usage: pyramid_regression.py OUTPUT_DIR
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
s = json.loads((out / "summary.json").read_text())
p = s["parameters"]
stored = json.loads((pathlib.Path(__file__).parent / "pyramid_reference.json").read_text())
reference = stored[f"order{p['order']}"]
checks = Checks()
checks.require(f"the run's options are those of the stored values {reference['options']}",
               all(p[k] == v for k, v in reference["options"].items()))
checks.require(f"run {s['status']} to d/H = {s['final_d_over_H']}",
               s["status"] == "completed" and abs(s["final_d_over_H"] - 0.3) < 1e-12)
for key in reference:
    if key != "options":
        checks.relative(f"{key} against the stored value", s[key], reference[key], 1e-6)
rows = read_table(out / "steps.csv")
checks.newton_tolerance(rows)
checks.absolute("largest penetration (um)", s["max_penetration"], 0, 1e-8)
# The slopes against the mesh-converged 0.8793 (README "Work precision", fit to d/H = 0.8):
# these coarse meshes' slopes differ from it by 1.1 % to 7.0 % (measured, both orders, both
# corner estimators, the extrapolated one included), so 8 %
for key in ("slope_lc_vs_d", "slope_lc_vs_d_gap_law"):
    checks.relative(f"{key}: slope of l_c/L against d/H, against the converged 0.8793", s[key],
                    0.8793, 0.08)
# The force at d/H = 0.3 against the mesh-converged 5.00 uN (README "The force"): Q1-P0 on 1-5
# cells (5.759, 5.215, 5.101, 5.059, 5.043) extrapolates to 4.994-5.027 by three-level fits, and
# Q2-Q1 on 2 cells gives 4.979, so the limit is known to 0.6 %; these coarse meshes are 4.5 %
# (Q1-P0, 2 cells) and 2.1 % (Q2-Q1, 1 cell) above it: windows of 6 % and 3.5 %. A force of the
# quarter model, not the whole pyramid's, or with G off by 10 %, fails them
FORCE_WINDOW = {1: 0.06, 2: 0.035}
checks.relative("force at d/H = 0.3 (uN) against the converged 5.00", s["final_force"], 5.00,
                FORCE_WINDOW[p["order"]])

# Work and energy: frictionless contact with an exact active set dissipates nothing, so the
# stored energy (steps.csv strain_energy, the assembled Lagrangian whose derivative the
# residual is) equals the substrate's work int f dd (f from the contact forces) at every step.
# The work is integrated here from the steps' forces (f(0) = 0 at first touch) by local
# cubics through the four nearest steps, exact for a cubic; f(d) ~ d^2 is smooth between the
# nodes' arrivals in the patch, which kink it, and the quadrature errs there (measured: up to
# 9e-3 of the energy at that step, 9.6e-5 of the final energy with Q2-Q1 and 2.2e-4 with
# Q1-P0, whose patch gains more nodes per step; 4.5e-7 at the last step, Q2-Q1): 5e-4 of the
# final energy at every step. The work of a force off by 1 % fails it at 22 of 36 steps
H = p["L"] / math.sqrt(2)
d = np.array([0.0] + [float(r["d_over_H"]) * H for r in rows])
f = np.array([0.0] + [float(r["force"]) for r in rows])
energy = np.array([0.0] + [float(r["strain_energy"]) for r in rows])
work = np.zeros_like(d)
for k in range(len(d) - 1):
    near = np.unique(np.clip(np.arange(k - 1, k + 3), 0, len(d) - 1))
    cubic = np.polyint(np.polyfit(d[near], f[near], len(near) - 1))
    work[k + 1] = work[k] + np.polyval(cubic, d[k + 1]) - np.polyval(cubic, d[k])
for k in range(1, len(d)):
    checks.absolute(f"d/H = {d[k] / H:.3f}: (the substrate's work int f dd - the stored energy) "
                    f"/ the final energy", (work[k] - energy[k]) / energy[-1], 0.0, 5e-4)

stl = sorted((out / "surface").glob("step_*.stl"))[-1].read_bytes()
count = int(np.frombuffer(stl[80:84], "<u4")[0])
records = np.frombuffer(stl[84:], np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)),
                                            ("attributes", "<u2")]))
vertices = records["vertices"].astype(float)
normals = np.cross(vertices[:, 1] - vertices[:, 0], vertices[:, 2] - vertices[:, 0])
substrate = p["t"] + p["L"] / math.sqrt(2) * (1 - s["final_d_over_H"])
checks.require(f"STL holds {count} triangles", count == len(records) and count > 0)
checks.relative("STL: highest point against the substrate z = t + H - d", vertices[:, :, 2].max(),
                substrate, 1e-6)
checks.require(f"STL: triangles facing down: {(normals[:, 2] <= 0).sum()}",
               (normals[:, 2] > 0).all())

series = FieldSeries(out)
X, _ = series.mesh(-1)
z = X[:, 2] + series.field("displacement", -1)[:, 2]
status, gap, force = (series.field(f"contact_{name}", -1).ravel()
                      for name in ("status", "gap", "force"))
touching = status > 0.5
last_row = rows[-1]
# 1e-12: the output interpolates the vertex values into the output space, exact to round-off
checks.require(f"contact_status is 0 or 1 (to 1e-12) at every node, 1 at {touching.sum()} nodes",
               np.all(np.minimum(np.abs(status), np.abs(status - 1)) < 1e-12)
               and touching.sum() > 0)
if p["order"] == 1:
    checks.require(f"nodes in contact: {touching.sum()}, steps.csv says {last_row['active_nodes']}",
                   touching.sum() == int(last_row["active_nodes"]))
checks.absolute("largest |x_z - z_substrate| / H over the nodes in contact",
                np.abs(z[touching] - substrate).max() / H, 0, 1e-9)
checks.absolute("largest |contact_gap| / H over the nodes in contact", np.abs(gap[touching]).max() / H,
                0, 1e-9)
checks.require(f"contact_force >= 0 in contact (smallest {force[touching].min():.3g})",
               force[touching].min() >= 0)
free = ~touching & (np.abs(gap) > 1e-12 * H)
checks.absolute(f"largest |contact_gap - (z_substrate - x_z)| / H over {free.sum()} free candidates",
                np.abs(gap[free] - (substrate - z[free])).max() / H, 0, 1e-9)
checks.finish()
