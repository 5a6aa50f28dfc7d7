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
- the width grows with the indentation at a slope between 0.7 and 1, with the patch's corner
  located by the level set and by the gap's 3/2 law: below the truncated pyramid's 1 and near
  the thesis' 0.86;
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
checks.newton_tolerance(list(csv.DictReader(open(out / "steps.csv"))))
checks.absolute("largest penetration (um)", s["max_penetration"], 0, 1e-8)
for key in ("slope_lc_vs_d", "slope_lc_vs_d_gap_law"):
    checks.require(f"{key}: slope of l_c/L against d/H {s[key]:.4f} in (0.7, 1)",
                   0.7 < s[key] < 1.0)

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
H = p["L"] / math.sqrt(2)
touching = status > 0.5
last_row = list(csv.DictReader(open(out / "steps.csv")))[-1]
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
