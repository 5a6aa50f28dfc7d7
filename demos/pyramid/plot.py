"""Plots of a pyramid run (thesis Figs. 2.3b, 2.4a, 2.7a): pyramid.png and patch.png.

usage: plot.py OUTPUT_DIR
"""
import json
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as tri  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from fields import read_table  # noqa: E402  (demos/fields.py)

out = pathlib.Path(sys.argv[1])
s = json.loads((out / "summary.json").read_text())
rows = read_table(out / "steps.csv")
d = np.array([float(r["d_over_H"]) for r in rows])
lc = np.array([float(r["contact_width_over_L"]) for r in rows])
f = np.array([float(r["force"]) for r in rows])
G = s["parameters"]["G"]

fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
lc_gap_law = np.array([float(r["contact_width_over_L_gap_law"]) for r in rows])
left.plot(d, lc, "o", ms=4, label="gelx, corner by the level set")
limit = s.get("slope_lc_vs_d_extrapolated")
limit_text = (f" (mesh limit {limit:.3f})" if limit is not None and np.isfinite(limit) else "")
# The fits need the contact to have grown over a few steps: a short or stopped run has none
if "slope_lc_vs_d" in s:
    left.plot(d, s["slope_lc_vs_d"] * d + s["intercept_lc_vs_d"], "k-",
              label=f"fit: slope {s['slope_lc_vs_d']:.3f}{limit_text}, "
                    f"R² {s['r2_lc_vs_d']:.4f}")
left.plot(d, lc_gap_law, "s", ms=4, mfc="none", label="gelx, corner by the gap's 3/2 law")
if "slope_lc_vs_d_gap_law" in s:
    left.plot(d, s["slope_lc_vs_d_gap_law"] * d + s["intercept_lc_vs_d_gap_law"], "b-",
              label=f"fit: slope {s['slope_lc_vs_d_gap_law']:.3f}")
left.plot(d, 0.86 * d, "r--", label="thesis fit, slope 0.86")
left.plot(d, d, ":", color="gray", label="truncated pyramid, slope 1")
left.set_xlabel("d / H")
left.set_ylabel("l_c / L")
left.set_title("contact width against indentation (Fig. 2.3b)")
left.legend(fontsize=8)
left.grid(alpha=0.3)
# Incompressible neo-Hookean: f scales with G at a fixed geometry (one modulus, no other
# stress scale), so the curves of other moduli are this run's force times G'/G
for G_other in (0.25, 0.5, 1.0, 2.0, 3.0):
    right.plot(np.sqrt(f * G_other / G), lc, "o-", ms=3, label=f"G = {G_other:g} MPa")
right.set_xlabel("f^(1/2) (uN^(1/2))")
right.set_ylabel("l_c / L")
fit = f", R² = {s['r2_lc_vs_sqrtf']:.4f}" if "r2_lc_vs_sqrtf" in s else ""
right.set_title(f"l_c against f^(1/2) (Fig. 2.4a){fit}")
right.legend(fontsize=8)
right.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(out / "pyramid.png", dpi=120)

patch_file = out / "patch.csv"  # written at the end of the path: a stopped run has none
patch = np.array([[float(r[k]) for k in ("x", "y", "force", "in_contact")]
                  for r in read_table(patch_file)] if patch_file.is_file() else np.zeros((0, 4)))
if len(patch) >= 3:
    # Contact pressure: each node's force over its tributary area, a third of the area of the
    # triangles around it in a triangulation of the candidate nodes (current x, y); the patch's
    # edge is the half level of the in-contact indicator between contact and free nodes
    x, y, force, in_contact = patch.T
    triangulation = tri.Triangulation(x, y)
    corners = np.stack([x[triangulation.triangles], y[triangulation.triangles]], axis=-1)
    a, b, c = (corners[:, k] for k in range(3))
    areas = 0.5 * np.abs(np.cross(b - a, c - a))
    tributary = np.zeros(len(x))
    for k in range(3):
        np.add.at(tributary, triangulation.triangles[:, k], areas / 3)
    # (a node that no triangle keeps, e.g. one projected onto another, carries no pressure)
    pressure = np.divide(force, tributary, out=np.zeros_like(force), where=tributary > 0)
    fig, ax = plt.subplots(figsize=(5.5, 4.5))
    shading = ax.tripcolor(triangulation, pressure, shading="gouraud", cmap="viridis")
    fig.colorbar(shading, label=f"contact pressure (MPa, G = {G:g} MPa)")
    ax.tricontour(triangulation, in_contact, levels=[0.5], colors="w", linewidths=0.8)
    reach = 1.15 * np.abs(patch[in_contact > 0, :2]).max()
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_aspect("equal")
    ax.set_xlabel("x (um)")
    ax.set_ylabel("y (um)")
    ax.set_title(f"contact patch at d/H = {s['final_d_over_H']:.2f} (Fig. 2.7a): "
                 f"A_c / l_c² = {s['area_ratio']:.3f}", fontsize=9)
    fig.tight_layout()
    fig.savefig(out / "patch.png", dpi=120)
    print(f"wrote {out / 'pyramid.png'} and {out / 'patch.png'}")
else:
    print(f"wrote {out / 'pyramid.png'} (no contact patch: fewer than 3 nodes in contact, "
          f"or the run stopped before its end)")
