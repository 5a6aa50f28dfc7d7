"""Parameter studies of the bistrip scene (issue #16; thesis ch. 3, §3.4) as CSV + PNG.

  fig3.7     three perversions (w = 9 mm), 30 -> 9 cm, outputs every 3 mm: their positions,
             the loss of mirror symmetry, each perversion's winding about the end-to-end axis
             (the thesis: the rightmost turns ~360 degrees more than the others from 23.3 to
             13.9 cm), and the energy condensation Ee(n) at each (peak height and width; the
             least Ee between neighbours against the helix background: repulsion)
  fig3.3     loading rate: end speeds v = 67 mm / T for T = 0.1 and 1 s (--fig3.3-times); (a)
             the end stops at 23.3 cm (travel 67 mm, loading time T), (b) it passes 23.3 cm on
             its way to 9 cm (travel 210 mm, loading time T 210/67: the same mean speed).
             Perversions at 23.3 cm. The path model is the damped flow unless
             --fig3.3-method inertia (or explicit) asks for the equation of motion
  fig3.8     pre-compressed strip (Figs. 3.8, 3.9): section "B 3x3, A 3x3", stretch 0.4 (L' =
             75 cm; random imperfection, the bonded strip left to buckle first), 30 -> 15 cm and
             back out to 30 cm, outputs every 2 mm: perversion count along both legs, events
             (annihilation, coalescence, creation) from tracking, a kymograph of the twist's
             sign along the strip, the states in and out at the same end distance, and the
             same run at nz / 2 (count, positions, time split)
  fig3.8_inertia  the same strip bonded and let go at L with inertia (central differences,
             0.05 s, damping 300/s) on 15, 30 and 60 slabs: the perversions where it ends
  fig3.9     stretching back (w = 9, as the caption of Fig. 3.9 reads): in to 9 cm and back
             out to 30 cm, outputs every 5 mm: perversions, helix amplitude and helical periods
             on both ways, and the states in and out at the same end distance
  fig3.10    cross-sections a-f (below), each to 15 cm: helix/perversions, V-shape or straight
             from the final centreline, against the thesis' ticks and crosses
  deflation  metastable states at 23.3 cm for w = 5 and 9: deflation (--equilibria 4) from
             the path's state, the arc-length branch's equilibrium there, the state the strip
             reaches there stretched back from 13.9 cm, and the path states of fig3.3 (a):
             distinct equilibria, their energies above the lowest, stability

Meshes: nz = 60 Q2 slabs (the bench: 1.4 % energy error at 9 cm for w = 5), fig3.8 too, and
fig3.8 again at nz = 30: the quench's perversion count follows the mesh (4, 8, 18 at nz = 15,
30, 60, measured), and nz = 120's quench needed steps 1e4 times smaller than nz = 60's
(measured over its first 5 minutes): a run of many hours, not made here.

Cross-sections of Fig. 3.10 (w0 = 9 mm, h = 3 mm, h' = 0.2 mm; layers bottom to top; B
stress-free, A prestretched given by its natural section, S prestretched given by its bonded
section). Our reading of the text:
  a  "B 9x3, A 9x3"              the bistrip: A shrinks laterally to w = 5.1 mm        tick
  b  "B 9x3, S 9x3"              the prestretched strip as wide as B once stretched   tick
  c  "B 9x3, S 9x3, B 9x0.2"     b with a thin (h') stress-free outer strip: up-down  tick
                                 asymmetric ("b is c with an outer strip of zero thickness")
  d  "B 9x3, S 9x3, B 9x3"       symmetric tristrip, prestretched core                 cross
  e  "B 6x3, A 9x3, B 6x3"       symmetric tristrip with outer strips w' = 6 mm wide   cross
                                 (w' = 5.4-6.3 mm in the caption: nearer A's shrunk width)
  f  "B 9x0.2, S 9x3, B 9x0.2"   symmetric, outer strips much thinner than c's thick  cross
                                 one ("much thinner outer strips compared with ... c")
The caption does not say which strips w' belongs to; e is our guess (`--section` of a single
run tests another reading).

--quick shrinks every study (nz = 30, one loading time, short paths, two sections, one
deflation run) to smoke-test the whole sweep: about 15 minutes at 1 rank on the shared
2-core machine (measured per study: fig3.7 3 min, fig3.3 4, fig3.8 5, fig3.10 1, deflation
~3); its numbers mean nothing.

usage: sweep.py BUILD_DIR OUTPUT_DIR [--np N]
                [--studies fig3.7,fig3.3,fig3.8,fig3.8_inertia,fig3.9,fig3.10,deflation]
                [--quick] [--fig3.3-w 5] [--fig3.3-method dynamics|inertia|explicit]
                [--fig3.3-times 0.1,1] [scene options and PETSc options, given to every run]
Results: OUTPUT_DIR/<study>.csv (+ extra CSVs) and .png, OUTPUT_DIR/timing.csv (each run's
wall time), runs under OUTPUT_DIR/runs/<study>/<name>. A run folder that holds a completed run
is reused, so an interrupted sweep resumes; a study whose run fails is reported and skipped.
"""
import argparse
import csv
import json
import pathlib
import subprocess
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import Normalize  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))
from fields import FieldSeries  # noqa: E402  (demos/fields.py)
from studies import run_scene  # noqa: E402  (demos/studies.py)
import perversions as pv  # noqa: E402
from plot import column, perversions_of, plot_shapes, stacked_strips, table  # noqa: E402

