"""Cost of arc-length continuation against plain Newton on the inflated shell: runs the scene
and prints its measured cost figures (summary.json of the run).

usage: bench.py BUILD_DIR OUTPUT_DIR
"""
import json
import os
import pathlib
import subprocess
import sys

build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
subprocess.run([str(build / "demos" / "inflation" / "gelx-inflation"), "--output", str(out)],
               check=True, stdout=subprocess.DEVNULL,
               env=dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1"))
s = json.loads((out / "summary.json").read_text())
print(f"inflation ({s['num_dofs']} dofs, {s['mpi_ranks']} rank): {s['steps']} arc-length steps "
      f"through the limit point, {s['corrector_iterations_per_step']:.2f} corrector iterations "
      "per step")
print(f"  one Newton iteration (plain load stepping)  {s['time_per_newton_iteration']:.3f} s")
print(f"  one arc-length corrector iteration          {s['time_per_corrector_iteration']:.3f} s "
      f"({s['time_per_corrector_iteration'] / s['time_per_newton_iteration']:.2f} Newton iterations)")
print(f"  one arc-length step                         {s['time_per_step']:.3f} s")
print(f"  p_max/G = {s['p_max_over_G']:.6f} (closed form {s['closed_form_p_max_over_G']:.6f})")
