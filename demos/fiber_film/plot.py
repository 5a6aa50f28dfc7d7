"""Plot of a fiber_film run: the film's contraction in time after the temperature step, the
in-plane contraction ratios alpha_par (along the fibers) and alpha_perp (across) and the
swelling ratio V/V0 against log t with their final values, and the solvent's chemical
potential in the mid-plane over its undrained value phi_i^2 (chi_f - chi_i) (it rises above
it before it falls: the Mandel-Cryer effect). Prints t50 and t95, the times at which alpha_perp
has covered 50 % and 95 % of its change. Usage: /usr/bin/python3 demos/fiber_film/plot.py
OUTPUT_DIR (writes contraction.png)."""
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
p = summary["parameters"]
t = steps["time"][1:]  # the first row is the reference state at t = 0


def time_to(fraction, column):
    """First time (interpolated in log t) at which `column` covers `fraction` of its change."""
    values = steps[column][1:]
    covered = (values - 1) / (values[-1] - 1)
    k = int(np.argmax(covered >= fraction))
    if k == 0:
        return t[0]
    s = (fraction - covered[k - 1]) / (covered[k] - covered[k - 1])
    return float(np.exp(np.log(t[k - 1]) + s * (np.log(t[k]) - np.log(t[k - 1]))))


t50, t95 = time_to(0.5, "alpha_perp"), time_to(0.95, "alpha_perp")
chi = [summary["chi_A"] + summary["chi_B"] * T for T in (p["T_i"], p["T_f"])]
undrained = summary["phi_i"] ** 2 * (chi[1] - chi[0])

fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
for column, style, label in (("alpha_par", "b", "alpha_par (along the fibers)"),
                             ("alpha_perp", "r", "alpha_perp (across)"),
                             ("swelling_ratio", "k", "V/V0 of the gel")):
    ax.semilogx(t, steps[column][1:], style + ".-", ms=3, label=label)
    ax.axhline(steps[column][-1], color=style, ls=":", lw=0.8)
for time, name in ((t50, "t50"), (t95, "t95")):
    ax.axvline(time, color="gray", ls="--", lw=0.8)
    ax.text(time, ax.get_ylim()[0], f" {name} = {time:.3g} s", rotation=90, va="bottom",
            fontsize=8)
ax.set_xlabel("t [s]")
ax.set_ylabel("contraction ratio")
ax.set_title(f"d = {p['d']:g}, l = {p['l']:g}, L = {p['L']:g}, D = {p['D']:g} nm; "
             f"alpha0 = {p['alpha0']:g}", fontsize=9)
ax.legend(fontsize=8)
bx.semilogx(t, steps["mu_midplane"][1:] / undrained, "g.-", ms=3)
bx.axhline(1, color="k", ls=":", lw=0.8)
bx.set_xlabel("t [s]")
bx.set_ylabel("mu in the mid-plane / phi_i^2 (chi_f - chi_i)")
bx.set_title("the core's solvent: undrained, then drained", fontsize=9)
fig.tight_layout()
fig.savefig(out / "contraction.png", dpi=120)
print(f"t50 = {t50:.4g} s, t95 = {t95:.4g} s (alpha_perp); plot: {out / 'contraction.png'}")
