"""Bad fiber_gel input ends with one line 'gelx-fiber_gel: error: ...' on stderr and exit code 1,
before any mesh is built.

usage: fiber_gel_bad_input.py SCENE_BINARY WORK_DIR
"""
import pathlib
import subprocess
import sys

from checks import Checks

binary, work = sys.argv[1], pathlib.Path(sys.argv[2])
work.mkdir(parents=True, exist_ok=True)
checks = Checks()


def run(name, args, expect):
    p = subprocess.run([binary, "--output", str(work / name)] + args, capture_output=True,
                       text=True, timeout=120)
    lines = p.stderr.strip().splitlines()
    checks.require(f"{name}: exit code {p.returncode}, stderr {lines!r}",
                   p.returncode == 1 and len(lines) == 1
                   and lines[0].startswith("gelx-fiber_gel: error:") and expect in lines[0])


run("phi_i_one", ["--phi_i", "1"], "must lie in (0, 1)")
run("phi_f_beyond_one", ["--phi_i", "0.6"], "phi_i / alpha0^3 must stay below 1")
run("negative_diameter", ["--d", "-10"], "must be positive")
run("negative_mesh_size", ["--h_fiber", "-1"], "must be positive")
run("cell_narrower_than_fiber", ["--D", "10"], "D must exceed the fiber diameter d")
run("fiber_longer_than_cell", ["--l", "40", "--L", "30"], "l must lie in [d, L]")
run("full_cell_with_rod", ["--cell", "full"], "needs a fiber shorter than the cell")
run("order_three", ["--order", "3"], "must be 1 or 2")
checks.finish()
