"""Cost of the swelling transient: the free cube (the eighth of a 2 mm cube, chi = 0.4, in pure
solvent from lambda0 = 1.5: it swells 5.45-fold) followed past 95 % of its uptake, on
meshes of 2 to 8 Q2-Q1 hexahedra an edge, with MUMPS; and the fieldsplit linear solver's
Krylov iterations per Newton iteration on the first 100 s, its Schur complement preconditioned
by PETSc's selfp and by the fixed-stress operator of forms/swelling.py (user).

Per mesh: unknowns, time steps the adaptive BDF2 takes to 3e6 s, Newton iterations, wall time
and its split, and t95, the time to 95 % of the volume change (V/V0 against a^3 of the
isotropic energy), whose change from mesh to mesh is the mesh's error in it. Then the cost of
the transient to 95 % uptake (its steps' wall time and Newton iterations up to the step that
passes t95) against the equilibrium solve of the same gel (--path equilibrium: the swollen
state by load steps in mu, its steps' wall time), both without the setup. Then, on 3 cells,
the time integrator's accuracy against its cost: BDF of order 2 and 4, TS tolerances rtol
1e-4 and 1e-3, each step's Newton solve to 1e-3 of its first residual (the default), to
PETSc's 1e-8, a single linear solve (the linearly implicit BDF; a run that stops says why),
or stopped by CVODE's test on the correction (-swelling_newton_test correction; also at order
3 and rtol 3e-3); the error is the largest difference of the uptake at the steps from that of
a reference run (order 3, rtol 1e-6), interpolated monotonically in log t, as a fraction of
the final uptake. Writes bench.csv.

usage: bench.py BUILD_DIR OUTPUT_DIR
"""
import csv
import json
import os
import pathlib
import subprocess
import sys

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from fields import read_table  # noqa: E402  (demos/fields.py)

build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
binary = build / "demos" / "swelling" / "gelx-swelling"
N_NU, LAMBDA0, CHI = 1e-3, 1.5, 0.4
PHI0 = LAMBDA0**-3
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def isotropic_energy(a):
    return (N_NU / 2 * PHI0 * (3 * PHI0**(-2 / 3) * a * a - 3 - np.log(a**3 / PHI0))
            + (a**3 - PHI0) * np.log(1 - PHI0 / a**3) + CHI * PHI0 * (1 - PHI0 / a**3))


a = brentq(lambda a: (isotropic_energy(a + 1e-6) - isotropic_energy(a - 1e-6)) / 2e-6,
           1 + 1e-6, 5.0, xtol=1e-15)


def run(name, cells, end_time, *options, may_fail=False):
    """A run's summary and steps; with may_fail a run that stops early returns them too (its
    summary's status says why)."""
    folder = out / name
    subprocess.run([str(binary), "--output", str(folder), "--sides", "free", "--W", "1",
                    "--nx", str(cells), "--nz", str(cells), "--chi", str(CHI), "--end_time",
                    str(end_time), "--outputs", "1", "--checkpoint_every", "0", *options],
                   check=not may_fail, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   env=env)
    steps = read_table(folder / "steps.csv")
    return json.loads((folder / "summary.json").read_text()), steps


def uptake_history(steps):
    """Times and uptake (V - V0 as a fraction of the equilibrium's) of a run's steps."""
    t = np.array([float(r["time"]) for r in steps])
    return t, (np.array([float(r["swelling_ratio"]) for r in steps]) - 1) / (a**3 - 1)


rows = []
for cells in (2, 3, 4, 6, 8):
    summary, steps = run(f"cube_{cells}", cells, 3e6)
    t, uptake = uptake_history(steps)
    split = summary["time_split"]
    to_t95 = np.searchsorted(uptake, 0.95) + 1  # the steps up to the one that passes t95
    eq_summary, eq_steps = run(f"equilibrium_{cells}", cells, 1, "--path", "equilibrium")
    eq_wall = sum(float(r["wall_time"]) for r in eq_steps)
    rows.append({"cells": cells, "num_dofs": summary["num_dofs"], "steps": summary["steps"],
                 "newton_iterations": summary["newton_iterations"],
                 "wall_time": summary["wall_time"], "assembly": split["assembly"],
                 "solve": split["solve"], "t95": float(np.interp(0.95, uptake, t)),
                 "final_uptake": uptake[-1],
                 "newton_to_t95": sum(int(r["newton_iterations"]) for r in steps[:to_t95]),
                 "wall_to_t95": sum(float(r["wall_time"]) for r in steps[:to_t95]),
                 "equilibrium_newton": eq_summary["newton_iterations"],
                 "equilibrium_wall": eq_wall,
                 "equilibrium_swelling_ratio": eq_summary["swelling_ratio"]})

split_rows = []
for schur in ("selfp", "user"):
    for cells in (2, 3, 4):
        summary, steps = run(f"fieldsplit_{schur}_{cells}", cells, 100, "-swelling_linear_solver",
                             "fieldsplit", "-swelling_fieldsplit_u_pc_type", "lu",
                             "-swelling_fieldsplit_p_pc_type", "hypre",
                             "-swelling_pc_fieldsplit_schur_precondition", schur)
        newton = sum(int(r["newton_iterations"]) for r in steps)
        split_rows.append({"schur": schur, "cells": cells, "num_dofs": summary["num_dofs"],
                           "krylov_per_newton": sum(int(r["linear_iterations"]) for r in steps)
                           / newton, "wall_time": summary["wall_time"]})


