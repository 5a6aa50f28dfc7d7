"""`./gelx new` round trip, as docs/new-scene.md tells it, in a copy of the source tree with a
build folder of its own (the checkout is not touched; the library's objects come from ccache's
cache of the checkout's build, so the copy compiles the scenes' forms and links):

1. `./gelx new cyl` makes demos/cyl and forms/cyl.py (exit code 0); a second time it refuses,
   in one line with exit code 1.
2. `./gelx run cyl` (the runner re-configures CMake for the new folder, builds gelx-cyl alone,
   runs it, plots and draws it) completes a short block path: summary.json says scene "cyl",
   status "completed", and its forces are the block's of the same run (same law, same mesh).
3. The law of forms/cyl.py alone is edited: its energy density doubled. Displacement-driven,
   the equilibrium displacement of 2 psi is that of psi, so every reaction doubles: the axial
   force and the torque at every step of the rerun are twice the first run's, to 1e-8 (the
   Newton tolerance |R| <= 1e-10 |R0| on forces of O(1)). The block's own forms are unchanged,
   so a rerun of the block gives its first forces again.

Fails when `./gelx new` leaves a name of the block in the copy (the build of gelx-cyl fails on
the duplicate target), or when the edit does not reach the scene (ratio 1).

usage: new_scene.py WORK_DIR
"""
import json
import os
import pathlib
import shutil
import subprocess
import sys

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)

work = pathlib.Path(sys.argv[1])
source = pathlib.Path(__file__).resolve().parents[1]
# The copy's build folder inside it, where the checkout has its own: ccache (CMakeLists.txt) then
# hashes the copy's compile commands as the checkout's and compiles none of the library again
tree = work / "tree"
build = tree / "build"
checks = Checks()
shutil.rmtree(work, ignore_errors=True)
shutil.copytree(source, tree, ignore=shutil.ignore_patterns(".git", "build", "results"))
env = dict(os.environ, GELX_BUILD_DIR=str(build))
RUN = ["--np", "1", "--h", "0.5", "--stretch", "1.3", "--twist", "45"]
TOL = 1e-8


def gelx(*words, timeout=1800):
    return subprocess.run([str(tree / "gelx"), *words], capture_output=True, text=True,
                          timeout=timeout, env=env, cwd=tree)


def forces(scene):
    return [(float(r["axial_force"]), float(r["torque"]))
            for r in read_table(tree / "results" / scene / "steps.csv")]


def finish_if(failed, what, p):
    if failed:
        print(f"{what}: stdout {p.stdout[-1500:]}\nstderr {p.stderr[-1500:]}")
        checks.finish()


# 1. The scene
p = gelx("new", "cyl")
made = (tree / "demos" / "cyl" / "main.cpp").is_file() and (tree / "forms" / "cyl.py").is_file()
checks.require(f"./gelx new cyl: exit code {p.returncode}, demos/cyl and forms/cyl.py made",
               p.returncode == 0 and made)
again = gelx("new", "cyl")
lines = again.stderr.splitlines()
checks.require(f"./gelx new cyl again: exit code {again.returncode}, stderr {lines!r}",
               again.returncode == 1 and len(lines) == 1 and "exists already" in lines[0])

# 2. Its first run, and the block's
p = gelx("run", "cyl", *RUN)
summary_file = tree / "results" / "cyl" / "summary.json"
summary = json.loads(summary_file.read_text()) if summary_file.is_file() else {}
checks.require(f"./gelx run cyl: exit code {p.returncode}, scene {summary.get('scene')!r}, "
               f"status {summary.get('status')!r}, picture made",
               p.returncode == 0 and summary.get("scene") == "cyl"
               and summary.get("status") == "completed"
               and (tree / "results" / "cyl" / "view.png").is_file())
finish_if(p.returncode != 0, "run cyl", p)
p = gelx("run", "block", *RUN)
finish_if(p.returncode != 0, "run block", p)
cyl, block = forces("cyl"), forces("block")
checks.require(f"cyl's {len(cyl)} steps of axial force and torque are the block's "
               f"(last: {cyl[-1]} and {block[-1]})", cyl == block and len(cyl) >= 2)

# 3. Its law doubled, in its own form file only
law = tree / "forms" / "cyl.py"
text = law.read_text()
edited = text.replace('"nh": lambda F: materials.neo_hookean_compressible(F, G, K)',
                      '"nh": lambda F: 2 * materials.neo_hookean_compressible(F, G, K)')
checks.require("forms/cyl.py has the block's law to edit", edited != text)
law.write_text(edited)
p = gelx("run", "cyl", *RUN)
finish_if(p.returncode != 0, "rerun cyl", p)
doubled = forces("cyl")
ratios = [(a / a0, t / t0) for (a, t), (a0, t0) in zip(doubled, cyl)]
worst = max(max(abs(ra - 2), abs(rt - 2)) for ra, rt in ratios) if ratios else float("inf")
checks.require(f"with 2 psi every force of cyl doubled: {len(ratios)} steps, ratios differ from "
               f"2 by at most {worst:.1e} (tol {TOL:.0e})",
               len(doubled) == len(cyl) and worst <= TOL)
p = gelx("run", "block", *RUN)
finish_if(p.returncode != 0, "rerun block", p)
checks.require("the block's forces are unchanged by the edit of forms/cyl.py",
               forces("block") == block)
checks.finish()
