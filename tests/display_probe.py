"""A gelx run, its picture included, opens no X display that is not its own.

hwloc's GL plugin (libhwloc-plugins), which Open MPI loads in mpirun and in every rank, opens the
displays :0 to :9 to look for NVIDIA GPUs; when such a display goes away while it is open, Xlib
ends the process with "X connection to :0 broken" and exit code 1. So a test failed in CI, beside
a render's Xvfb that had taken :0 (2026-12-04). gelx now turns the plugin off
(HWLOC_COMPONENTS=-gl) and puts its renders' Xvfb on :10 and up.

The test starts an Xvfb of its own on a free display among :0 to :9, logging each client that
connects (-audit 2). Control: `mpirun -np 1 true` without HWLOC_COMPONENTS must connect to it
(hwloc's probe is there to be seen on this machine, and the log sees it). Then
`./gelx run block --np 2 --stop_after_steps 1`, with HWLOC_COMPONENTS removed from the
environment it is given (gelx must set it) and its picture rendered, must not connect.
It failed with the export removed from ./gelx.

usage: display_probe.py SOURCE_DIR BUILD_DIR OUT_DIR
"""
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

from checks import Checks

source, build, out = (pathlib.Path(a) for a in sys.argv[1:4])
checks = Checks()
shutil.rmtree(out, ignore_errors=True)
out.mkdir(parents=True)
env = {k: v for k, v in os.environ.items() if k != "HWLOC_COMPONENTS"}
env["GELX_BUILD_DIR"] = str(build)

free = [n for n in range(10) if not pathlib.Path(f"/tmp/.X{n}-lock").exists()]  # as Xvfb sees it
checks.require(f"a free display among :0 to :9 for the test's Xvfb (free: {free})", free)
if not free:
    checks.finish()
log = out / "xvfb_audit.log"
with tempfile.TemporaryFile() as ready, open(log, "w") as audit:
    xvfb = subprocess.Popen(["Xvfb", f":{free[0]}", "-displayfd", str(ready.fileno()), "-audit",
                             "2", "-nolisten", "tcp"], stdout=audit, stderr=audit,
                            pass_fds=[ready.fileno()])
    for _ in range(300):
        ready.seek(0)
        if ready.read() or xvfb.poll() is not None:
            break
        time.sleep(0.1)
    try:
        def connections():
            return log.read_text().count(" connected from ")

        probe = subprocess.run(["mpirun", "-np", "1", "true"], env=env, capture_output=True,
                               text=True, timeout=60)
        time.sleep(0.5)  # the server writes its log line after the client's connection
        control = connections()
        checks.require(f"control: 'mpirun -np 1 true' without HWLOC_COMPONENTS (exit code "
                       f"{probe.returncode}) opened the test's display :{free[0]} {control} "
                       f"times (hwloc's probe; at least 1) {probe.stderr[-300:]}",
                       probe.returncode == 0 and control >= 1)
        run = subprocess.run([str(source / "gelx"), "run", "block", "--np", "2",
                              "--stop_after_steps", "1", "--output", str(out / "block")],
                             env=env, capture_output=True, text=True, timeout=600)
        checks.require(f"./gelx run block, with its picture, completed (exit code "
                       f"{run.returncode}) {run.stderr[-500:]}",
                       run.returncode == 0 and (out / "block" / "view.png").is_file())
        time.sleep(0.5)
        opened = connections() - control
        checks.require(f"./gelx run block opened the test's display :{free[0]} {opened} times "
                       f"(none)", opened == 0)
    finally:
        xvfb.terminate()  # (SIGKILL would leave its lock file and socket behind)
        xvfb.wait()
checks.finish()
