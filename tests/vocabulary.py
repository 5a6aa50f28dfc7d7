"""One name a quantity: every array in every XDMF file of the scenes' runs (fields.xdmf,
branch/, modes/) is a name of gelx::field_names (cpp/gelx/io/output.h, read here), or a tensor's
output of one (_xx, _yy, _zz, _yz, _xz, _xy, _vm, _p), and each run writes at least one.
Failed before the fields were renamed: the pyramid's and the fiber gel's stress was `sigma`,
the bistrip's `stress`.

usage: vocabulary.py RUN_DIR...
"""
import pathlib
import re
import sys
import xml.etree.ElementTree as ET

from checks import Checks

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
    checks.require(f"{run.name}: {len(arrays)} array names, each in the vocabulary (not: "
                   f"{unknown})", arrays and not unknown)
checks.finish()
