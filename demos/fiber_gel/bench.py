"""Speed against error of the fiber_gel scene: alpha_perp and A of one cell (Fig. 4.7's
l = 200 nm, L/l = 1.5, D/d = 4, near the maximum of A) over five P1 and four P2 mesh levels,
on 1 and 2 ranks, against the value extrapolated from the three finest P2 meshes; then the total
time of the Fig. 4.7 sweep (sweep.py --figs 4.7, its own default mesh).

usage: bench.py BUILD_DIR OUTPUT_DIR [--np-list 1,2] [--skip-sweep]
Results: OUTPUT_DIR/bench.csv, bench.png, bench.md (the README table), sweep_fig4_7/.
Times are the scene's own wall_time (mesh, setup and the temperature ramp; not MPI start-up).
"""
import argparse
import csv
import pathlib
import subprocess
import sys
import time

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from studies import richardson, run_scene  # noqa: E402  (demos/studies.py)

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("build", type=pathlib.Path)
parser.add_argument("out", type=pathlib.Path)
parser.add_argument("--np-list", default="1,2", help="rank counts")
parser.add_argument("--skip-sweep", action="store_true", help="do not time the Fig. 4.7 sweep")
args = parser.parse_args()
CASE = {"l": 200, "L": 300, "D": 40}
# h_fiber (nm), h_far = 5 h_fiber; P1 needs finer meshes for the same error
LEVELS = {1: [3, 2, 1.5, 1, 0.75], 2: [4, 3, 2, 1.5]}
QUANTITIES = ("alpha_perp", "anisotropy")


def run(order, h, ranks):
    options = [a for k, v in {**CASE, "order": order, "h_fiber": h, "h_far": 5 * h}.items()
               for a in (f"--{k}", f"{v:g}")]
    s = run_scene(args.build, "fiber_gel", args.out / f"p{order}_h{h:g}_np{ranks}", ranks,
                  options)
    return {"order": order, "h_fiber": h, "ranks": ranks, "num_dofs": s["num_dofs"],
            "newton_iterations": s["newton_iterations"], "wall_time": s["wall_time"],
            **{q: s[q] for q in QUANTITIES}}


args.out.mkdir(parents=True, exist_ok=True)
ranks = [int(r) for r in args.np_list.split(",")]
rows = [run(order, h, r) for r in ranks for order in (1, 2) for h in LEVELS[order]]
reference = {}
for q in QUANTITIES:
    p2 = [r for r in rows if r["order"] == 2 and r["ranks"] == ranks[0]][1:]
    reference[q] = richardson([r["h_fiber"] for r in p2], [r[q] for r in p2])
    print(f"{q}: extrapolated {reference[q][0]:.7f} (observed order {reference[q][1]:.2f})")
for r in rows:
    for q in QUANTITIES:
        r[f"error_{q}"] = abs(r[q] - reference[q][0])
with open(args.out / "bench.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)

fig, axes = plt.subplots(1, 2, figsize=(10, 4))
for ax, q in zip(axes, QUANTITIES):
    for order in (1, 2):
        for r_count in ranks:
            sel = [r for r in rows if r["order"] == order and r["ranks"] == r_count]
            ax.loglog([r["wall_time"] for r in sel], [r[f"error_{q}"] for r in sel], "o-",
                      label=f"P{order}, {r_count} rank{'s' if r_count > 1 else ''}")
    ax.set(xlabel="wall time (s)", ylabel=f"|{q} - extrapolated|", title=q)
    ax.legend()
fig.tight_layout()
fig.savefig(args.out / "bench.png", dpi=150)

lines = ["| order | h_fiber (nm) | ranks | dofs | Newton its | wall time (s) | alpha_perp | "
         "error | A | error |", "|---|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    lines.append(f"| P{r['order']} | {r['h_fiber']:g} | {r['ranks']} | {r['num_dofs']} | "
                 f"{r['newton_iterations']} | {r['wall_time']:.2f} | {r['alpha_perp']:.6f} | "
                 f"{r['error_alpha_perp']:.1e} | {r['anisotropy']:.6f} | "
                 f"{r['error_anisotropy']:.1e} |")
lines.append(f"\nextrapolated: alpha_perp = {reference['alpha_perp'][0]:.7f} (order "
             f"{reference['alpha_perp'][1]:.2f}), A = {reference['anisotropy'][0]:.7f} (order "
             f"{reference['anisotropy'][1]:.2f})")

if not args.skip_sweep:
    start = time.perf_counter()
    subprocess.run([sys.executable, str(pathlib.Path(__file__).parent / "sweep.py"),
                    str(args.build), str(args.out / "sweep_fig4_7"), "--figs", "4.7"],
                   check=True, stdout=subprocess.DEVNULL)
    total = time.perf_counter() - start
    lines.append(f"\nFig. 4.7 sweep (sweep.py --figs 4.7: 10 rod runs for L/l = 1 and 27 runs "
                 f"for L/l = 1.25, 1.5, 2; 2 ranks each): {total:.0f} s")
(args.out / "bench.md").write_text("\n".join(lines) + "\n")
print("\n".join(lines))
