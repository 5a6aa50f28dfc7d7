"""Plot of a design run: the optimiser's history (the rms distance to the target against the
iterations) and the designed pattern, the stretch s and angle a per slab of each layer, at the
start and at the last iterate. Usage: /usr/bin/python3 demos/design/plot.py OUTPUT_DIR (writes
design.png)."""
import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

out = pathlib.Path(sys.argv[1])
steps = np.genfromtxt(out / "steps.csv", delimiter=",", names=True, skip_header=1, dtype=None,
                      encoding="utf-8")
design = np.genfromtxt(out / "design.csv", delimiter=",", names=True, skip_header=1,
                       dtype=None, encoding="utf-8")
layers = np.char.strip(design["layer"], '"')  # a text column is quoted
summary = json.loads((out / "summary.json").read_text())
p = summary["parameters"]
fig, (history, stretch, angle) = plt.subplots(1, 3, figsize=(12, 3.8))
history.semilogy(steps["step"], steps["rms_distance"], "b.-", ms=3)
history.set_xlabel("iteration")
history.set_ylabel("rms distance to the target [mm]")
history.set_title(f"{p['shape']}: R = {p['radius']:g} mm", fontsize=9)
slab_length = p["length"] / p["slabs"]
last = design["step"].max()
for layer, colour in (("upper", "tab:blue"), ("lower", "tab:red")):
    for step, style, label in ((0, ":", "start"), (last, "-", f"iteration {last}")):
        rows = design[(layers == layer) & (design["step"] == step)]
        if len(rows) == 0:
            continue
        X = (rows["slab"] + 0.5) * slab_length
        stretch.plot(X, rows["stretch"], style, color=colour, marker=".",
                     label=f"{layer}, {label}")
        angle.plot(X, rows["angle"], style, color=colour, marker=".", label=f"{layer}, {label}")
if p["shape"] == "perversion":
    for ax in (stretch, angle):
        ax.axvline(p["perversion_at"], color="k", ls=":", lw=0.8)
stretch.set_ylabel("stretch s")
angle.set_ylabel("angle a [rad]")
for ax in (stretch, angle):
    ax.set_xlabel("position along the strip [mm]")
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(out / "design.png", dpi=110)
print(f"plot: {out / 'design.png'}")
