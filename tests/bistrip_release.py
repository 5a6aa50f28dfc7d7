"""Check a bistrip run that is its bonding leg alone, released with inertia: the pre-compressed
strip bonded and let go at L (--bonding quench --end_distance L, --method explicit or inertia).

- The run is the bonding leg alone: every row of steps.csv is leg 0, and it ends at the leg's
  time given to the run (--end_time, the loading and hold time of its options).
- The motion is inertial: the kinetic energy at the end is above 1e-3 of the strain energy
  released so far (a first-order flow's rows carry no kinetic energy: a leg that ran the
  flow fails), and energy is conserved: SE + KE + ED, each recomputed here from the
  columns (SE = SE_A + SE_B), stays at its first row's value within `--balance` of the
  strain energy (central differences and TSALPHA2 with rho_inf < 1 are not exactly
  conservative; the end is held, so no work enters: the bound, relative to the largest KE + ED, is a few times the measured
  drift, stated in tests/CMakeLists.txt), over the leg's outputs (50 at equal times).

usage: bistrip_release.py OUTPUT_DIR --end_time T --balance TOL
"""
import json
import pathlib
import sys

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)

out = pathlib.Path(sys.argv[1])
balance_tolerance = float(sys.argv[sys.argv.index("--balance") + 1])
end_time = float(sys.argv[sys.argv.index("--end_time") + 1])
summary = json.loads((out / "summary.json").read_text())
prm = summary["parameters"]
checks = Checks()
checks.require(f"the run completed ({summary['status']})", summary["status"] == "completed")
rows = read_table(out / "steps.csv")
legs = sorted({r["leg"] for r in rows})
checks.require(f"{len(rows)} rows, all of the bonding leg (legs {legs}; 0 alone)",
               rows and legs == ["0"])
last_time = float(rows[-1]["time"])
checks.require(f"the leg ends at t = {last_time:.6g} s, the leg's time given to the run "
               f"({end_time:.6g} s)", abs(last_time - end_time) <= 1e-9 * end_time)


def energy(r):
    return (float(r["strain_energy_A"]) + float(r["strain_energy_B"]),
            float(r["kinetic_energy"]), float(r["dissipated_energy"]))


se0, ke0, ed0 = energy(rows[0])
total0 = se0 + ke0 + ed0
exchanged = max(e[1] + e[2] for e in map(energy, rows))  # the largest KE + ED
drift = max(abs(sum(energy(r)) - total0) for r in rows) / exchanged
checks.require(f"SE + KE + ED stays at its first row's {total0:.9g} mJ over {len(rows)} outputs "
               f"(at least 10) within {balance_tolerance:.1e} of the energy SE gave up (KE + "
               f"ED, at most {exchanged:.4g} mJ; largest change {drift:.2e} of it)",
               len(rows) >= 10 and drift <= balance_tolerance)
se, ke, ed = energy(rows[-1])
released = se0 + ke0 - se
checks.require(f"inertial: KE {ke:.4g} mJ at the end, above 1e-3 of the strain energy released "
               f"since the first row ({released:.4g} mJ)", released > 0 and ke > 1e-3 * released)
checks.finish()