STUDIES = ["fig3.7", "fig3.3", "fig3.8", "fig3.8_inertia", "fig3.9", "fig3.10", "deflation"]
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("build", type=pathlib.Path)
parser.add_argument("out", type=pathlib.Path)
parser.add_argument("--np", type=int, default=2, help="MPI ranks per run")
parser.add_argument("--studies", default=",".join(STUDIES), help="studies to run (comma list)")
parser.add_argument("--quick", action="store_true", help="shrink every study (smoke test)")
parser.add_argument("--fig3.3-w", dest="fig3_3_w", type=float, default=5,
                    help="strip width of the loading-rate study (mm)")
parser.add_argument("--fig3.3-method", dest="fig3_3_method", default="dynamics",
                    choices=["dynamics", "inertia", "explicit"],
                    help="the loading-rate study's path model: the damped flow (quasi-static at "
                         "every rate, demos/bistrip/README.md), or with inertia")
parser.add_argument("--fig3.3-times", dest="fig3_3_times",
                    help="the loading-rate study's loading times T of case (a) (s, comma list; "
                         "default 0.1,1, with --quick 1)")
args, scene_options = parser.parse_known_args()
QUICK = args.quick
L = 300.0  # mm, the strip's length in every study
NZ = 30 if QUICK else 60
# fig3.10 asks helix or V only, of six runs: 40 slabs (the bench: 3.5 % energy error at 9 cm
# for w = 5) are enough to tell, and save a third of the time
NZ_SECTIONS = 30 if QUICK else 40
THESIS_DISTANCE = 233.0  # mm: Figs. 3.3 and 3.7 (23.3 cm)
DEEPEST = 139.0  # mm: the last end distance of Fig. 3.7 (13.9 cm)
# Each run's wall time, {(study, run): row}, kept across sweeps that run some studies only
timing = ({(r["study"], r["run"]): r for r in table(args.out, "timing.csv")}
          if (args.out / "timing.csv").exists() else {})


def options(petsc=None, **scene):
    """Command-line options: scene options --name value, PETSc options -name value."""
    return ([a for k, v in scene.items() for a in (f"--{k}", str(v))]
            + [a for k, v in (petsc or {}).items() for a in (f"-{k}", str(v))])


def run(study, name, *opts):
    """One scene run under OUT/runs/<study>/<name> (reused when complete); its wall time goes
    to timing.csv at once, so an interrupted sweep keeps it. Returns (folder, summary)."""
    folder = args.out / "runs" / study / name
    summary = run_scene(args.build, "bistrip", folder, args.np, [*opts, *scene_options],
                        reuse=True)
    timing[study, name] = {"study": study, "run": name, "ranks": summary["mpi_ranks"],
                           "num_dofs": summary["num_dofs"], "wall_time": summary["wall_time"],
                           **{f"time_{part}": t
                              for part, t in summary.get("time_split", {}).items()}}
    write_csv("timing", list(timing.values()))
    return folder, summary


