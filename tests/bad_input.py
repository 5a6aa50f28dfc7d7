"""Bad input ends with one clear line on stderr and a non-zero exit; a run that diverges with
cut-back disabled exits non-zero and keeps its completed steps readable.

usage: bad_input.py SCENE_BINARY WORK_DIR
"""
import json
import pathlib
import subprocess
import sys

import h5py

from checks import Checks

binary, work = sys.argv[1], pathlib.Path(sys.argv[2])
work.mkdir(parents=True, exist_ok=True)
checks = Checks()
quick = ["--h", "0.5", "-newton_monitor", "0"]


def run(name, args, expect):
    out = work / name
    p = subprocess.run([binary, "--output", str(out)] + quick + args, capture_output=True,
                       text=True, timeout=600)
    lines = p.stderr.strip().splitlines()
    checks.require(f"{name}: exit code {p.returncode}, stderr {lines!r}",
                   p.returncode != 0 and len(lines) == 1
                   and lines[0].startswith("gelx-block: error:") and expect in lines[0])
    return out


garbled = work / "garbled.scene"
garbled.write_text("G = 1\nthis line has no equals sign\n")
run("missing_mesh", ["--mesh", str(work / "no-such.geo")], "not found")
run("negative_modulus", ["--G", "-1"], "must be positive")
run("unknown_option", ["--stiffness", "3"], "unknown parameter 'stiffness'")
run("missing_scene_file", ["--scene", str(work / "no-such.scene")], "cannot read scene file")
run("garbled_scene_file", ["--scene", str(garbled)], "expected 'name = value'")
run("stretch_not_a_number", ["--stretch", "long"], "is not a number")

# Divergence: a first small step, then a jump to the full load that 4 Newton iterations cannot
# reach, with cut-back disabled.
out = run("forced_divergence", ["--dt", "0.05", "--dt_grow", "20", "--dt_max", "1",
                                "--max_cutbacks", "0", "-newton_max_it", "4"], "failed")
summary = json.loads((out / "summary.json").read_text())
checks.require(f"forced_divergence: summary status {summary['status'][:40]!r}..., "
               f"{summary['steps']} completed step", summary["status"].startswith("failed")
               and summary["steps"] == 1)
with h5py.File(out / "fields.h5", "r") as h5:
    n = len(h5["Function/displacement"])
    u = h5["Function/displacement"][list(h5["Function/displacement"])[0]][:]
checks.require(f"forced_divergence: fields.h5 readable with {n} displacement step of shape "
               f"{u.shape}", n == 1 and u.shape[1] == 3)
rows = (out / "steps.csv").read_text().strip().splitlines()
checks.require(f"forced_divergence: steps.csv has {len(rows) - 1} data row", len(rows) == 2)
checks.finish()
