"""Check a run of gelx-buckling-dynamics (the imperfect column loaded through its bifurcation by
damped quasi-static dynamics) against Euler and the elastica, both computed here from the run's
parameters (closed_forms.euler_load, closed_forms.elastica_load_ratio), and its energies:

- the linear buckling load against pi^2 EI/(KL)^2 within 2% (as tests/post_buckling.py);
- the final state on the elastica: the measured axial force over the linear buckling load
  against the elastica's P/P_cr at the final d/L, within 1% (the issue's bound; the 3-D column
  differs from the inextensible elastica by O(P/(EA)) = 3.7e-3 clamped-clamped, measured 5.0e-3
  with the imperfection's effect, tests/damped_dynamics.cpp);
- steps.csv holds every accepted step, in increasing time, up to the end time the run's options
  set (loading + hold time);
- quasi-static: ED/SE at the last row (the first-order flow's criterion) and the largest KE/SE
  over the rows, both recomputed from the energy columns, within the bounds of the run's options
  (or the library's default 0.05), and the summary's verdict agrees;
- with --method inertia, the energy history: the supports' work W against the work of the
  measured axial force over the prescribed shortening, int P d(delta) (trapezoidal over the
  rows, as W is; P the reaction at the fixed end, W's from the moved end's reactions, which
  differ by the column's axial inertia: 1e-3, measured 1.5e-4), and the balance residual
  W - dSE - dKE - ED, recomputed here from the energy columns, within 1e-3 of W (generalised-alpha's
  numerical dissipation at rho_inf = 0.8 on a motion its steps resolve; measured 1.9e-5).

usage: buckling_dynamics.py OUTPUT_DIR
"""
import json
import pathlib
import sys

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)
from closed_forms import elastica_load_ratio, euler_load  # noqa: E402  (demos/closed_forms.py)

out = pathlib.Path(sys.argv[1])
s = json.loads((out / "summary.json").read_text())
p, dyn = s["parameters"], s["dynamics"]
rows = read_table(out / "steps.csv")
checks = Checks()

P_cr = s["critical_load"]
checks.relative("linear buckling load against Euler's", P_cr, euler_load(p), 0.02)

last = rows[-1]
d = float(last["deflection_over_L"])
checks.relative(f"final state: P/P_cr at d/L = {d:.5f} against the elastica",
                float(last["axial_force_over_critical"]), elastica_load_ratio(d, p["ends"]), 0.01)

# The run's end time and the bounds from the options it ran with (summary.json's record of
# the options database, the scene's defaults included), not from what the run says of itself;
# a bound the run did not set is the library's default, 0.05 (dynamics.h, inertia.h)
prefix = "inertial_" if p["method"] == "inertia" else "dynamics_"
options = s["petsc_options"]
end_time = float(options[prefix + "loading_time"]) + float(options[prefix + "hold_time"])
kinetic_bound = float(options.get(prefix + "kinetic_bound", 0.05))
dissipation_bound = float(options.get(prefix + "dissipation_bound", 0.05))
times = [float(r["time"]) for r in rows]
checks.require(f"{len(rows)} rows, one per accepted step ({dyn['steps']})",
               len(rows) == dyn["steps"] and all(a < b for a, b in zip(times, times[1:])))
checks.relative("last row at the end time, loading + hold", times[-1], end_time, 1e-12)

dissipation = float(last["dissipated_energy"]) / float(last["strain_energy"])
kinetic = max(float(r["kinetic_energy"]) / float(r["strain_energy"]) for r in rows
              if float(r["strain_energy"]) > 0)
if p["method"] == "dynamics":
    checks.require(f"ED/SE = {dissipation:.3e} <= {dissipation_bound}",
                   dissipation <= dissipation_bound)
checks.require(f"largest KE/SE = {kinetic:.3e} <= {kinetic_bound}", kinetic <= kinetic_bound)
checks.require(f"verdict {dyn['verdict']!r}", dyn["verdict"] == "quasi-static")

if p["method"] == "inertia":
    E = 2 * p["G"] * (1 + p["nu"])
    shortening_per_euler_load = s["euler_load"] * p["L"] / (E * p["tx"] * p["ty"])
    work, previous = 0.0, (0.0, 0.0)
    for r in rows:
        delta = float(r["amplitude"]) * p["load"] * shortening_per_euler_load
        force = float(r["axial_force_over_critical"]) * P_cr
        work += 0.5 * (force + previous[1]) * (delta - previous[0])
        previous = (delta, force)
    W = float(last["external_work"])
    checks.relative("supports' work W against int P d(delta) of the axial force", W, work, 1e-3)
    # The run starts at rest in the seeded, stress-free geometry: SE0 = KE0 = 0
    balance = W - float(last["strain_energy"]) - float(last["kinetic_energy"]) \
        - float(last["dissipated_energy"])
    checks.absolute("balance residual over W (numerical dissipation and error)", balance / W,
                    0.0, 1e-3)
checks.finish()
