"""`./gelx help` (also `--help`, `-h` and a bare `./gelx`) explains the runner: exit code 0, every
command of the runner's dispatch (read from the script itself: a command added without a help
line fails), and every scene folder of demos/ with its README's title; and nothing is built
or run (no results/ folder appears). `./gelx view --help` on a run gives the options with help
texts and the fields of that run's last output, read here from its fields.xdmf.

usage: runner_help.py BLOCK_RESULTS
"""
import pathlib
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

from checks import Checks

results = pathlib.Path(sys.argv[1])
root = pathlib.Path(__file__).resolve().parents[1]
gelx = root / "gelx"
checks = Checks()
script = gelx.read_text()
# the dispatch's cases: '  NAME)' or '  NAME|...)' at the case's indentation
commands = sorted({m for line in re.findall(r"^  ([a-z|-]+)\)", script, re.M)
                   for m in line.split("|") if not m.startswith("-")})
scenes = sorted(p.parent.name for p in (root / "demos").glob("*/README.md"))
checks.require(f"the runner's commands {commands} and scenes {scenes} were found",
               {"run", "view", "test", "help"} <= set(commands) and len(scenes) >= 5)
had_results = (root / "results").exists()
for words in (["help"], ["--help"], ["-h"], []):
    run = subprocess.run([str(gelx), *words], capture_output=True, text=True, timeout=120)
    text = run.stdout
    missing = [c for c in commands if not re.search(rf"\./gelx {c}\b", text)]
    missing += [s for s in scenes if not re.search(rf"^  {s} +\S", text, re.M)]
    checks.require(f"./gelx {' '.join(words)}: exit code {run.returncode}, stderr "
                   f"{run.stderr.strip()[:80]!r}, every command and scene listed (missing: "
                   f"{missing})", run.returncode == 0 and not run.stderr and not missing)
checks.require("nothing was run (no results/ folder appeared)",
               had_results or not (root / "results").exists())

view = subprocess.run([str(gelx), "view", "block", "--output", str(results), "--help"],
                      capture_output=True, text=True, timeout=120)
grids = ET.parse(results / "fields.xdmf").getroot().find("Domain/Grid").findall("Grid")
fields = [a.get("Name") for a in grids[-1].findall("Attribute")]
options = re.findall(r"^  (--[a-z]+)", view.stdout, re.M)
undocumented = [line for line in view.stdout.splitlines()
                if re.match(r"^  --[a-z]+( [A-Z]+)*$", line)]  # an option with no text after it
listed = re.search(r"^fields of .*: (.*)$", view.stdout, re.M)
checks.require(f"./gelx view --help: exit code {view.returncode}, {len(options)} options, each "
               f"with a help text (without: {undocumented})",
               view.returncode == 0 and len(options) >= 10 and not undocumented)
checks.require(f"./gelx view --help lists the run's {len(fields)} fields "
               f"({listed[1][:60] if listed else None}...)",
               listed is not None and listed[1].split(", ") == fields)
checks.finish()
