"""Parameter studies of the fiber_gel scene: thesis Figs. 4.6, 4.7, 4.9 and 4.10 as CSV + PNG.

  Fig. 4.6   L = l = 30 nm (a rod through the cell): alpha_perp against D/d, with the limits of
             the 0-D theory (free gel alpha0; uniaxially constrained gel, reached as D/d grows)
  Fig. 4.7   l = 200 nm, L/l = 1.25, 1.5, 2: alpha_perp, alpha_par and A against D/d (the rod
             curve of Fig. 4.6 added as L/l = 1); the extrema located by a parabola through the
             three points around the discrete one
  Fig. 4.9   l = 200 nm, L/l = 1.25: A against D/d for N nu/V_m = 0.005, 0.01, 0.02
  Fig. 4.10  L/l = 2, D = 40 nm: A, alpha_par, alpha_perp against l/d = 5 ... 50

usage: sweep.py BUILD_DIR OUTPUT_DIR [--np N] [--figs 4.6,4.7,4.9,4.10] [--D-over-d 2,3,...]
                [scene options]
Scene options (e.g. --h_fiber 2 --order 1) go to every run and override the sweep's mesh:
h_fiber = min(3 nm, (D - d)/6), h_far = 15 nm (README: its error in A is about 2.4e-3).
Results: OUTPUT_DIR/fig4_*.csv and .png, OUTPUT_DIR/extrema.csv, OUTPUT_DIR/timing.csv, one
scene folder per run under OUTPUT_DIR/runs.
"""
import argparse
import csv
import pathlib
import sys
import time

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from studies import run_scene  # noqa: E402  (demos/studies.py)

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("build", type=pathlib.Path)
parser.add_argument("out", type=pathlib.Path)
parser.add_argument("--np", type=int, default=2, help="MPI ranks per run")
parser.add_argument("--figs", default="4.6,4.7,4.9,4.10", help="figures to make")
parser.add_argument("--D-over-d", default="2,2.5,3,3.5,4,4.5,5,6,7",
                    help="D/d values of Figs. 4.7 and 4.9 (comma list)")
args, scene_options = parser.parse_known_args()
MESH = {"h_fiber": 3, "h_far": 15}
d = 10.0  # nm, the thesis' fiber diameter
D_OVER_D_ROD = [2, 2.5, 3, 4, 5, 6, 8, 10, 15, 20]
D_OVER_D = [float(r) for r in args.D_over_d.split(",")]
COLUMNS = ["D_over_d", "l_over_d", "L_over_l", "n_nu_vm", "alpha_perp", "alpha_perp_y",
           "alpha_par", "anisotropy", "num_dofs", "newton_iterations", "wall_time"]


def run(name, **parameters):
    """One scene run; returns its summary.json. The mesh size at the fiber is at most a third
    of the gel's gap between fiber and cell face, (D - d)/2, which narrow cells need."""
    mesh = dict(MESH, h_fiber=min(MESH["h_fiber"], (parameters.get("D", 50) - d) / 6))
    options = [a for k, v in {**mesh, **parameters}.items() for a in (f"--{k}", f"{v:g}")]
    return run_scene(args.build, "fiber_gel", args.out / "runs" / name, args.np,
                     [*options, *scene_options])


def row(s):
    p = s["parameters"]
    return {"D_over_d": p["D"] / p["d"], "l_over_d": p["l"] / p["d"], "L_over_l": p["L"] / p["l"],
            "n_nu_vm": p["n_nu_vm"], **{k: s[k] for k in COLUMNS[4:]}}


def write_csv(name, rows):
    with open(args.out / f"{name}.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows({k: r[k] for k in COLUMNS} for r in rows)


def extremum(figure, curve, quantity, kind, x, y):
    """A row of extrema.csv: where y(x) has its maximum (kind = max) or minimum, from a
    parabola through the discrete extremum and its neighbours; empty at an end of the range."""
    y = np.asarray(y)
    i = int(np.argmax(y) if kind == "max" else np.argmin(y))
    at, value = "", ""
    if 0 < i < len(y) - 1:
        a, b, c = np.polyfit(x[i - 1:i + 2], y[i - 1:i + 2], 2)
        at, value = -b / (2 * a), c - b * b / (4 * a)
    return {"figure": figure, "curve": curve, "quantity": quantity, "kind": kind,
            "D_over_d": at, "value": value}


def sweep_D(label, **parameters):
    """Rows of runs over D/d with fixed other parameters."""
    return [row(run(f"{label}_D{r:g}", D=r * d, **parameters)) for r in D_OVER_D]


def fig4_6():
    summaries = [run(f"fig4_6_D{r:g}", L=30, l=30, D=r * d) for r in D_OVER_D_ROD]
    rows, limits = [row(s) for s in summaries], summaries[0]  # every run has the theory's limits
    write_csv("fig4_6", rows)
    x = np.array([r["D_over_d"] for r in rows])
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.plot(x, [r["alpha_perp"] for r in rows], "o-", label="FE, L = l = 30 nm")
    ax.axhline(limits["theory_uniaxial_alpha_perp"], ls="--", c="k",
               label="uniaxially constrained gel (0-D)")
    ax.axhline(limits["theory_alpha0"], ls=":", c="gray", label="free gel alpha0")
    ax.set(xlabel="D/d", ylabel="alpha_perp", title="Fig. 4.6: rod through the cell")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out / "fig4_6.png", dpi=150)
    return rows


