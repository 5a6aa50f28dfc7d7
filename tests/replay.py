"""A run's scene.txt replays it to the last digit: run a scene with non-default parameters and
PETSc options, run it again from nothing but the first run's scene.txt (--scene), and require
every number of steps.csv and summary.json to be the same string, wall-clock times (elapsed)
and memory aside (same binary, options and one rank: the same floating-point operations; at several ranks
the order of MPI reductions varies from run to run). The file must name
every parameter that --help lists (but --output and --restart, which say where a run goes).
A control run from the same file with one parameter changed after it on the command line
must differ: the comparison can fail, and the command line overrides the file.

scene.txt also records what the run was computed from, by content: the SHA-256 of every form
file the kernels were compiled with and of the mesh file, each checked here against the file in
the tree. It names no path of the checkout it ran in (a project mesh by its name in meshes/),
so that it replays in another. A replay whose record has another forms/materials.py (a law edited since), lacks one
of the program's form files, or names a mesh file edited since is refused in one line with no
results written.

usage: replay.py MPIEXEC RANKS EXE OUT_DIR CHANGE_NAME CHANGE_VALUE [scene options...]
"""
import hashlib
import json
import pathlib
import re
import shutil
import subprocess
import sys

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)

mpiexec, ranks, exe, out, change_name, change_value = sys.argv[1:7]
options = sys.argv[7:]
out = pathlib.Path(out)
checks = Checks()
TIMES = re.compile(r"(^|_)(wall_time|time|timing|memory|elapsed)($|_)")


def run(name, *args):
    folder = out / name
    p = subprocess.run([mpiexec, "-np", ranks, exe, "--output", str(folder), *args],
                       capture_output=True, text=True)
    checks.require(f"{name}: exit code {p.returncode}", p.returncode == 0)
    if p.returncode != 0:
        print(p.stderr[-2000:])
        checks.finish()
    return folder


def numbers(folder):
    """Every value of steps.csv and summary.json but times, memory and the output folder"""
    rows = [{k: v for k, v in r.items() if not TIMES.search(k)}
            for r in read_table(folder / "steps.csv")]
    summary = json.loads((folder / "summary.json").read_text())

    def strip(d):
        return {k: strip(v) if isinstance(v, dict) else v for k, v in d.items()
                if not TIMES.search(k) and k != "output"}
    return rows, strip(summary)


first = run("first", *options)
scene = (first / "scene.txt").read_text()
print(scene)
listed = set(re.findall(r"^(\w+) = ", scene, re.M))
help_text = subprocess.run([exe, "--help"], capture_output=True, text=True).stdout
declared = set(re.findall(r"^\s+--(\w+)", help_text, re.M)) - {"output", "restart"}
checks.require(f"scene.txt sets all {len(declared)} parameters of --help but output and "
               f"restart (missing: {sorted(declared - listed)}, extra: {sorted(listed - declared)})",
               listed == declared)
petsc = [o for o in options if o.startswith("-") and not o.startswith("--")]
checks.require(f"scene.txt holds the PETSc options given {petsc}",
               all(re.search(rf"^{re.escape(o)}\b", scene, re.M) for o in petsc))
replay = run("replay", "--scene", str(first / "scene.txt"))
rows, summary = numbers(first)
replay_rows, replay_summary = numbers(replay)
checks.require(f"replay: steps.csv's {len(rows)} rows, every column but times, are the same "
               f"strings", rows == replay_rows and len(rows) > 0)
differing = sorted(k for k in summary if summary[k] != replay_summary.get(k))
checks.require(f"replay: summary.json is the same but for times (differing: {differing})",
               not differing)
control = run("control", "--scene", str(first / "scene.txt"), f"--{change_name}", change_value)
control_rows, control_summary = numbers(control)
checks.require(f"control with --{change_name} {change_value} after the file: steps.csv differs",
               control_rows != rows)
checks.require(f"control: summary.json's parameters say {change_name} = "
               f"{control_summary['parameters'][change_name]}",
               str(control_summary["parameters"][change_name]) == change_value)

# What the run was computed from, by content: every form file the build compiles the kernels
# with (forms/NAME.py, the modules forms/_*.py and materials.py) and the mesh file it read, each
# with the SHA-256 of the file in this tree, computed here
source_tree = pathlib.Path(__file__).resolve().parents[1]
recorded = dict(re.findall(r"^source (\S+) = ([0-9a-f]{64})$", scene, re.M))
modules = {f"forms/{p.name}" for p in (source_tree / "forms").glob("_*.py")} | {"forms/materials.py"}
forms = {p for p in recorded if p.startswith("forms/")}
checks.require(f"scene.txt records the form modules {sorted(modules)} and the scene's form "
               f"files {sorted(forms - modules)}", modules < forms)


def in_tree(path):
    """A recorded file: forms/... in the source tree, a bare name in meshes/, else the path"""
    if path.startswith("forms/"):
        return source_tree / path
    return source_tree / "meshes" / path if "/" not in path else pathlib.Path(path)


for path, digest in recorded.items():
    file = in_tree(path)
    actual = hashlib.sha256(file.read_bytes()).hexdigest()
    checks.require(f"recorded SHA-256 of {path} is the file's ({digest[:12]}..., {actual[:12]}...)",
                   digest == actual)


# A record for any checkout: no file named by a path of this one (the default mesh by its name
# in meshes/; a scene file that named /.../meshes/block.geo replayed only here)
checks.require(f"scene.txt names no path of this checkout ({source_tree})",
               str(source_tree) not in scene)


def refused(name, scene_text, expect):
    """A replay from `scene_text` ends in one line naming `expect`, exit code 1, no results"""
    file = out / f"{name}.txt"
    file.write_text(scene_text)
    folder = out / name
    shutil.rmtree(folder, ignore_errors=True)  # a run before this one may have left it
    p = subprocess.run([mpiexec, "-q", "-np", ranks, exe, "--output", str(folder), "--scene",
                        str(file)],
                       capture_output=True, text=True)
    lines = p.stderr.splitlines()
    checks.require(f"{name}: exit code {p.returncode}, stderr {lines}, results "
                   f"{'written' if folder.exists() else 'not written'}",
                   p.returncode == 1 and len(lines) == 1 and expect in lines[0]
                   and not folder.exists())


# A replay after a law was edited (the record's materials.py differs from the one built in)
edited = "0" * 64
refused("replay_other_law", re.sub(r"^(source forms/materials\.py = )\S+", rf"\g<1>{edited}",
                                   scene, flags=re.M),
        "was computed with another forms/materials.py")
# A record that lacks one of the forms this program was built from
form = sorted(forms - modules)[0]
refused("replay_form_not_recorded", re.sub(rf"^source {re.escape(form)} = .*\n", "", scene,
                                           flags=re.M),
        f"was built from {form}, which the scene file's run does not record")
# A mesh file whose content changed since the run read it
if "mesh" in declared:
    mesh = re.search(r"^mesh = (.*)$", scene, re.M)[1]
    copy = out / "mesh_copy.geo"
    copy.write_bytes(in_tree(mesh).read_bytes())
    meshed = run("mesh_copy", "--scene", str(first / "scene.txt"), "--mesh", str(copy))
    copy.write_bytes(copy.read_bytes() + b"// edited after the run\n")
    refused("replay_edited_mesh", (meshed / "scene.txt").read_text(),
            f"'{copy}' is not the file the scene file's run read")
checks.finish()
