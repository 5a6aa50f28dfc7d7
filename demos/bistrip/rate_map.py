"""The perversion count at 23.3 cm against the dimensionless rate at which the loading passes the
first bifurcation, for the equation of motion and for the first-order flow (issue #29;
README "Rate study", "The dimensionless rate").

The end shortening follows the smooth step s(t/T) = 10 x^3 - 15 x^4 + 6 x^5 over the loading
time T, from L = 300 mm to 233 mm (travel D = 67 mm). It passes the first critical shortening
D_c at the speed v_c = (D / T) s'(x_c), s(x_c) = D_c / D. Past it mode 1 grows; with the
linear-buckling law omega^2 = omega_1^2 (1 - shortening / D_c) its rate is
omega_1 sqrt(v_c t / D_c) with inertia and omega_1^2 v_c t / (D_c c) in the flow c M u' + R = 0,
so the passage is slow or fast against the mode by
    eps = v_c / (D_c omega_1)            (inertia)
    eps = v_c c / (D_c omega_1^2)         (flow)
(the time to pass D_c over the mode's own time, 1 / omega_1 or c / omega_1^2, inverted). omega_1
and D_c are measured on the scene's 40 Q2 slabs: the bonded strip's first free vibration has a
period of 0.0206 s (SLEPc) and its first critical shortening is 25.99 mm (bistrip_coarse).

The counts are those of the README's runs (each row there gives its command); a run's count is
one sample where several perversions form (the seed, the step and the mesh change it).

usage: rate_map.py OUT_DIR     (writes rate_map.png and rate_map.csv)
"""
import csv
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

OMEGA_1 = 2 * math.pi / 0.0206  # rad/s, the bonded strip's first free vibration (40 slabs)
D_C = 25.99                     # mm, the first critical shortening (40 slabs)
TRAVEL = 300.0 - 233.0          # mm

# (model, loading time T in s, damping c in 1/s (flow), variant, perversions at 23.3 cm),
# w = 5 mm, 40 slabs, mode 1 seeded at 0.01 mm; README "With inertia" and "Rate study"
RUNS = [
    ("inertia", 1.0, None, "1 ms", [1]),
    ("inertia", 1.0, None, "0.5 ms", [1]),
    ("inertia", 1.0, None, "noise, seeds 1 and 2", [2, 1]),
    ("inertia", 0.7, None, "1 ms", [3]),
    ("inertia", 0.7, None, "0.5 ms", [1]),
    ("inertia", 0.5, None, "1 ms", [3]),
    ("inertia", 0.3, None, "1 ms, 0.5 ms, 80 slabs", [3, 3, 3]),
    ("inertia", 0.3, None, "noise, seeds 1, 2, 3", [2, 2, 3]),
    ("inertia", 0.1, None, "1 ms", [3]),
    ("flow", 1.0, 1.0, "symmetric seed; noise seed 1", [1, 1]),
    ("flow", 0.3, 3.0, "default tolerances", [1]),
    ("flow", 0.3, 10.0, "default tolerances", [1]),
    ("flow", 0.3, 30.0, "default tolerances", [3]),
    ("flow", 1.0, 100.0, "default tolerances", [3]),
    ("flow", 0.3, 60.0, "default tolerances", [3]),
    ("flow", 1.0, 300.0, "default tolerances", [3]),
    ("flow", 0.3, 100.0, "default tolerances", [3]),
    ("flow", 0.3, 1000.0, "default and ten times tighter tolerances", [4, 5]),
    ("flow", 1.0, 1000.0, "default tolerances", [3]),
]


def smooth_step(x):
    return 10 * x**3 - 15 * x**4 + 6 * x**5


def passage_speed(T):
    """The end's speed (mm/s) when the shortening reaches D_C on the smooth step over T"""
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if smooth_step(mid) < D_C / TRAVEL else (lo, mid)
    return TRAVEL / T * 30 * lo**2 * (1 - lo)**2


def rate(model, T, c):
    v = passage_speed(T)
    return v / (D_C * OMEGA_1) if model == "inertia" else v * c / (D_C * OMEGA_1**2)


out = pathlib.Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
rows = []
for model, T, c, variant, counts in RUNS:
    eps = rate(model, T, c)
    rows.append({"model": model, "loading_time": T, "damping": c or "", "variant": variant,
                 "passage_speed": passage_speed(T), "rate": eps,
                 "perversions": " ".join(str(n) for n in counts)})
with open(out / "rate_map.csv", "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
for r in rows:
    print(f"{r['model']:8s} T = {r['loading_time']:4.2f} s  c = {str(r['damping']):7s} "
          f"v_c = {r['passage_speed']:7.1f} mm/s  eps = {r['rate']:.3g}  "
          f"perversions {r['perversions']:8s} ({r['variant']})")

fig, ax = plt.subplots(figsize=(6.4, 4))
for model, marker, colour in (("inertia", "o", "tab:blue"), ("flow", "s", "tab:red")):
    first = True
    for r in rows:
        if r["model"] != model:
            continue
        counts = [int(n) for n in r["perversions"].split()]
        ax.scatter([r["rate"]] * len(counts), counts, marker=marker, color=colour, alpha=0.6,
                   label=("equation of motion" if model == "inertia" else "first-order flow")
                   if first else None)
        first = False
ax.set_xscale("log")
ax.set_xlabel(r"passage rate $\varepsilon$ ($v_c/(\Delta_c\omega_1)$; flow: $v_c c/(\Delta_c\omega_1^2)$)")
ax.set_ylabel("perversions at 23.3 cm")
ax.set_yticks(range(0, 6))
ax.set_title("bistrip, w = 5 mm, 40 slabs, mode 1 seeded")
ax.grid(True, which="both", alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(out / "rate_map.png", dpi=120)
print(f"wrote {out / 'rate_map.png'}, {out / 'rate_map.csv'}")
