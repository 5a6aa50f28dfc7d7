"""Work-precision benchmark of the block scene: stored energy and torque at full load against
wall time, over mesh sizes h and displacement degrees 1 and 2.

The reference is the P2 run on the finest mesh; errors are relative to it, so the finest P2 row
has none. Writes bench.csv and bench.png into the output folder and prints the table.

usage: bench.py BUILD_DIR OUTPUT_DIR [--np N]
"""
import csv
import json
import os
import pathlib
import subprocess
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
np_ranks = sys.argv[sys.argv.index("--np") + 1] if "--np" in sys.argv else "1"
binary = build / "demos" / "block" / "gelx-block"
runs = [(1, h) for h in (0.5, 0.35, 0.25, 0.18, 0.125)] + \
       [(2, h) for h in (0.5, 0.35, 0.25, 0.18, 0.125)]
reference_run = (2, 0.125)

rows = []
for degree, h in runs:
    folder = out / f"p{degree}_h{h}"
    subprocess.run(["mpirun", "-np", np_ranks, str(binary), "--output", str(folder),
                    "--degree", str(degree), "--h", str(h)],
                   check=True, stdout=subprocess.DEVNULL,
                   env=dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                            OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1"))
    s = json.loads((folder / "summary.json").read_text())
    rows.append({"degree": degree, "h": h, "num_dofs": s["num_dofs"], "steps": s["steps"],
                 "newton_iterations": s["newton_iterations"], "wall_time": s["wall_time"],
                 "strain_energy": s["strain_energy"], "torque": s["torque"]})

ref = next(r for r in rows if (r["degree"], r["h"]) == reference_run)
for r in rows:
    for q in ("strain_energy", "torque"):
        r[f"{q}_error"] = abs(r[q] / ref[q] - 1) if r is not ref else float("nan")

out.mkdir(parents=True, exist_ok=True)
with open(out / "bench.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)

print(f"block work-precision ({np_ranks} rank(s)); reference: P{reference_run[0]}, "
      f"h = {reference_run[1]}")
print(" p      h    dofs  steps  newton   wall [s]    energy           err      torque"
      "           err")
for r in rows:
    print(f"{r['degree']:2d} {r['h']:6.3f} {r['num_dofs']:7d} {r['steps']:6d} "
          f"{r['newton_iterations']:7d} {r['wall_time']:10.2f}  {r['strain_energy']:.10f} "
          f"{r['strain_energy_error']:9.2e}  {r['torque']:.10f} {r['torque_error']:9.2e}")

fig, axes = plt.subplots(1, 2, figsize=(10, 4))
for ax, q in zip(axes, ("strain_energy", "torque")):
    for degree, marker in ((1, "o"), (2, "s")):
        pts = [r for r in rows if r["degree"] == degree and r is not ref]
        ax.loglog([r["wall_time"] for r in pts], [r[f"{q}_error"] for r in pts],
                  marker=marker, label=f"P{degree}")
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel(f"relative error in {q}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
fig.suptitle("block: stretch 1.5 + twist 90°, error against P2 at h = 0.125")
fig.tight_layout()
fig.savefig(out / "bench.png", dpi=120)
print(f"wrote {out / 'bench.csv'} and {out / 'bench.png'}")
