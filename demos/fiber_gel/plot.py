"""Plots of a fiber_gel run: fiber_gel.png, the contraction ratios against temperature, and the
von Mises stress on the mirror plane y = 0 at the final temperature (thesis Fig. 4.8: the
stress concentrates at the fiber's end).

usage: plot.py OUTPUT_DIR
"""
import json
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from fields import FieldSeries, read_table  # noqa: E402  (demos/fields.py)

out = pathlib.Path(sys.argv[1])
s = json.loads((out / "summary.json").read_text())
rows = read_table(out / "steps.csv")
T = [s["parameters"]["T_i"]] + [float(r["T"]) for r in rows]  # from the stress-free start

fig, (left, right) = plt.subplots(1, 2, figsize=(11, 5), width_ratios=[3, 2])
for key in ("alpha_par", "alpha_perp", "anisotropy"):
    left.plot(T, [1.0] + [float(r[key]) for r in rows], "o-", label=key)
left.axhline(s["theory_alpha0"], ls=":", c="gray", label="free gel alpha0")
left.axhline(s["theory_uniaxial_alpha_perp"], ls="--", c="k",
             label="uniaxially constrained alpha_perp")
left.set(xlabel="T (K)", ylabel="contraction ratio", title="temperature ramp")
left.legend(fontsize=8)

# Cells of the 1/8 cell (or of the whole cell) that touch the plane y = 0, at their centroids
series = FieldSeries(out)
x, cells = series.mesh(-1)
vm = series.field("cauchy_stress_vm", -1).ravel()
on_plane = np.abs(x[cells, 1]).min(axis=1) < 1e-9 * np.abs(x).max()
centroids = x[cells[on_plane]].mean(axis=1)
shown = right.tricontourf(centroids[:, 0], centroids[:, 2], vm[on_plane], levels=30)
fig.colorbar(shown, ax=right, label="von Mises stress (MPa)")
right.set(xlabel="x (nm)", ylabel="z (nm)", title=f"von Mises stress on y = 0, T = {T[-1]:g} K")
fig.tight_layout()
fig.savefig(out / "fiber_gel.png", dpi=150)
