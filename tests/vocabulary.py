"""One name a quantity, one unit a name.

Fields: every array in every XDMF file of the scenes' runs (fields.xdmf, branch/, modes/) is a
name of gelx::field_names (cpp/gelx/io/output.h, read here), or a tensor's output of one (_xx,
_yy, _zz, _yz, _xz, _xy, _vm, _p), and each run writes at least one. Failed before the fields
were renamed: the pyramid's and the fiber gel's stress was `sigma`, the bistrip's `stress`.

Units (cpp/gelx/io/units.cpp): every table of a run (steps.csv, ...) starts with the line
"# units: name [unit], ..." naming its header's columns in order, and summary.json's "units"
gives every quantity of the summary a unit ("?": none); a name has one unit in all of a run's
files. The units must make the numbers agree where the physics ties them together, read in SI
through this test's own table of units: the block's stored energy is the work of its top face's
force and torque, sum of (F dz + M dtheta) along the path (dz = (stretch - 1) H dt, dtheta =
twist dt), and the pyramid's strain energy the work of the indentation force, sum of f dd
(d = d_over_H H, H = L/sqrt(2)). The trapezoidal rule over the recorded steps approximates the
work to 0.5 % (block) and 0.1 % (pyramid) on the runs of the suite; a tolerance of 2 % keeps
that margin and fails a unit of one quantity that disagrees with the others' (a factor 1000
or more: mJ for pJ, N for N mm, the torque's share of the block's work being 11 %). Failed with
the block's torque written in N and with the pyramid's energy in mJ.

usage: vocabulary.py RUN_DIR...
"""
import json
import math
import pathlib
import re
import sys
import xml.etree.ElementTree as ET

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table, table_units  # noqa: E402  (demos/fields.py)

# Each unit gelx writes, in SI (None: no number)
SI = {"1": 1.0, "text": None, "s": 1.0, "K": 1.0, "1/K": 1.0, "MiB": 1.0, "MPa": 1e6,
      "mm": 1e-3, "mm^2": 1e-6, "1/mm": 1e3, "N": 1.0, "N mm": 1e-3, "mJ": 1e-3,
      "um": 1e-6, "um^2": 1e-12, "1/um": 1e6, "uN": 1e-6, "uN um": 1e-12, "pJ": 1e-12}

header = pathlib.Path(__file__).resolve().parents[1] / "cpp" / "gelx" / "io" / "output.h"
listed = re.search(r"field_names\s*=\s*\{([^}]*)\}", header.read_text())
names = set(re.findall(r'"(\w+)"', listed[1])) if listed else set()
suffixes = ("xx", "yy", "zz", "yz", "xz", "xy", "vm", "p")
allowed = names | {f"{n}_{s}" for n in names for s in suffixes}
checks = Checks()
checks.require(f"gelx::field_names read from output.h: {sorted(names)}", len(names) >= 3)
for run in map(pathlib.Path, sys.argv[1:]):
    arrays = set()
    for xdmf in run.rglob("*.xdmf"):
        arrays |= {a.get("Name") for a in ET.parse(xdmf).getroot().iter("Attribute")}
    unknown = sorted(arrays - allowed)
    # (the Flory-Rehner scene evaluates the gel theory pointwise: it has no fields)
    pointwise = json.loads((run / "summary.json").read_text())["scene"] == "flory_rehner"
    checks.require(f"{run.name}: {len(arrays)} array names, each in the vocabulary (not: "
                   f"{unknown})", (arrays or pointwise) and not unknown)


def units_of_run(run):
    """{name: unit} over the run's tables and summaries, with checks that each is whole"""
    units = {}

    def note(where, given):
        unknown = sorted(f"{n} [{u}]" for n, u in given.items() if u not in SI)
        twice = sorted(f"{n} [{units[n]}] and [{u}]" for n, u in given.items()
                       if n in units and units[n] != u)
        for name, unit in given.items():
            units.setdefault(name, unit)
        checks.require(f"{run.name}/{where}: {len(given)} units, each in this test's table (not: "
                       f"{unknown}) and as in the run's other files (not: {twice})",
                       given and not unknown and not twice)

    for table in sorted(run.rglob("*.csv")):
        header = table.read_text().split("\n", 2)[1].split(",")
        named = table_units(table)
        checks.require(f"{run.name}/{table.relative_to(run)}: the units line names the "
                       f"{len(header)} columns in order", list(named) == header)
        note(table.relative_to(run), named)
    for summary_path in sorted(run.rglob("summary.json")):
        given = json.loads(summary_path.read_text()).get("units", {})
        missing = sorted(k for k, u in given.items() if u == "?")
        checks.require(f"{run.name}/{summary_path.relative_to(run)}: no quantity without unit "
                       f"(not: {missing})", not missing)
        note(summary_path.relative_to(run),
             {k.rsplit(".", 1)[-1]: u for k, u in given.items() if u != "?"})
    return units


def trapezoid(x, y):
    return sum(0.5 * (y[i] + y[i + 1]) * (x[i + 1] - x[i]) for i in range(len(x) - 1))


def check_work(run, summary, energy_column, work_of_rows):
    """The last row's energy against the work along the path, both in J"""
    rows = read_table(run / "steps.csv")
    units = table_units(run / "steps.csv")
    work = work_of_rows(rows, units, summary["unit_system"], summary["parameters"])
    energy = float(rows[-1][energy_column]) * SI[units[energy_column]]
    checks.relative(f"{run.name}: {energy_column} [{units[energy_column]}] against the work "
                    f"along the path, in J", energy, work, 2e-2)


def block_work(rows, units, system, prm):
    t = [0.0] + [float(r["t"]) for r in rows]
    force = [0.0] + [float(r["axial_force"]) * SI[units["axial_force"]] for r in rows]
    torque = [0.0] + [float(r["torque"]) * SI[units["torque"]] for r in rows]
    lift = (prm["stretch"] - 1) * prm["height"] * SI[system["length"]]
    return trapezoid(t, force) * lift + trapezoid(t, torque) * math.radians(prm["twist"])


def pyramid_work(rows, units, system, prm):
    height = prm["L"] / math.sqrt(2) * SI[system["length"]]
    d = [0.0] + [float(r["d_over_H"]) * height for r in rows]
    force = [0.0] + [float(r["force"]) * SI[units["force"]] for r in rows]
    return trapezoid(d, force)


scene_units = {}
for run in map(pathlib.Path, sys.argv[1:]):
    units = units_of_run(run)
    scene = json.loads((run / "summary.json").read_text())
    # One vocabulary across scenes of one unit system
    for name, unit in units.items():
        key = (scene.get("unit_system", {}).get("length"), name)
        if scene_units.setdefault(key, (unit, run.name))[0] != unit:
            checks.require(f"{name} is [{scene_units[key][0]}] in {scene_units[key][1]} and "
                           f"[{unit}] in {run.name}", False)
    if scene["scene"] == "block":
        check_work(run, scene, "strain_energy", block_work)
    if scene["scene"] == "pyramid":
        check_work(run, scene, "strain_energy", pyramid_work)
checks.finish()
