"""Plot of a swelling run: the layer's thickness change against time on log axes (the
uptake: polymer and solvent are incompressible), with the sqrt(t) of a diffusion front for
reference; of a --path equilibrium run, the thickness against the solvent's mu of each load
step. Usage: /usr/bin/python3 demos/swelling/plot.py OUTPUT_DIR (writes uptake.png)."""
import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

out = pathlib.Path(sys.argv[1])
steps = np.genfromtxt(out / "steps.csv", delimiter=",", names=True, skip_header=1)
summary = json.loads((out / "summary.json").read_text())
H = summary["parameters"]["H"]
fig, ax = plt.subplots(figsize=(5, 4))
if summary["parameters"]["path"] == "equilibrium":
    ax.plot(steps["mu"], steps["thickness"] / H, "bo-", label="gelx, each load step")
    ax.set_xlabel(r"chemical potential of the solvent $\mu$ [kT]")
    ax.set_ylabel(r"thickness $h/H$ at equilibrium")
else:
    t, dh = steps["time"], steps["thickness"] - H
    ax.loglog(t, dh / H, "b-", label="gelx")
    middle = len(t) // 3
    ax.loglog(t, dh[middle] / H * np.sqrt(t / t[middle]), "k:", label=r"$\propto\sqrt{t}$")
    ax.set_xlabel("time t [s]")
    ax.set_ylabel(r"thickness change $(h - H)/H$ (solvent taken up)")
ax.set_title(f"layer in solvent: chi = {summary['parameters']['chi']}, "
             f"lambda0 = {summary['parameters']['lambda0']}", fontsize=9)
ax.legend()
fig.tight_layout()
fig.savefig(out / "uptake.png", dpi=120)
print(f"plot: {out / 'uptake.png'}")
