"""Plot of a crease run: the valley's depth against the far field's swelling ratio h/H along
the path, the onset (the first limit point) marked, beside Hong, Zhao and Suo's crease
threshold (2.4) and Biot's wrinkling threshold (3.4). Usage: /usr/bin/python3
demos/crease/plot.py OUTPUT_DIR (writes fold.png)."""
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
summary = json.loads((out / "summary.json").read_text())
H = summary["parameters"]["H"]
fig, ax = plt.subplots(figsize=(5, 4))
ax.semilogy(steps["swelling_ratio"], steps["valley_depth"] / H, "b.-", label="gelx")
if "fold" in summary:
    fold = summary["fold"]
    ax.semilogy([fold["swelling_ratio"]], [fold["valley_depth"] / H], "rs",
                label=f"onset (limit point): h/H = {fold['swelling_ratio']:.4g}")
for ratio, name in ((2.4, "crease, Hong et al."), (3.4, "Biot")):
    ax.axvline(ratio, color="k", ls=":")
    ax.text(ratio, ax.get_ylim()[1], name, rotation=90, va="top", ha="right", fontsize=8)
ax.set_xlabel("far field's swelling ratio h/H")
ax.set_ylabel("valley depth / H")
p = summary["parameters"]
ax.set_title(f"{p['nx']} x {p['nz']} cells, dip {p['imperfection']:g} H", fontsize=9)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(out / "fold.png", dpi=120)
print(f"plot: {out / 'fold.png'}")
