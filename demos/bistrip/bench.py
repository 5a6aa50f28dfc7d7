"""Work-precision benchmark of the bistrip scene: the critical shortening of mode 1, and the
total strain energy and perversion positions at end distances 200, 150 and 90 mm, against wall
time, over meshes (slabs nz, Q2 hexahedra) and element choices (Q1 hexahedra, which lock in
bending, on the finest Q2 mesh's nodes).

Errors are against the Richardson extrapolation of the three finest Q2 meshes (observed order
from the three; the extrapolation uses the actual ratios of nz). The energy at an end distance
d is interpolated between the two outputs around it (every 5 mm of end travel, each taken at
the first time step past its mark) by the cubic Hermite polynomial with dE/dd = F, the end
force: the outputs of different meshes fall at different d, and E changes by F ~ 20 N per mm.
The perversion positions are those of the output nearest d. Writes bench.csv and prints the
table. Each run is a whole path: 2 to 5 minutes at 2 ranks (15 minutes for the default set,
measured). A run whose folder already holds a completed summary.json is not repeated.

usage: bench.py BUILD_DIR OUTPUT_DIR [--np N] [--nz 40,60,100] [--end_distance 90]
"""
import csv
import json
import os
import pathlib
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from fields import read_table  # noqa: E402  (demos/fields.py)


def option(name, default):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default


build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
ranks = option("--np", "2")
slabs = [int(n) for n in option("--nz", "40,60,100").split(",")]
end_distance = float(option("--end_distance", "90"))
distances = [d for d in (200.0, 150.0, 90.0) if d >= end_distance]
binary = build / "demos" / "bistrip" / "gelx-bistrip"
# (label, options): Q2 on each mesh; Q1 with the Q2 finest mesh's node layers and cross-section
runs = [(f"Q2 nz={n}", ["--nz", str(n)]) for n in slabs]
runs.append((f"Q1 nz={2 * slabs[-1]}",
             ["--degree", "1", "--nz", str(2 * slabs[-1]), "--nx", "4", "--ns", "2", "--nb", "2",
              "--na", "2"]))



def completed(folder):
    summary = folder / "summary.json"
    return summary.exists() and json.loads(summary.read_text())["status"] == "completed"


def energy_at(steps, d):
    """The total strain energy at end distance d, cubic Hermite between the outputs around it
    with the slopes dE/dd = F."""
    for a, b in zip(steps, steps[1:]):
        d0, d1 = float(a["end_distance"]), float(b["end_distance"])
        if d1 <= d <= d0 and d0 > d1:
            E = [float(r["strain_energy_A"]) + float(r["strain_energy_B"]) for r in (a, b)]
            F = [float(r["end_force"]) for r in (a, b)]
            h, t = d0 - d1, (d0 - d) / (d0 - d1)
            # from d0 (t = 0) towards d1 (t = 1): dE/dt = -h F
            return ((2 * t**3 - 3 * t**2 + 1) * E[0] + (t**3 - 2 * t**2 + t) * (-h * F[0])
                    + (-2 * t**3 + 3 * t**2) * E[1] + (t**3 - t**2) * (-h * F[1]))
    return float(steps[-1]["strain_energy_A"]) + float(steps[-1]["strain_energy_B"])


rows = []
for label, options in runs:
    folder = out / label.replace(" ", "_").replace("=", "")
    if not completed(folder):
        subprocess.run(["mpirun", "-np", ranks, str(binary), "--output", str(folder),
                        "--end_distance", str(end_distance), "--output_every", "5"] + options,
                       check=True, stdout=subprocess.DEVNULL,
                       env=dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                                OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1"))
    s = json.loads((folder / "summary.json").read_text())
    steps = read_table(folder / "steps.csv")
    row = {"run": label, "nz": int(options[options.index("--nz") + 1]),
           "num_dofs": s["num_dofs"], "wall_time": s["wall_time"],
           "critical_shortening": s["first_critical_shortening"]}
    for d in distances:
        near = min(steps, key=lambda r: abs(float(r["end_distance"]) - d))
        row[f"energy_{d:g}"] = energy_at(steps, d)
        row[f"perversions_{d:g}"] = near["perversion_positions"]
    rows.append(row)


def richardson(values, nz):
    """Extrapolate q(h) = q + c h^p from three meshes h ~ 1/nz (p from the three)."""
    (q1, q2, q3), (n1, n2, n3) = values, nz
    r12, r23 = n2 / n1, n3 / n2
    if (q2 - q1) * (q3 - q2) <= 0:
        return float("nan"), float("nan")  # not monotone: no asymptotic range yet
    # Solve (q2 - q1) / (q3 - q2) = (1 - r12^-p) / (r12^-p (1 - r23^-p)) for p by bisection
    target = (q2 - q1) / (q3 - q2)
    lo, hi = 0.1, 8.0
    f = lambda p: (1 - r12**-p) / (r12**-p * (1 - r23**-p)) - target  # noqa: E731
    if f(lo) * f(hi) > 0:
        return float("nan"), float("nan")
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(lo) * f(mid) > 0 else (lo, mid)
    p = 0.5 * (lo + hi)
    return q3 + (q3 - q2) / (r23**p - 1), p


q2_rows = [r for r in rows if r["run"].startswith("Q2")][-3:]
quantities = ["critical_shortening"] + [f"energy_{d:g}" for d in distances]
reference = {}
if len(q2_rows) == 3:
    for q in quantities:
        reference[q], order = richardson([r[q] for r in q2_rows], [r["nz"] for r in q2_rows])
        print(f"{q}: Richardson extrapolation {reference[q]:.8g} (observed order {order:.2f})")
for r in rows:
    for q in quantities:
        r[f"{q}_error"] = abs(r[q] / reference[q] - 1) if q in reference else float("nan")

out.mkdir(parents=True, exist_ok=True)
with open(out / "bench.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
print(f"bistrip work-precision ({ranks} ranks), errors against the extrapolation:")
for r in rows:
    errors = "  ".join(f"{q} {r[q]:.6g} ({r[q + '_error']:.1e})" for q in quantities)
    print(f"{r['run']:>12} {r['num_dofs']:7d} dofs {r['wall_time']:8.1f} s  {errors}")
    print(" " * 13 + "perversions: " + ", ".join(f"{d:g} mm: [{r[f'perversions_{d:g}']}]"
                                                 for d in distances))
