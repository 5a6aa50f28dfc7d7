"""How time and memory grow with the number of unknowns N, for the direct and the iterative
linear solvers (the option sets of -newton_linear_solver, docs/runner.md "Linear solvers").

Two problems, each one short load path at growing sizes, on 2 ranks:
- block: the compressible P2 block (K/G = 10), stretched to 1.1 and twisted by 10 degrees in
  one load step; `direct` (MUMPS LU) against `amg` (GMRES + GAMG) and `amg` with
  Eisenstat-Walker inexact Newton (-newton_snes_ksp_ew);
- pyramid: the incompressible Q1-P0 pyramid pressed to d/H = 0.05 in two load steps (mixed
  u-p, contact, the apex graded);
  `direct` against `fieldsplit` (Schur complement, GAMG on the displacement block).
Per run, per Newton iteration: the time of assembly and of the linear solve (PETSc's log, the
summary's time_split), Krylov iterations, and the run's peak memory (all ranks) and output
time. Then, per problem and solver, the growth exponent of time and memory in N (least
squares in log-log over the runs with N >= 2e4, where fixed costs no longer dominate) and the
N where the iterative solve overtakes the direct one. The direct solve and Eisenstat-Walker
stop growing at MAX_UNKNOWNS. Time a quiet machine: both cores are used.

Writes scaling.csv and scaling.png into the output folder and prints the tables.

usage: scaling.py BUILD OUT [--quick] [--reuse]   (./gelx bench scaling)
--quick: the three smallest sizes of each problem, a check of the script; --reuse: read the
runs already in OUT instead of running them again (e.g. to redo the tables)
"""
import csv
import json
import math
import pathlib
import subprocess
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)
from studies import MPI_ENV  # noqa: E402  (demos/studies.py)

RANKS = 2
# The direct solve's memory and time leave this 24 GiB, 2-core machine beyond some 2.5e5
# unknowns; Eisenstat-Walker's Newton iterations grow with N (measured on the block: 8, 10, 25,
# 39 up to 1.6e5 unknowns, against 4), so it is stopped there too
MAX_UNKNOWNS = {"direct": 2.5e5, "amg+ew": 2.5e5}
FIT_MIN_UNKNOWNS = 2e4
PROBLEMS = {
    "block": {
        "options": ["--stretch", "1.1", "--twist", "10", "--dt", "1", "--dt_max", "1",
                    "--checkpoint_every", "0"],
        # mesh sizes h [mm] for P2: 4.2k ... 1.0M unknowns
        "sizes": [["--h", h] for h in ("0.25", "0.125", "0.0867", "0.0662", "0.05", "0.0335")],
        "solvers": {"direct": [],
                    "amg": ["-newton_linear_solver", "amg"],
                    "amg+ew": ["-newton_linear_solver", "amg", "-newton_snes_ksp_ew"]},
        "answer": "strain_energy",
    },
    "pyramid": {
        "options": ["--order", "1", "--d_max", "0.05", "--dt", "0.5", "--dt_max", "0.5",
                    "--extrapolate", "false", "--checkpoint_every", "0"],
        "sizes": [["--cells", c] for c in ("2", "3", "4", "5", "6")],
        "solvers": {"direct": [],
                    "fieldsplit": ["-newton_linear_solver", "fieldsplit"]},
        "answer": "final_force",
    },
}


def run(build, problem, folder, options, reuse):
    """One run (with `reuse`, a completed run already in `folder` is read, not run again);
    its unknowns, Newton and Krylov iterations, time split and peak memory."""
    exe = build / "demos" / problem / f"gelx-{problem}"
    error = ""
    if not (reuse and (folder / "summary.json").exists()):
        done = subprocess.run(["mpirun", "-np", str(RANKS), str(exe), "--output", str(folder)]
                              + options, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              text=True, env=MPI_ENV)
        error = done.stderr.strip().splitlines()[-1] if done.returncode else ""
    summary = json.loads((folder / "summary.json").read_text())
    steps = read_table(folder / "steps.csv")
    newton = sum(int(r["newton_iterations"]) for r in steps)
    split = summary["time_split"]
    return {"unknowns": int(summary.get("num_unknowns", summary["num_dofs"])),
            "status": (summary["status"] + " " + error).strip(),
            "newton_iterations": newton,
            "krylov_per_newton": sum(int(r["linear_iterations"]) for r in steps) / newton,
            "assembly_per_newton": split["assembly"] / newton,
            "solve_per_newton": split["solve"] / newton,
            "output": split["output"], "mesh": split["mesh"],
            "wall_time": summary["wall_time"],
            "peak_memory_MiB": summary["peak_memory_MiB"]["sum_over_ranks"],
            "answer": summary.get(PROBLEMS[problem]["answer"], math.nan)}


def exponent(rows, key):
    """Least-squares slope of log(key) against log(unknowns) over rows with N >= FIT_MIN."""
    pts = [(math.log(r["unknowns"]), math.log(r[key])) for r in rows
           if r["unknowns"] >= FIT_MIN_UNKNOWNS and r[key] > 0]
    if len(pts) < 2:
        return math.nan
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    return (sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts))


