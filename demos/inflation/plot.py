"""Pressure-stretch path of an inflation run against the closed form: inflation.png.

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

out = pathlib.Path(sys.argv[1])
rows = read_table(out / "steps.csv")
s = json.loads((out / "summary.json").read_text())
prm = s["parameters"]
la = np.array([float(r["inner_stretch"]) for r in rows])
p = np.array([float(r["pressure_over_G"]) for r in rows])

# The closed form of shell.h, p/G(la), over the range of the path
grid = np.linspace(1.0, la.max(), 400)
lb = np.cbrt(1 + (grid**3 - 1) * (prm["A"] / prm["B"])**3)
closed = 2 * ((1 / lb - 1 / grid) + (lb**-4 - grid**-4) / 4)

fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(grid, closed, "k-", label="incompressible closed form")
ax.plot(la, p, "o", ms=4, label=f"gelx arc-length ({s['steps']} steps)")
if "stretch_at_p_max" in s:  # a run stopped before the maximum has none
    ax.plot([s["stretch_at_p_max"]], [s["p_max_over_G"]], "r*", ms=12, label="located maximum")
ax.set_xlabel("inner hoop stretch a/A")
ax.set_ylabel("cavity pressure p/G")
ax.set_title(f"Inflated neo-Hookean shell, B/A = {prm['B'] / prm['A']:g}")
ax.legend()
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(out / "inflation.png", dpi=120)
print(f"wrote {out / 'inflation.png'}")
