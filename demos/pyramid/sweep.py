"""Parameter studies of the pyramid scene (thesis Figs. 2.5a, 2.6 and the size and constitutive
checks of §2.3): runs the scene over the array period W, the base thickness t, the pyramid size
L (W and t scaled with it) and the law, and plots l_c/L against d/H and against f^(1/2).

usage: sweep.py BUILD_DIR OUTPUT_DIR [scene options, e.g. --order 2 --cells 2]
Results: OUTPUT_DIR/<study>.png, OUTPUT_DIR/sweep.csv and one scene folder per case (named
after its parameters; a folder that holds a completed run is reused, so an interrupted sweep
resumes where it stopped).
"""
import csv
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from fields import read_table  # noqa: E402  (demos/fields.py)
from studies import run_scene  # noqa: E402  (demos/studies.py)

build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
scene_options = sys.argv[3:]
L = 8.0  # um, the thesis' pyramid
# The reference case (the scene's defaults, spelled out so that equal cases are run once)
REFERENCE = {"L": L, "W": 8 * L, "t": 4 * L, "law": "nh"}
# study: (figure title, [(label, scene parameters)])
STUDIES = {
    "fig2_5a_period": ("array period W (t = 4L)",
                       [(f"W = {r:g} L", {"W": r * L}) for r in (1.5, 2, 4, 8)]),
    "fig2_6_thickness": ("base thickness t (W = 8L)",
                         [(f"t = {r:g} L", {"t": r * L}) for r in (0.5, 1, 2, 4)]),
    "size": ("pyramid size L (W = 8L, t = 4L)",
             [(f"L = {s:g} um", {"L": s, "W": 8 * s, "t": 4 * s}) for s in (8, 16, 32)]),
    "laws": ("constitutive law", [("neo-Hookean", {"law": "nh"}),
                                  ("Mooney-Rivlin, C01 = C10", {"law": "mr"}),
                                  ("linear elastic", {"law": "le"})]),
}


def run(study, label, parameters):
    parameters = {**REFERENCE, **parameters}
    folder = out / "_".join(f"{k}_{v}" if isinstance(v, str) else f"{k}{v:g}"
                            for k, v in sorted(parameters.items()))
    args = [a for k, v in parameters.items() for a in (f"--{k}", str(v))]
    summary = run_scene(build, "pyramid", folder, 2,
                        ["--extrapolate", "false", *scene_options, *args], reuse=True)
    rows = read_table(folder / "steps.csv")
    return {"study": study, "label": label, "folder": folder.name,
            "d": np.array([float(r["d_over_H"]) for r in rows]),
            "lc": np.array([float(r["contact_width_over_L"]) for r in rows]),
            "f": np.array([float(r["force"]) for r in rows]),
            "summary": summary}


out.mkdir(parents=True, exist_ok=True)
table = []
for study, (title, cases) in STUDIES.items():
    results = [run(study, label, parameters) for label, parameters in cases]
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for r in results:
        s = r["summary"]
        left.plot(r["d"], r["lc"], "o-", ms=3, label=r["label"])
        right.plot(np.sqrt(r["f"]), r["lc"], "o-", ms=3,
                   label=f"{r['label']}: R² {s['r2_lc_vs_sqrtf']:.4f}")
        at = {x: float(np.interp(x, r["d"], r["lc"])) for x in (0.3, 0.5, 0.8)}
        table.append({"study": study, "case": r["label"], "folder": r["folder"],
                      "slope_lc_vs_d": s["slope_lc_vs_d"], "r2_lc_vs_d": s["r2_lc_vs_d"],
                      "r2_lc_vs_sqrtf": s["r2_lc_vs_sqrtf"], "area_ratio": s["area_ratio"],
                      "lc_at_0.3": at[0.3], "lc_at_0.5": at[0.5], "lc_at_0.8": at[0.8],
                      "final_d_over_H": s["final_d_over_H"], "final_force": s["final_force"],
                      "wall_time": s["wall_time"], "status": s["status"]})
    d = np.linspace(0, 0.8, 2)
    left.plot(d, 0.86 * d, "k--", label="thesis, Eq. 2.1: 0.86 d/H")
    left.set_xlabel("d / H")
    left.set_ylabel("l_c / L")
    left.set_title(f"contact width against indentation: {title}")
    right.set_xlabel("f^(1/2) (uN^(1/2), G = 1 MPa)")
    right.set_ylabel("l_c / L")
    right.set_title("contact width against f^(1/2)")
    for ax in (left, right):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / f"{study}.png", dpi=120)

with open(out / "sweep.csv", "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(table[0]))
    writer.writeheader()
    writer.writerows(table)
print("| study | case | slope | R² (d) | R² (f^1/2) | A_c/l_c² | l_c/L at 0.3, 0.5, 0.8 | "
      "wall time (s) |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for r in table:
    print(f"| {r['study']} | {r['case']} | {r['slope_lc_vs_d']:.3f} | {r['r2_lc_vs_d']:.4f} | "
          f"{r['r2_lc_vs_sqrtf']:.4f} | {r['area_ratio']:.3f} | {r['lc_at_0.3']:.3f}, "
          f"{r['lc_at_0.5']:.3f}, {r['lc_at_0.8']:.3f} | {r['wall_time']:.0f} |")
print(f"wrote {out}/*.png and {out / 'sweep.csv'}")
