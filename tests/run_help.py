"""`./gelx run SCENE --help` prints the scene's options and nothing else: exit code 0, the
option table (the scene's own --help, so its first line is "usage: gelx-SCENE"), no run (no
output folder is made), no plot script (no traceback) and no "results are in" line.

usage: run_help.py SCENE OUT_DIR
"""
import pathlib
import subprocess
import sys

from checks import Checks

scene, out = sys.argv[1], pathlib.Path(sys.argv[2])
gelx = pathlib.Path(__file__).resolve().parents[1] / "gelx"
checks = Checks()
for flag in ("--help", "-h"):
    folder = out / flag.lstrip("-")
    run = subprocess.run([str(gelx), "run", scene, "--output", str(folder), flag],
                         capture_output=True, text=True, timeout=600)
    text = run.stdout + run.stderr
    checks.require(f"{flag}: exit code {run.returncode} is 0", run.returncode == 0)
    checks.require(f"{flag}: the scene's help ({text.splitlines()[:1]})",
                   text.startswith(f"usage: gelx-{scene}"))
    checks.require(f"{flag}: no traceback, no 'results ... are in'",
                   "Traceback" not in text and "are in" not in text)
    checks.require(f"{flag}: nothing written ({folder} does not exist)", not folder.exists())
checks.finish()