def newton_time(r):
    """Assembly and linear solves of the whole run: what a solver choice changes (inexact
    Newton takes more, cheaper iterations)."""
    return (r["assembly_per_newton"] + r["solve_per_newton"]) * r["newton_iterations"]


def crossover(direct, iterative):
    """The N where the run's Newton time (newton_time) with the iterative solver becomes
    shorter than with the direct one (log-log interpolation between the sizes that bracket it),
    or None."""
    by_size = {r["unknowns"]: newton_time(r) for r in direct}
    pairs = [(r["unknowns"], by_size[r["unknowns"]] / newton_time(r))
             for r in iterative if r["unknowns"] in by_size]
    for (n0, q0), (n1, q1) in zip(pairs, pairs[1:]):
        if q0 < 1 <= q1:
            s = math.log(q0) / (math.log(q0) - math.log(q1))
            return math.exp(math.log(n0) + s * (math.log(n1) - math.log(n0)))
    return pairs[0][0] if pairs and pairs[0][1] >= 1 else None


def main():
    build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    quick, reuse = "--quick" in sys.argv, "--reuse" in sys.argv
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for problem, case in PROBLEMS.items():
        sizes = case["sizes"][:3] if quick else case["sizes"]
        for size in sizes:
            for solver, options in case["solvers"].items():
                # the sizes grow by about 2.5: stop a capped solver before it passes its cap
                if solver in MAX_UNKNOWNS and any(
                        2.5 * r["unknowns"] > MAX_UNKNOWNS[solver] for r in rows
                        if (r["problem"], r["solver"]) == (problem, solver)):
                    continue
                folder = out / problem / solver.replace("+", "_") / "_".join(size).strip("-")
                r = {"problem": problem, "solver": solver, "size": " ".join(size)}
                r.update(run(build, problem, folder, case["options"] + size + options, reuse))
                rows.append(r)
                r["newton_time"] = newton_time(r)
                print(f"{problem:8s} {solver:10s} {r['size']:12s} N = {r['unknowns']:8d}: "
                      f"Newton time {r['newton_time']:8.2f} s, "
                      f"{r['newton_iterations']:3d} Newton, {r['krylov_per_newton']:7.1f} "
                      f"Krylov/Newton, assembly {r['assembly_per_newton']:7.2f} s, solve "
                      f"{r['solve_per_newton']:7.2f} s per Newton iteration, "
                      f"{r['peak_memory_MiB']:7.0f} MiB, {r['status']}", flush=True)
    with open(out / "scaling.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    print(f"\nGrowth in N (least squares over N >= {FIT_MIN_UNKNOWNS:.0e}), and agreement with "
          "the direct solve")
    print("problem  solver      solve/Newton  assembly/Newton  peak memory  Krylov/Newton"
          "  max |answer - direct|/|direct|")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for problem, case in PROBLEMS.items():
        direct = [r for r in rows if (r["problem"], r["solver"]) == (problem, "direct")]
        reference = {r["unknowns"]: r["answer"] for r in direct}
        for solver in case["solvers"]:
            mine = [r for r in rows if (r["problem"], r["solver"]) == (problem, solver)]
            diffs = [abs(r["answer"] / reference[r["unknowns"]] - 1) for r in mine
                     if r["unknowns"] in reference]
            print(f"{problem:8s} {solver:10s}  N^{exponent(mine, 'solve_per_newton'):.2f}"
                  f"        N^{exponent(mine, 'assembly_per_newton'):.2f}           "
                  f"N^{exponent(mine, 'peak_memory_MiB'):.2f}      "
                  f"{min(r['krylov_per_newton'] for r in mine):.0f}-"
                  f"{max(r['krylov_per_newton'] for r in mine):.0f}"
                  f"          {max(diffs):.1e}")
            label = f"{problem} {solver}"
            n = [r["unknowns"] for r in mine]
            axes[0].loglog(n, [r["solve_per_newton"] for r in mine], "o-", label=label)
            axes[1].loglog(n, [r["peak_memory_MiB"] for r in mine], "o-", label=label)
            if solver != "direct":
                n_cross = crossover(direct, mine)
                print(f"         {solver} overtakes direct at N = "
                      + (f"{n_cross:.3g}" if n_cross else "(not within the sizes run)"))
    n_all = sorted(r["unknowns"] for r in rows)
    smallest = min(rows, key=lambda r: r["unknowns"])
    for ax, key in zip(axes, ("solve_per_newton", "peak_memory_MiB")):
        ax.loglog([n_all[0], n_all[-1]], [smallest[key], smallest[key] * n_all[-1] / n_all[0]],
                  "k:", label="∝ N")
        ax.set_xlabel("unknowns N")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("linear solve per Newton iteration [s]")
    axes[1].set_ylabel("peak memory, 2 ranks [MiB]")
    axes[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "scaling.png", dpi=120)
    print(f"wrote {out / 'scaling.csv'} and {out / 'scaling.png'}")


if __name__ == "__main__":
    main()
