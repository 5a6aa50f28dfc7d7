"""`./gelx view` on a block run: the PNG it writes (tools/view.py, rendered by pvbatch under
xvfb-run) shows the deformed block coloured by von Mises stress over the colour map's range.

Checks, on the pixels: the picture has the requested size; the body covers a sensible part of
it (not an empty or a flooded view: 5-80 % of the pixels differ from the white background);
the body is coloured by the field, not flat-shaded: among its pixels, both ends of the
cool-to-warm map appear (blue-dominated and red-dominated pixels, each at least 1 % of the
body), which a grey surface or a constant field cannot give; and a second picture at the first
step, where the block is barely twisted and the stress is low, differs from the last one.

usage: paraview_picture.py BLOCK_RESULTS OUT_DIR
"""
import pathlib
import shutil
import subprocess
import sys

import matplotlib.image
import numpy as np

from checks import Checks

results, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
out.mkdir(parents=True, exist_ok=True)
gelx = pathlib.Path(__file__).resolve().parents[1] / "gelx"
checks = Checks()
missing = [p for p in ("xvfb-run", "pvbatch") if shutil.which(p) is None]
checks.require(f"xvfb-run and pvbatch are installed (missing: {missing})", not missing)
if missing:
    checks.finish()


def render(step):
    png = out / f"block_step{step}.png"
    run = subprocess.run([str(gelx), "view", "block", "--output", str(results), "--step",
                          str(step), "--png", str(png)], capture_output=True, text=True,
                         timeout=300)
    checks.require(f"./gelx view rendered step {step} (exit code {run.returncode}): "
                   f"{run.stdout.strip()}", run.returncode == 0 and png.is_file())
    if run.returncode != 0:
        print(run.stderr[-2000:])
        checks.finish()
    return matplotlib.image.imread(str(png))[:, :, :3]


last = render(-1)
checks.require(f"picture of {last.shape[1]} x {last.shape[0]} pixels (asked 1200 x 900)",
               last.shape[:2] == (900, 1200))
body = np.any(last < 0.98, axis=2)
checks.require(f"{body.mean():.1%} of the pixels are not background (5 % to 80 %)",
               0.05 < body.mean() < 0.8)
r, b = last[..., 0][body], last[..., 2][body]
blue, red = np.mean(b > r + 0.2), np.mean(r > b + 0.2)
checks.require(f"coloured by the field: {blue:.1%} blue-dominated and {red:.1%} red-dominated "
               f"pixels of the body (each at least 1 %)", blue > 0.01 and red > 0.01)
first = render(0)
changed = np.mean(np.any(np.abs(first - last) > 0.1, axis=2))
checks.require(f"the first step's picture differs from the last's in {changed:.1%} of the pixels "
               f"(at least 5 %)", changed > 0.05)
checks.finish()
