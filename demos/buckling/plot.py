"""Load-deflection paths of a buckling run against the elastica: buckling.png.

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
from fields import read_table  # noqa: E402  (demos/fields.py)
from closed_forms import cantilever_elastica  # noqa: E402  (demos/closed_forms.py)

out = pathlib.Path(sys.argv[1])
s = json.loads((out / "summary.json").read_text())
rows = read_table(out / "steps.csv")
P_cr = s["critical_load_over_euler"]


# The cantilever elastica, parametrised by k = sin(tip angle / 2); with clamped ends each
# quarter of the column is such a cantilever and the mid-span deflection is twice its tip's
d_cantilever, load = np.array([cantilever_elastica(k) for k in np.linspace(1e-6, 0.8, 400)]).T
d = d_cantilever / 2 if s["parameters"]["ends"] == "clamped-clamped" else d_cantilever

shown = d <= 1.1 * max(float(r["deflection_over_L"]) for r in rows)

fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(d[shown], load[shown], "k-", label="elastica")
styles = {"straight": ("s", "perfect column, straight path"),
          "branch": ("o", "after branch switching"),
          "imperfect": ("^", f"imperfect, amplitude {s['imperfection_amplitude']:g}")}
for path, (marker, label) in styles.items():
    pts = [r for r in rows if r["path"] == path]
    ax.plot([float(r["deflection_over_L"]) for r in pts],
            [float(r["axial_force_over_euler"]) / P_cr for r in pts], marker, ms=4, label=label)
ax.set_xlabel("lateral deflection d / L")
ax.set_ylabel("axial load P / P_cr")
ax.set_ylim(0, 1.1 * max(load[d <= 0.35].max(), 1.05))
ax.set_title(f"{s['parameters']['ends']} column, slenderness {s['slenderness']:.0f}: "
             f"P_cr / P_Euler = {P_cr:.4f}")
ax.legend(loc="lower right")
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(out / "buckling.png", dpi=120)
print(f"wrote {out / 'buckling.png'}")

# The bifurcation diagram (--diagram true): the tip deflections of every branch against the
# load, stable points (no negative eigenvalue) joined by solid lines, unstable by dashed ones
if (out / "diagram.csv").exists():
    points = read_table(out / "diagram.csv")
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for axis, (ax, column) in enumerate(zip(axes, ["tip_x_over_L", "tip_y_over_L"])):
        for branch in sorted({int(p["branch"]) for p in points}):
            pts = [p for p in points if int(p["branch"]) == branch]
            load = [float(p["load_over_critical"]) for p in pts]
            tip = [float(p[column]) for p in pts]
            negative = [int(p["negative_eigenvalues"]) for p in pts]
            for k in range(len(pts)):
                style = "-" if negative[k] == 0 else "--"
                segment = slice(max(k - 1, 0), k + 1)
                ax.plot(tip[segment], load[segment], style, color=f"C{branch}")
            ax.plot(tip, load, "o", color=f"C{branch}", ms=3,
                    label=f"branch {branch}" if axis == 0 else None)
        ax.set_xlabel(f"tip deflection {'x' if axis == 0 else 'y'} / L")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("P / P_cr1")
    axes[0].legend(loc="lower left", fontsize=8)
    fig.suptitle("bifurcation diagram by deflated continuation (solid: stable, dashed: unstable)")
    fig.tight_layout()
    fig.savefig(out / "diagram.png", dpi=120)
    print(f"wrote {out / 'diagram.png'}")