def write_csv(name, rows, fields=None):
    """OUT/<name>.csv; `fields` names the columns of a table that may be empty."""
    fields = fields or list(dict.fromkeys(k for r in rows for k in r))
    with open(args.out / f"{name}.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)


def joined(values, digits=2):
    return ";".join(f"{v:.{digits}f}" for v in values)


def by_output(folder, name):
    """A per-output table (centreline.csv, slab_energy.csv) as {output: rows}."""
    grouped = {}
    for r in table(folder, name):
        grouped.setdefault(int(r["output"]), []).append(r)
    return grouped


def pitch(row):
    """The output's mean helix pitch (mm), nan before helices (or in older runs)."""
    value = row.get("helix_pitch", "")
    return float(value) if value not in ("", "nan", "null") else np.nan


def nearest(rows, distance):
    """The row of steps.csv whose end distance is nearest `distance`."""
    return min(rows, key=lambda r: abs(float(r["end_distance"]) - distance))


def save(fig, name):
    fig.savefig(args.out / name, dpi=130, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {args.out / name}")


# ---------------------------------------------------------------------------------------------
def fig3_7():
    """Three perversions (w = 9): positions, mirror asymmetry, winding, energy condensation.

    Matching tolerance 10 mm: at an output every 3 mm of end travel a perversion moves a few
    mm at most (the default strip's stays at L/2 to 1e-3 mm); the perversions of Fig. 3.7 are
    ~50 mm apart. The clamps' boundary layers (Ee up to 1.24 at 9 cm, elevated over the first
    ~8 slabs = 24 mm in the default run) are left out of the peaks: clamp zone 30 mm. The
    background is the median Ee one helix pitch or more from every perversion."""
    end, every = (200, 5) if QUICK else (90, 3)
    folder, _ = run("fig3.7", "w9", *options(w=9, nz=NZ, end_distance=end, output_every=every))
    steps = table(folder, "steps.csv")
    lines, slabs = by_output(folder, "centreline.csv"), by_output(folder, "slab_energy.csv")
    path = [perversions_of(r) for r in steps]
    ids, _ = pv.track(path, tolerance=10, near=0)
    angles, rows, profiles = [], [], []
    for r, positions in zip(steps, path):
        line = lines[int(r["output"])]
        width = np.column_stack([column(line, f"d1{c}") for c in "xyz"])
        angles.append([pv.frame_angle(column(line, "Z"), width, z) for z in positions])
        slab = slabs[int(r["output"])]
        peaks, troughs, background = pv.condensation(
            column(slab, "z"), column(slab, "energy_scaled"), positions, L, clamp_zone=30,
            far=pitch(r) if np.isfinite(pitch(r)) else 0.1 * L)
        profiles.append((column(slab, "z"), column(slab, "energy_scaled")))
        rows.append({"output": r["output"], "end_distance": float(r["end_distance"]),
                     "perversions": len(positions), "positions": joined(positions),
                     "ids": ";".join(map(str, ids[len(rows)])),
                     "mirror_asymmetry": pv.mirror_asymmetry(positions, L),
                     "negative_eigenvalues": r["negative_eigenvalues"],
                     "peaks": joined([p["peak"] for p in peaks], 4),
                     "peak_widths": joined([p["width"] for p in peaks], 1),
                     "troughs_between": joined(troughs, 4), "background": background})
    turned = pv.windings(ids, angles)
    for k, row in enumerate(rows):
        row["windings"] = joined([turned[i][k] for i in ids[k]], 1)
    write_csv("fig3.7", rows)
    # Winding from 23.3 to 13.9 cm per perversion: nan unless outputs lie within one output
    # spacing of both (a shorter path, or a perversion born or gone in between)
    d = np.array([r["end_distance"] for r in rows])
    first, last = (int(np.argmin(np.abs(d - target))) for target in (THESIS_DISTANCE, 139))
    reached = abs(d[first] - THESIS_DISTANCE) <= every and abs(d[last] - 139) <= every
    summary = []
    for i, angle in turned.items():
        there = [k for k in range(len(d)) if not np.isnan(angle[k])]
        summary.append({"perversion": i, "from_end_distance": d[there[0]],
                        "to_end_distance": d[there[-1]],
                        "position_first": path[there[0]][ids[there[0]].index(i)],
                        "position_last": path[there[-1]][ids[there[-1]].index(i)],
                        "winding_233_to_139": angle[last] - angle[first] if reached else np.nan,
                        "winding_total": angle[there[-1]] - angle[there[0]]})
    write_csv("fig3.7_winding", summary)
    for s in summary:
        print(f"fig3.7: perversion {s['perversion']} at {s['position_last']:.1f} mm: winding "
              f"from 23.3 to 13.9 cm {s['winding_233_to_139']:.0f} degrees")

    fig, (top, middle, bottom) = plt.subplots(3, 1, figsize=(8, 11))
    for i, angle in turned.items():
        there = [k for k in range(len(d)) if not np.isnan(angle[k])]
        top.plot(d[there], [path[k][ids[k].index(i)] for k in there], ".-", label=f"#{i}")
        middle.plot(d[there], angle[there], ".-", label=f"#{i}")
    top.set(ylabel="perversion position Z (mm)", ylim=(0, L))
    middle.set(ylabel="winding of d1 about z (degrees)")
    middle.axvspan(139, THESIS_DISTANCE, color="gray", alpha=0.15)
    for ax in (top, middle):
        ax.set_xlabel("end distance (mm)")
        ax.invert_xaxis()
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=4)
    shown = sorted({int(np.argmin(np.abs(d - t))) for t in (THESIS_DISTANCE, 186, 139, end)})
    for colour, k in enumerate(shown):
        z, scaled = profiles[k]
        bottom.plot(z, scaled, color=f"C{colour}", label=f"{d[k]:.0f} mm")
        for Z in path[k]:
            bottom.axvline(Z, color=f"C{colour}", ls="--", lw=0.8)
    bottom.set(xlabel="Z (mm)", ylabel="Ee = E(n)/min E - 1",
               title="slab energy (Fig. 3.7b); dashed: perversions")
    bottom.legend(fontsize=8)
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, "fig3.7.png")
    save(plot_shapes(folder, normalized=False), "fig3.7_shapes.png")


