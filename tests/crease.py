"""Check the crease scene (demos/crease: a bonded gel layer, swollen by lowering chi, folds at
its surface) against what holds whatever the fold's details:

1. The far field. At x = W, away from the dip at x = 0, the layer is the homogeneous bonded
   layer: held laterally at the reference stretch, stretched by l through its thickness, in
   pure solvent (mu = 0) at every chi, so dU/dl = 0 for the energy the form file writes in
   principal stretches (thesis Eq. 4.28; tests/swelling_layer.py)
       U(l) = n/2 phi0 (phi0^(-2/3) (2 + l^2) - 3 - ln(l / phi0)) + (l - phi0) ln(1 - phi0/l)
              + chi phi0 (1 - phi0/l),
   solved here by bisection at each point's chi. Q2 represents the homogeneous state exactly;
   what remains is the dip's reach to x = W = H, which grows with the valley's depth. While
   the surface is nearly flat (the valley at most twice the dip's depth), h/H within 1e-4 of
   l (measured worst 1.41e-5 on the test's 12 x 6 cells).
2. The limit point: the path turns back in chi where the tangent becomes singular, so the
   first negative eigenvalue of the tangent (its inertia) appears within one step of the
   first limit point (a regular limit point; a bifurcation would show an eigenvalue crossing
   without the turn).
3. The fold: at the limit point the valley is at least 10 times deeper than the dip it
   started from (the surface folds there: the path's turn is the crease snapping in, not a
   homogeneous softening, which would move the valley with the far field), and beyond it
   the flanks meet the plane x = 0 (self-contact) at a lower swelling ratio than the onset
   (the snap-back of a subcritical instability: a creased state exists below the swelling
   ratio at which the flat, imperfect surface loses it). The surface's contact with that
   plane keeps every point of the path off it (fold_gap >= -1e-9 H: the rows of a node held
   on the plane are solved to Newton's tolerance), and the path ends where they touch
   (fold_gap <= 1e-6 H, the scene's test). Without the contact the path steps through the
   plane (measured: -3.0e-5 H at the last point); with it but without the arc-length's
   restoring of the contact's active set after a failed attempt (gelx::CompletedPoint), no
   attempt after the first that touches converges and the run fails.
4. summary.json's time split: no part negative (the continuation's solves with the wrapped
   tangent, nested in the bordered system's, counted once: before, "other" was -1.6 s), and
   every evaluation of the continuation counted where it belongs: "other" (set-up, the
   scene's probes, the step control) at most 5 % of the wall time (measured 0.71 %; 11 % with
   the predictor's tangent and load derivative, assembled outside any SNES, left untimed).

usage: crease.py GELX_CREASE WORK_DIR [MPIEXEC NP]
"""
import json
import math
import pathlib
import subprocess
import sys

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)

binary, work = sys.argv[1], pathlib.Path(sys.argv[2])
launcher = [sys.argv[3], "-np", sys.argv[4]] if len(sys.argv) > 4 else []
checks = Checks()
N_NU, LAMBDA0, IMPERFECTION = 1e-3, 1.2, 1e-3
PHI0 = LAMBDA0**-3


def stress(l, chi):
    """dU/dl in closed form."""
    return (N_NU / 2 * PHI0 * (2 * PHI0**(-2 / 3) * l - 1 / l) + math.log(1 - PHI0 / l)
            + PHI0 / l + chi * PHI0**2 / l**2)


def bonded_stretch(chi):
    lo, hi = 1.0 + 1e-12, 50.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if stress(lo, chi) * stress(mid, chi) <= 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


folder = work / "crease"
subprocess.run(launcher + [binary, "--output", str(folder), "--nx", "12", "--nz", "6",
                           "--n", str(N_NU), "--lambda0", str(LAMBDA0),
                           "--imperfection", str(IMPERFECTION)],
               check=True, stdout=subprocess.DEVNULL)
rows = read_table(folder / "steps.csv")
summary = json.loads((folder / "summary.json").read_text())

# 1. The far field before the fold
checks.absolute("stress-free reference: dU/dl at l = 1, chi0", stress(1.0, summary["chi0"]),
                0.0, 1e-12)
flat = [r for r in rows if float(r["valley_depth"]) <= 2 * IMPERFECTION]
worst = max(abs(float(r["swelling_ratio"]) - bonded_stretch(float(r["chi"])))
            / bonded_stretch(float(r["chi"])) for r in flat)
checks.require(f"far field h/H against the bonded layer's l(chi) at the {len(flat)} points "
               f"of a nearly flat surface (h/H up to "
               f"{float(flat[-1]['swelling_ratio']):.4g}): worst relative error {worst:.2e} "
               f"(tol 1e-4)", len(flat) >= 5 and worst <= 1e-4)
limit = next((i for i, r in enumerate(rows) if r["limit_point"] == "true"), None)
checks.require("the path has a limit point (the fold snaps in)", limit is not None)
if limit is None:
    checks.finish()

# 2. The limit point against the inertia
unstable = next((i for i, r in enumerate(rows) if int(r["negative_eigenvalues"]) > 0), None)
checks.require(f"first negative eigenvalue at point {unstable and unstable + 1}, first limit "
               f"point at {limit + 1}: within one step",
               unstable is not None and abs(unstable - limit) <= 1)

# 3. The fold
onset = rows[limit]
checks.require(f"valley depth at the limit point {float(onset['valley_depth']):.4g} H >= 10 "
               f"times the dip {IMPERFECTION:g} H",
               float(onset["valley_depth"]) >= 10 * IMPERFECTION)
contact = summary.get("self_contact", {}).get("swelling_ratio", math.inf)
checks.require(f"the flanks meet the plane x = 0 at h/H = {contact:.4g}, below the onset's "
               f"{float(onset['swelling_ratio']):.4g}",
               contact < float(onset["swelling_ratio"]))
gaps = [float(r["fold_gap"]) for r in rows]
checks.require(f"no point of the path through the plane x = 0: smallest fold_gap "
               f"{min(gaps):.2e} H (at least -1e-9 H)", min(gaps) >= -1e-9)
checks.require(f"the path ends where the flanks touch: fold_gap {gaps[-1]:.2e} H (at most "
               f"1e-6 H)", gaps[-1] <= 1e-6)
checks.time_split(summary)
other = summary["time_split"]["other"] / summary["wall_time"]
checks.require(f"'other' is {100 * other:.2g} % of the wall time (at most 5 %)", other <= 0.05)
print(f"onset: chi = {float(onset['chi']):.6g}, h/H = {float(onset['swelling_ratio']):.6g}")
checks.finish()