def fig4_7(rod_rows):
    curves = {1.0: rod_rows}
    for ratio in (1.25, 1.5, 2.0):
        curves[ratio] = sweep_D(f"fig4_7_Ll{ratio:g}", l=200, L=ratio * 200)
    write_csv("fig4_7", [r for ratio in (1.25, 1.5, 2.0) for r in curves[ratio]])
    extrema = []
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    for ratio, rows in curves.items():
        x = np.array([r["D_over_d"] for r in rows])
        style = "--" if ratio == 1 else "o-"
        for ax, key in zip(axes, ("alpha_perp", "alpha_par", "anisotropy")):
            ax.plot(x, [r[key] for r in rows], style, label=f"L/l = {ratio:g}")
        if ratio == 1:
            continue
        for key, kind in (("alpha_perp", "min"), ("alpha_par", "max"), ("anisotropy", "max")):
            extrema.append(extremum("4.7", f"L/l = {ratio:g}", key, kind, x,
                                    [r[key] for r in rows]))
    for ax, key in zip(axes, ("alpha_perp", "alpha_par", "A = alpha_par / alpha_perp")):
        ax.set(xlabel="D/d", ylabel=key, xlim=(min(D_OVER_D) - 0.2, max(D_OVER_D) + 0.2))
    axes[0].legend()
    fig.suptitle("Fig. 4.7: l = 200 nm, d = 10 nm")
    fig.tight_layout()
    fig.savefig(args.out / "fig4_7.png", dpi=150)
    return curves[1.25], extrema


def fig4_9(rows_n001):
    curves = {0.01: rows_n001 or sweep_D("fig4_7_Ll1.25", l=200, L=250)}
    for n in (0.005, 0.02):
        curves[n] = sweep_D(f"fig4_9_n{n:g}", l=200, L=250, n_nu_vm=n)
    write_csv("fig4_9", [r for n in sorted(curves) for r in curves[n]])
    extrema = []
    fig, ax = plt.subplots(figsize=(5, 4))
    for n in sorted(curves):
        x = np.array([r["D_over_d"] for r in curves[n]])
        A = [r["anisotropy"] for r in curves[n]]
        ax.plot(x, A, "o-", label=f"N nu/V_m = {n:g}")
        extrema.append(extremum("4.9", f"N nu/V_m = {n:g}", "anisotropy", "max", x, A))
    ax.set(xlabel="D/d", ylabel="A", title="Fig. 4.9: L/l = 1.25, l = 200 nm")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out / "fig4_9.png", dpi=150)
    return extrema


def fig4_10():
    rows = [row(run(f"fig4_10_ld{r:g}", l=r * d, L=2 * r * d, D=40))
            for r in (5, 10, 20, 30, 40, 50)]
    write_csv("fig4_10", rows)
    x = [r["l_over_d"] for r in rows]
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    left.plot(x, [r["anisotropy"] for r in rows], "o-")
    left.set(xlabel="l/d", ylabel="A", title="Fig. 4.10: L/l = 2, D = 40 nm")
    right.plot(x, [r["alpha_par"] for r in rows], "o-", c="r", label="alpha_par")
    right.plot(x, [r["alpha_perp"] for r in rows], "o-", c="g", label="alpha_perp")
    right.axhline(0.8, ls=":", c="gray", label="alpha0")
    right.set(xlabel="l/d", ylabel="contraction ratio")
    right.legend()
    fig.tight_layout()
    fig.savefig(args.out / "fig4_10.png", dpi=150)


args.out.mkdir(parents=True, exist_ok=True)
figs = args.figs.split(",")
timing, extrema, rod, ratio125 = [], [], [], None
for fig in ("4.6", "4.7", "4.9", "4.10"):
    if fig not in figs:
        continue
    start = time.perf_counter()
    if fig == "4.6":
        rod = fig4_6()
    elif fig == "4.7":
        ratio125, found = fig4_7(rod or fig4_6())
        extrema += found
    elif fig == "4.9":
        extrema += fig4_9(ratio125)
    else:
        fig4_10()
    timing.append({"figure": fig, "ranks": args.np, "wall_time": time.perf_counter() - start})
    print(f"Fig. {fig}: {timing[-1]['wall_time']:.1f} s")
for name, table in (("extrema", extrema), ("timing", timing)):
    if table:
        with open(args.out / f"{name}.csv", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(table[0]))
            w.writeheader()
            w.writerows(table)
for e in extrema:
    where = (f"D/d = {e['D_over_d']:.2f}, value {e['value']:.4f}" if e["value"] != ""
             else "at an end of the range")
    print(f"Fig. {e['figure']}, {e['curve']}: {e['kind']} of {e['quantity']}: {where}")