# ---------------------------------------------------------------------------------------------
def fig3_3():
    """Loading rate: perversions at 23.3 cm when the end stops there (a) or passes it (b).

    Outputs every 67/6 mm, so that (b) has one within a few tenths of a mm of 23.3 cm (the
    output is taken at the first time step past its mark); (a) ends exactly there, after the
    hold. The smooth-step ramp starts and ends at rest, so the end's speed at 23.3 cm is 0 in
    (a) and near its peak in (b): both the mean speed (travel / loading time) and, for (b),
    the speed measured between the outputs around 23.3 cm are reported."""
    times = ([float(t) for t in args.fig3_3_times.split(",")] if args.fig3_3_times
             else [1.0] if QUICK else [0.1, 1.0])
    method = args.fig3_3_method
    prefix = {"dynamics": "dynamics_", "inertia": "inertial_", "explicit": "explicit_"}[method]
    far_end = 200 if QUICK else 90
    travel_a, travel_b = L - THESIS_DISTANCE, L - far_end
    every = travel_a / 6
    rows = []
    for T in times:
        for case, travel, end in (("a", travel_a, THESIS_DISTANCE), ("b", travel_b, far_end)):
            loading = T * travel / travel_a
            folder, _ = run("fig3.3", f"{method}_{case}_T{loading:.4g}", *options(
                {prefix + "loading_time": loading}, method=method, w=args.fig3_3_w, nz=NZ,
                end_distance=end, output_every=every))
            steps = table(folder, "steps.csv")
            at = steps[-1] if case == "a" else nearest(steps, THESIS_DISTANCE)
            k = steps.index(at)
            speed = (0.0 if case == "a" else
                     (float(steps[k - 1]["end_distance"]) - float(steps[k + 1]["end_distance"]))
                     / (float(steps[k + 1]["time"]) - float(steps[k - 1]["time"])))
            rows.append({"method": method, "case": case, "loading_time": loading,
                         "travel": travel,
                         "mean_end_speed": travel / loading, "end_speed_at_233": speed,
                         "end_distance": float(at["end_distance"]),
                         "perversions": int(at["perversions"]),
                         "perversion_positions": at["perversion_positions"],
                         "negative_eigenvalues": at["negative_eigenvalues"],
                         "strain_energy": float(at["strain_energy_A"])
                         + float(at["strain_energy_B"]),
                         "kinetic_ratio": at["kinetic_ratio"], "run": folder.name})
            print(f"fig3.3 ({case}) mean speed {travel / loading:.0f} mm/s: "
                  f"{at['perversions']} perversions at {float(at['end_distance']):.1f} mm")
    write_csv("fig3.3", rows)
    fig, ax = plt.subplots(figsize=(6, 4))
    for case, marker in (("a", "o-"), ("b", "s--")):
        chosen = [r for r in rows if r["case"] == case]
        ax.semilogx([r["mean_end_speed"] for r in chosen], [r["perversions"] for r in chosen],
                    marker, label={"a": "(a) stops at 23.3 cm",
                                   "b": f"(b) passes 23.3 cm on to {far_end / 10:g} cm"}[case])
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set(xlabel="mean end speed (mm/s)", ylabel="perversions at 23.3 cm",
           title=f"Fig. 3.3: loading rate, w = {args.fig3_3_w:g} mm, --method {method}")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, "fig3.3.png")