# TS's atol as the scene sets it, rtol |mu - mu0| (mu = 0, pure solvent)
atol_per_rtol = abs(json.loads((out / "cube_2" / "summary.json").read_text())["mu0"])
_, reference_steps = run("integrator_reference", 3, 3e6, "-swelling_ts_bdf_order", "3",
                         "-swelling_ts_rtol", "1e-6", "-swelling_ts_atol",
                         str(1e-6 * atol_per_rtol))
t_ref, uptake_ref = uptake_history(reference_steps)
reference = PchipInterpolator(np.log(t_ref), uptake_ref)
# Each step's nonlinear solve: Newton to 1e-3 of its first residual (the default), to PETSc's
# 1e-8, one linear solve from TS's predictor (SNES ksponly: the linearly implicit BDF, whose
# linearisation error is the square of the predictor's; no line search keeps J > phi0), or
# Newton stopped by CVODE's test on the correction against TS's tolerance (gelx::TransientProblem)
newton_options = {"1e-3": ["-swelling_snes_rtol", "1e-3"], "1e-8": ["-swelling_snes_rtol", "1e-8"],
                  "one": ["-swelling_snes_type", "ksponly"],
                  "correction": ["-swelling_newton_test", "correction"]}
cases = ([(order, rtol, newton) for order in (2, 4) for rtol in (1e-4, 1e-3)
          for newton in newton_options] + [(2, 3e-3, "one")]
         + [(order, rtol, "correction") for order, rtol in ((2, 3e-3), (3, 1e-3), (3, 3e-3),
                                                             (4, 3e-3))])
integrator_rows = []
for order, rtol, newton in cases:
    name = f"integrator_bdf{order}_rtol{rtol:g}_newton{newton}"
    summary, steps = run(name, 3, 3e6, "-swelling_ts_bdf_order", str(order), "-swelling_ts_rtol",
                         str(rtol), "-swelling_ts_atol", str(rtol * atol_per_rtol),
                         *newton_options[newton], may_fail=True)
    row = {"order": order, "rtol": rtol, "newton": newton, "status": summary["status"]}
    if summary["status"] == "completed":
        t, uptake = uptake_history(steps)
        inside = (t > t_ref[0]) & (t <= t_ref[-1])
        to_t95 = np.searchsorted(uptake, 0.95) + 1
        row.update({"steps_to_t95": int(to_t95),
                    "newton_to_t95": sum(int(r["newton_iterations"]) for r in steps[:to_t95]),
                    "wall_to_t95": sum(float(r["wall_time"]) for r in steps[:to_t95]),
                    "uptake_error": float(np.max(np.abs(uptake[inside]
                                                        - reference(np.log(t[inside])))))})
    integrator_rows.append(row)

out.mkdir(parents=True, exist_ok=True)
with open(out / "bench.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
print(f"swelling: the free cube to 3e6 s, MUMPS, 1 rank (a^3 = {a**3:.4f})")
print("cells   dofs  steps  newton  wall [s]  assembly  solve   t95 [s]    uptake at end")
for r in rows:
    print(f"{r['cells']:5d} {r['num_dofs']:6d} {r['steps']:6d} {r['newton_iterations']:7d} "
          f"{r['wall_time']:9.1f} {r['assembly']:9.1f} {r['solve']:6.1f} {r['t95']:10.4g} "
          f"{r['final_uptake']:10.4f}")
print("the transient to 95 % uptake against the equilibrium solve of the same gel:")
print("cells  newton to t95  wall to t95 [s]  equilibrium: newton  wall [s]  V/V0   ratio")
for r in rows:
    print(f"{r['cells']:5d} {r['newton_to_t95']:14d} {r['wall_to_t95']:16.2f} "
          f"{r['equilibrium_newton']:20d} {r['equilibrium_wall']:9.2f} "
          f"{r['equilibrium_swelling_ratio']:.4f} {r['wall_to_t95'] / r['equilibrium_wall']:6.1f}")
print("fieldsplit (LU on u, BoomerAMG on the Schur complement's preconditioner: selfp, or the "
      "fixed-stress operator, user), first 100 s:")
for r in split_rows:
    print(f"{r['schur']:>6} {r['cells']:5d} {r['num_dofs']:6d}  {r['krylov_per_newton']:.1f} "
          f"Krylov iterations per Newton iteration, {r['wall_time']:.1f} s")
print("the time integrator on 3 cells, to t95 (uptake error: largest, of the final uptake, "
      "against order 3 at rtol 1e-6; the cost against the equilibrium solve on 3 cells):")
equilibrium_wall = next(r["equilibrium_wall"] for r in rows if r["cells"] == 3)
print("order   rtol      newton  steps  newton  wall [s]  uptake error  / equilibrium")
for r in integrator_rows:
    head = f"{r['order']:5d} {r['rtol']:6g} {r['newton']:>11}"
    if r["status"] != "completed":
        print(f"{head}  {r['status']}")
        continue
    print(f"{head} {r['steps_to_t95']:6d} {r['newton_to_t95']:7d} {r['wall_to_t95']:9.2f} "
          f"{r['uptake_error']:13.2e} {r['wall_to_t95'] / equilibrium_wall:14.1f}")
print(f"wrote {out / 'bench.csv'}")