# ---------------------------------------------------------------------------------------------
def fig3_8():
    """Pre-compressed strip: perversions going in and stretched back, tracked events, states
    on the way in and out at the same end distance, and the mesh's effect.

    The bonded strip is already unstable (87 negative tangent eigenvalues at nz = 30, 272 at
    nz = 120: the compressed A buckles by itself), so eigen-buckling does not apply: the
    imperfection is random (--seed random) and the bonded strip is first left to buckle at
    L (--bonding quench: leg 0), as the thesis' ~20 perversions at once suggest. (Building
    the pre-compression up slowly instead, --bonding ramp, measured at nz = 60: one central
    perversion, 547 s.) Leg 1 starts where unstable directions are left (1 at nz = 30, 2 at
    nz = 60): its first milliseconds resolve their growth with steps of microseconds. At
    nz = 60 an element is driven to zero volume 0.11 ms into leg 1 (every stage after it is
    inadmissible, det F <= 0, down to steps of 1e-16 s: measured with
    -dynamics_ts_adapt_monitor), and TS gives up after 20 rejections in a row; nz = 30 gets
    through. The figures show the finest run that got through leg 1.

    The same run at half the slabs is the coarser mesh the issue asks about: its perversion
    count and positions against the finer one's, and the time of each.

    Matching tolerance 4 mm (a quarter of the ~15 mm between perversions when ~20 form);
    coalescence when the survivor is within two helical pitches (the thesis sees no
    coalescence beyond about two helical periods)."""
    nz, end, every = (30, 290, 2) if QUICK else (60, 150, 2)
    meshes = {}
    for name, slabs in (("precompressed", nz), ("precompressed_coarse", nz // 2)):
        opts = options(section="B 3x3, A 3x3", stretch=0.4, seed="random", bonding="quench",
                       nz=slabs, end_distance=end, return_distance=L, output_every=every)
        try:
            meshes[name] = run("fig3.8", name, *opts)[0]
        except subprocess.CalledProcessError:
            # The outputs written before a failure stay valid (the scene never rewrites them):
            # the study shows how far the path got, and says so
            meshes[name] = args.out / "runs" / "fig3.8" / name
            print(f"fig3.8: {name} stopped early (see {meshes[name] / 'summary.json'}); "
                  "its outputs so far are analysed")
    through = [f for f in meshes.values()
               if (f / "steps.csv").exists() and any(r["leg"] == "1" for r in table(f, "steps.csv"))]
    write_csv("fig3.8_meshes", [mesh_row(name, f) for name, f in meshes.items()])
    if not through:
        print("fig3.8: no run got into leg 1; only fig3.8_meshes.csv is written")
        return
    folder = through[0]
    print(f"fig3.8: the figures show {folder.name}")
    steps = table(folder, "steps.csv")
    path, found = track_events(steps)
    d, leg = column(steps, "end_distance"), column(steps, "leg").astype(int)
    write_csv("fig3.8", [{"output": r["output"], "leg": r["leg"],
                          "end_distance": float(r["end_distance"]),
                          "perversions": int(r["perversions"]),
                          "positions": r["perversion_positions"],
                          "negative_eigenvalues": r["negative_eigenvalues"],
                          "helix_pitch": pitch(r)} for r in steps])
    events = [{"leg": leg[e["output"]], "output": steps[e["output"]]["output"],
               "end_distance_before": d[e["output"] - 1], "end_distance": d[e["output"]],
               "kind": e["kind"], "positions": joined(e["positions"]),
               "survivor": e["survivor"]} for e in found]
    write_csv("fig3.8_events", events, ["leg", "output", "end_distance_before",
                                        "end_distance", "kind", "positions", "survivor"])
    for k in (1, 2):
        kinds = [e["kind"] for e in events if e["leg"] == k]
        print(f"fig3.8 leg {k}: " + (", ".join(f"{kinds.count(kind)} {kind}"
                                                for kind in sorted(set(kinds))) or "no events"))
    write_csv("fig3.8_hysteresis", hysteresis(steps, every),
              ["end_distance", "distance_shift", "perversions_in", "perversions_out", "strain_energy_in",
               "strain_energy_out", "energy_out_minus_in", "negative_eigenvalues_in",
               "negative_eigenvalues_out"])

    fig, ax = plt.subplots(figsize=(8, 4))
    count = column(steps, "perversions")
    for k, style in ((1, "-"), (2, "--")):
        ax.plot(d[leg == k], count[leg == k], style, label={1: "going in", 2: "stretched back"}[k])
    markers = {"annihilation": "x", "coalescence": "v", "creation": "^", "vanishing": "1",
               "appearance": "2"}
    for kind, marker in markers.items():
        at = [e["output"] for e in found if e["kind"] == kind]  # indices into steps
        if at:
            ax.plot(d[at], count[at], marker, ms=8, ls="none", label=kind)
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set(xlabel="end distance (mm)", ylabel="perversions",
           title=f"Figs. 3.8-3.9: pre-compressed strip (L' = 75 cm), {folder.name}")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, "fig3.8.png")

    # Kymograph: the twist's sign along the strip at every output, one panel per leg
    lines = by_output(folder, "centreline.csv")
    Z = column(lines[int(steps[0]["output"])], "Z")
    sign = np.array([np.sign(column(lines[int(r["output"])], "twist")) for r in steps])
    # One panel per leg the run got through: 0 (the quench at L), 1 (in), 2 (back out)
    legs = [k for k in (0, 1, 2) if (leg == k).any()]
    fig, axes = plt.subplots(1, len(legs), figsize=(6 * len(legs), 5), sharey=True,
                             squeeze=False)
    axes = axes[0]
    for ax, k in zip(axes, legs):
        ax.pcolormesh(Z, d[leg == k], sign[leg == k], cmap="coolwarm", norm=Normalize(-1, 1),
                      shading="nearest")
        for i in np.flatnonzero(leg == k):
            ax.plot(path[i], [d[i]] * len(path[i]), "k.", ms=2)
        ax.set(xlabel="Z (mm)",
               title={0: "left to buckle at L", 1: "going in", 2: "stretched back"}[k])
    axes[0].set_ylabel("end distance (mm)")
    axes[0].invert_yaxis()
    fig.suptitle("sign of the twist along the strip (red: right-handed); dots: perversions")
    fig.tight_layout()
    save(fig, "fig3.8_kymograph.png")


def track_events(steps):
    """The perversions of each output and the events between outputs (perversions.track)."""
    path = [perversions_of(r) for r in steps]
    near = [2 * pitch(r) if np.isfinite(pitch(r)) else 0 for r in steps]
    return path, pv.track(path, tolerance=4, near=near)[1]


def hysteresis(steps, spacing):
    """The states near the same end distance going in (leg 1) and stretched back (leg 2): two
    equilibria of one strip at one end distance when their perversions differ. Outputs fall
    on time steps, not on exact distances: each leg-2 output is paired with the leg-1 output
    nearest it (within a quarter of the output spacing `spacing`), whose energy is carried to the
    leg-2 distance with dE/dd = F (as for the arc-length branch in the deflation study)."""
    def energy(r):
        return float(r["strain_energy_A"]) + float(r["strain_energy_B"])
    going_in = [r for r in steps if r["leg"] == "1"]
    rows = []
    for r in (r for r in steps if r["leg"] == "2"):
        d = float(r["end_distance"])
        before = min(going_in, key=lambda q: abs(float(q["end_distance"]) - d))
        shift = d - float(before["end_distance"])
        if abs(shift) <= spacing / 4:
            energy_in = energy(before) + float(before["end_force"]) * shift
            rows.append({"end_distance": d, "distance_shift": shift,
                         "perversions_in": int(before["perversions"]),
                         "perversions_out": int(r["perversions"]),
                         "strain_energy_in": energy_in, "strain_energy_out": energy(r),
                         "energy_out_minus_in": energy(r) - energy_in,
                         "negative_eigenvalues_in": int(before["negative_eigenvalues"]),
                         "negative_eigenvalues_out": int(r["negative_eigenvalues"])})
    return rows


def fig3_8_inertia():
    """The pre-compressed strip bonded and let go at L with inertia, on three meshes: does
    the count converge once the equation of motion, not a gradient flow, picks the
    wavelengths? fig3.8's quench (the flow) gives 4, 8, 18 perversions on 15, 30, 60 slabs.

    Central differences (--method explicit, the ABAQUS/Explicit analogue, at the stable
    step) from the bonded strip at rest, the end held at L (--end_distance 300: the bonding
    leg alone) for 0.05 s, with a mass-proportional damping of 300/s: half of critical on
    the strip's first bending mode (period 0.0206 s), so the motion settles within the leg,
    and 1/70 of the fastest modes' growth rate (~1e4/s), which inertia, not the damping,
    therefore selects. Per mesh: the perversions at 2 and 10 ms (while the pattern forms)
    and where the leg ends, KE / SE there, steps and wall time."""
    release = {"bonding_explicit_loading_time": 0.05, "bonding_explicit_rayleigh_mass": 300}
    rows = []
    for slabs in (15, 30) if QUICK else (15, 30, 60):
        folder, summary = run("fig3.8_inertia", f"nz{slabs}", *options(
            release, section="B 3x3, A 3x3", stretch=0.4, seed="random", bonding="quench",
            nz=slabs, end_distance=L, method="explicit"))
        outputs = table(folder, "steps.csv")
        last = outputs[-1]

        def at(ms):  # the perversions at the output nearest a time (ms) of the release
            nearest_time = min(outputs, key=lambda r: abs(float(r["time"]) - ms / 1e3))
            return int(nearest_time["perversions"])

        rows.append({"nz": slabs, "num_dofs": summary["num_dofs"],
                     "perversions_at_2ms": at(2), "perversions_at_10ms": at(10),
                     "perversions": int(last["perversions"]),
                     "positions": last["perversion_positions"],
                     "kinetic_ratio": float(last["kinetic_ratio"]), "steps": int(last["step"]),
                     "wall_time": summary["wall_time"]})
        print(f"fig3.8_inertia nz = {slabs}: {rows[-1]['perversions_at_2ms']} perversions "
              f"at 2 ms, {rows[-1]['perversions_at_10ms']} at 10 ms, "
              f"{rows[-1]['perversions']} at the end "
              f"[{rows[-1]['positions']}], KE/SE {rows[-1]['kinetic_ratio']:.2g}, "
              f"{rows[-1]['steps']} steps, {rows[-1]['wall_time']:.0f} s")
    write_csv("fig3.8_inertia", rows)


def mesh_row(name, folder):
    """One run of the mesh comparison: size, time and its split, perversions where the quench
    ended, at the end of leg 1 and back at L, and the events of each leg."""
    steps = table(folder, "steps.csv")
    summary = json.loads((folder / "summary.json").read_text())
    leg = column(steps, "leg").astype(int)
    ends = {k: steps[np.flatnonzero(leg == k)[-1]] for k in (0, 1, 2) if (leg == k).any()}
    kinds = [(leg[e["output"]], e["kind"]) for e in track_events(steps)[1]]
    row = {"run": name, "nz": summary["parameters"]["nz"],
           "num_dofs": summary["num_dofs"], "status": summary["status"],
           "wall_time": summary["wall_time"]}
    row.update({f"time_{part}": t for part, t in summary.get("time_split", {}).items()})
    if 1 in ends:  # the thesis counts ~20 after ~1 % shortening (Fig. 3.8a)
        ends["one_percent"] = nearest([r for r in steps if r["leg"] == "1"], 0.99 * L)
    for k, what in ((0, "quenched"), ("one_percent", "at_1pct"), (1, "leg1_end"),
                    (2, "back_at_L")):
        if k in ends:
            row[f"perversions_{what}"] = int(ends[k]["perversions"])
            row[f"positions_{what}"] = ends[k]["perversion_positions"]
    for k in (1, 2):
        for kind in ("annihilation", "coalescence", "creation"):
            row[f"leg{k}_{kind}"] = kinds.count((k, kind))
    return row


def fig3_9():
    """Stretching back, as Fig. 3.9's caption has it (w = 9 mm, L' = L / 3.5: the prestretched
    strip; its text speaks of the pre-compressed one, whose path ends before, fig3.8): in to
    9 cm, then back out to 30 cm, outputs every 5 mm. At each output the perversions, the
    helices' amplitude (helix_radius: their length-weighted mean radius) and the number of
    helical periods, the frame's turns int |twist| ds / 2 pi (perversions.shape); and the
    states in and out at the same end distance (hysteresis)."""
    end, every = (200, 10) if QUICK else (90, 5)
    folder, _ = run("fig3.9", "w9", *options(w=9, nz=NZ, end_distance=end, return_distance=L,
                                             output_every=every))
    steps = table(folder, "steps.csv")
    lines = by_output(folder, "centreline.csv")
    rows = []
    for r in steps:
        line = lines[int(r["output"])]
        got = pv.shape(np.column_stack([column(line, c) for c in "xyz"]), column(line, "twist"))
        radius = r["helix_radius"]
        rows.append({"leg": int(r["leg"]), "end_distance": float(r["end_distance"]),
                     "perversions": int(r["perversions"]), "positions": r["perversion_positions"],
                     "helix_radius": float(radius) if radius not in ("", "nan", "null") else np.nan,
                     "helical_periods": got["frame_turns"], "shape": got["shape"],
                     "negative_eigenvalues": int(r["negative_eigenvalues"])})
    write_csv("fig3.9", rows)
    write_csv("fig3.9_hysteresis", hysteresis(steps, every),
              ["end_distance", "distance_shift", "perversions_in", "perversions_out",
               "strain_energy_in", "strain_energy_out", "energy_out_minus_in",
               "negative_eigenvalues_in", "negative_eigenvalues_out"])
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    for k, style, label in ((1, "-", "going in"), (2, "--", "stretched back")):
        leg = [r for r in rows if r["leg"] == k]
        d = [r["end_distance"] for r in leg]
        for ax, key in zip(axes, ("perversions", "helical_periods", "helix_radius")):
            # A radius only where the shape is helical (a barely bent strip's fitted circle
            # is hundreds of mm wide)
            ax.plot(d, [r[key] if key != "helix_radius" or r["shape"] == "helix/perversions"
                        else np.nan for r in leg], style, marker=".", label=label)
    for ax, label in zip(axes, ("perversions", "helical periods (frame turns)",
                                "helix radius (mm)")):
        ax.set(xlabel="end distance (mm)", ylabel=label)
        ax.grid(alpha=0.3)
    axes[0].yaxis.set_major_locator(MaxNLocator(integer=True))
    axes[0].legend(fontsize=8)
    fig.suptitle("Fig. 3.9: the strip (w = 9 mm) driven in to 9 cm and stretched back to 30 cm")
    fig.tight_layout()
    save(fig, "fig3.9.png")


# ---------------------------------------------------------------------------------------------
SECTIONS = {"a": ("B 9x3, A 9x3", True), "b": ("B 9x3, S 9x3", True),
            "c": ("B 9x3, S 9x3, B 9x0.2", True), "d": ("B 9x3, S 9x3, B 9x3", False),
            "e": ("B 6x3, A 9x3, B 6x3", False), "f": ("B 9x0.2, S 9x3, B 9x0.2", False)}


def fig3_10():
    """Cross-sections a-f to 15 cm: helix/perversions or V-shape (perversions.shape). At 20 cm
    b and c were still straight and stable (no negative eigenvalue), though linear buckling
    put their first critical end distances at 264 and 249 mm (measured)."""
    panels, end = (("a", "d"), 230) if QUICK else (tuple(SECTIONS), 150)
    rows, strips = [], []
    for panel in panels:
        section, thesis_helix = SECTIONS[panel]
        folder, _ = run("fig3.10", f"{panel}_to{end:g}", *options(
            section=section, nz=NZ_SECTIONS, end_distance=end, output_every=20))
        last = table(folder, "steps.csv")[-1]
        line = by_output(folder, "centreline.csv")[int(last["output"])]
        got = pv.shape(np.column_stack([column(line, c) for c in "xyz"]), column(line, "twist"))
        thesis = "helix/perversions" if thesis_helix else "V-shape"
        rows.append({"panel": panel, "section": section, "thesis": thesis,
                     "thesis_mark": "tick" if thesis_helix else "cross", "gelx": got["shape"],
                     "agrees": got["shape"] == thesis, "frame_turns": got["frame_turns"],
                     "lateral_ratio": got["lateral_ratio"], "lateral": got["lateral"],
                     "perversions": int(last["perversions"]),
                     "negative_eigenvalues": last["negative_eigenvalues"],
                     "end_distance": float(last["end_distance"])})
        print(f"fig3.10 {panel} [{section}]: {got['shape']} (turns {got['frame_turns']:.2f}, "
              f"lateral ratio {got['lateral_ratio']:.2f}); thesis {thesis}")
        series = FieldSeries(folder)
        i = len(series.times) - 1
        x, cells = series.mesh(i)
        strips.append((f"({panel}) {section}: {got['shape']}, thesis {thesis}",
                       x + series.field("displacement", i), cells,
                       series.field("cauchy_stress_vm", i).ravel()))
    write_csv("fig3.10", rows)
    top = max(values.max() for *_, values in strips)
    save(stacked_strips(strips, "von Mises stress (MPa)", Normalize(0, top), plt.cm.jet),
         "fig3.10.png")


# ---------------------------------------------------------------------------------------------
def deflation():
    """Metastable states by deflation at 23.3 cm for w = 5 and 9, with the equilibrium on the
    arc-length branch there, the state reached there on the way back out from 13.9 cm, and
    the path states of fig3.3 (a) at 23.3 cm (OUT/fig3.3.csv, from this sweep or an earlier one with
    the same --quick and --fig3.3-w; its width must be 5 or 9). Two states are one
    equilibrium when their perversions agree in number and to 2 mm in position and their
    energies to 1e-4 relative (a path state after its 0.05 s hold is settled to the kinetic
    ratio's few 1e-3 of the energy change, far below the mJ differences between states)."""
    cases = [(5, THESIS_DISTANCE)] if QUICK else [(5, THESIS_DISTANCE), (9, THESIS_DISTANCE)]
    rows = []
    for w, d in cases:
        folder, _ = run("deflation", f"w{w}_d{d:g}", *options(
            w=w, nz=NZ, end_distance=d, output_every=(L - d) / 4, equilibria=2 if QUICK else 4))
        for e in table(folder, "equilibria.csv"):
            rows.append({"w": w, "end_distance": d, "source": e["origin"],
                         "guess": e["guess"], "strain_energy": float(e["strain_energy"]),
                         "perversions": int(e["perversions"]),
                         "positions": e["perversion_positions"],
                         "negative_eigenvalues": int(e["negative_eigenvalues"]),
                         "distance_to_path_state": e["distance"]})
        # The equilibrium arc-length continuation reaches there: it stays on the branch that
        # continues the straight strip (README, "Arc-length, compared"). Its last point lies
        # up to one arc-length step past d: its energy is taken back to d with dE/dd = F
        arc, _ = run("deflation", f"w{w}_d{d:g}_arclength", *options(
            w=w, nz=NZ, end_distance=d, output_every=(L - d) / 4, method="arclength"))
        last = table(arc, "steps.csv")[-1]
        reached = float(last["end_distance"])
        rows.append({"w": w, "end_distance": d,
                     "source": f"arc-length branch (at {reached:.2f} mm)", "guess": "",
                     "strain_energy": float(last["strain_energy_A"])
                     + float(last["strain_energy_B"]) + float(last["end_force"]) * (d - reached),
                     "perversions": int(last["perversions"]),
                     "positions": last["perversion_positions"],
                     "negative_eigenvalues": int(last["negative_eigenvalues"]),
                     "distance_to_path_state": ""})
        # The strip driven on in to 13.9 cm (the thesis' last distance of Fig. 3.7) and back
        # out to d: the state the way back reaches there (its last output, after the hold)
        back, _ = run("deflation", f"w{w}_back_to_d{d:g}", *options(
            w=w, nz=NZ, end_distance=DEEPEST, return_distance=d, output_every=(L - DEEPEST) / 4))
        last = table(back, "steps.csv")[-1]
        rows.append({"w": w, "end_distance": d,
                     "source": f"path in to {DEEPEST:g} mm, then back out", "guess": "",
                     "strain_energy": float(last["strain_energy_A"])
                     + float(last["strain_energy_B"]),
                     "perversions": int(last["perversions"]),
                     "positions": last["perversion_positions"],
                     "negative_eigenvalues": int(last["negative_eigenvalues"]),
                     "distance_to_path_state": ""})
    loading = args.out / "fig3.3.csv"
    for r in table(args.out, "fig3.3.csv") if loading.exists() and args.fig3_3_w in (5, 9) else []:
        if r["case"] == "a":
            rows.append({"w": args.fig3_3_w, "end_distance": THESIS_DISTANCE,
                         "source": f"path, loading time {float(r['loading_time']):.3g} s",
                         "guess": "", "strain_energy": float(r["strain_energy"]),
                         "perversions": int(r["perversions"]),
                         "positions": r["perversion_positions"],
                         "negative_eigenvalues": int(r["negative_eigenvalues"]),
                         "distance_to_path_state": ""})
    for (w, d) in cases:
        group = [r for r in rows if r["w"] == w and r["end_distance"] == d]
        lowest = min(r["strain_energy"] for r in group)
        distinct = []
        for r in sorted(group, key=lambda r: r["strain_energy"]):
            positions = perversions_of({"perversion_positions": r["positions"]})
            for k, (energy, known) in enumerate(distinct):
                if (len(known) == len(positions) and abs(r["strain_energy"] / energy - 1) < 1e-4
                        and all(abs(a - b) <= 2 for a, b in zip(known, positions))):
                    break
            else:
                k = len(distinct)
                distinct.append((r["strain_energy"], positions))
            r.update(state=k, energy_above_lowest=r["strain_energy"] - lowest,
                     stable=r["negative_eigenvalues"] == 0, lowest=k == 0)
        best = min(group, key=lambda r: r["strain_energy"])
        print(f"deflation w = {w}, {d:g} mm: {len(distinct)} distinct states; the lowest has "
              f"{best['perversions']} perversions ({best['positions']}), found by "
              f"{best['source']}")
    write_csv("deflation", rows)
    fig, axes = plt.subplots(1, len(cases), figsize=(3.5 * len(cases), 4), squeeze=False)
    for ax, (w, d) in zip(axes[0], cases):
        for r in (r for r in rows if r["w"] == w and r["end_distance"] == d):
            path = r["source"].startswith("path")
            ax.plot(r["perversions"], r["energy_above_lowest"], "*" if path else "o", ms=9,
                    mfc=("C1" if path else "C0") if r["stable"] else "none",
                    mec="C1" if path else "C0")
        ax.set(title=f"w = {w} mm, {d:g} mm", xlabel="perversions")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("strain energy above the lowest (mJ)\nfilled: stable; *: path")
    fig.tight_layout()
    save(fig, "deflation.png")


args.out.mkdir(parents=True, exist_ok=True)
chosen = args.studies.split(",")
unknown = set(chosen) - set(STUDIES)
if unknown:
    sys.exit(f"sweep.py: error: unknown studies {sorted(unknown)} (known: {STUDIES})")
failed = []
for study, make in (("fig3.7", fig3_7), ("fig3.3", fig3_3), ("fig3.8", fig3_8),
                    ("fig3.8_inertia", fig3_8_inertia), ("fig3.9", fig3_9),
                    ("fig3.10", fig3_10), ("deflation", deflation)):
    if study not in chosen:
        continue
    try:
        make()
    except subprocess.CalledProcessError as error:  # a failed run: the other studies go on
        print(f"{study}: a run failed ({error}); see its folder under {args.out / 'runs'}")
        failed.append(study)
sys.exit(f"sweep.py: failed studies: {', '.join(failed)}" if failed else 0)
