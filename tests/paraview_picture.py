"""`./gelx view` on a block run: the PNG it writes (tools/view.py, rendered by pvbatch on its
own Xvfb) shows the deformed block coloured by von Mises stress over the colour map's range.

Checks, on the pixels: the picture has the requested size; the body covers a sensible part of
it (not an empty or a flooded view: 5-80 % of the pixels differ from the white background);
the body is coloured by the field, not flat-shaded: among its pixels, both ends of the
cool-to-warm map appear (blue-dominated and red-dominated pixels, each at least 1 % of the
body), which a grey surface or a constant field cannot give; the colours are where the values
are: each surface triangle of the deformed mesh (read from the XDMF here) seen whole in the
picture, projected by the camera ./gelx view prints, is coloured warmer the higher its cell's
stress (rank correlation >= 0.98: measured 0.997; 0.39 without the warp, -0.42 coloured by the
displacement, 0.963 with the printed extent 10 % off), warm above the range's middle and cool
below it; and a second picture at the first step, where the block is barely twisted and the
stress is low, differs from the last one.
A render interrupted midway (SIGINT to its process group, as Ctrl-C sends) leaves no process
of its own behind within 10 s. A render killed (SIGKILL) but for its Xvfb, as a timeout's kill
that misses the display server, holds up no later render: the next finishes within 120 s.
Before, the render lock was inherited by xvfb-run's Xvfb, and when it outlived its render
every later render waited forever (seen under ctest -j2; this check hung on that code). The
render's display is :10 or above, out of the range hwloc's GL plugin opens in MPI processes
(tests/display_probe.py says why): with Xvfb -displayfd's first free display it failed.

usage: paraview_picture.py BLOCK_RESULTS OUT_DIR
"""
import pathlib
import os
import shutil
import signal
import subprocess
import sys
import time

import matplotlib.image
import numpy as np

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import FieldSeries  # noqa: E402  (demos/fields.py)

results, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
out.mkdir(parents=True, exist_ok=True)
gelx = pathlib.Path(__file__).resolve().parents[1] / "gelx"
checks = Checks()
missing = [p for p in ("Xvfb", "pvbatch") if shutil.which(p) is None]
checks.require(f"Xvfb and pvbatch are installed (missing: {missing})", not missing)
if missing:
    checks.finish()


def view(step, png):
    return [str(gelx), "view", "block", "--output", str(results), "--step", str(step),
            "--png", str(png)]


def render(step, timeout=300):
    png = out / f"block_step{step}.png"
    try:
        run = subprocess.run(view(step, png), capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        checks.require(f"./gelx view rendered step {step} within {timeout} s", False)
        checks.finish()
    checks.require(f"./gelx view rendered step {step} (exit code {run.returncode}): "
                   f"{run.stdout.strip()}", run.returncode == 0 and png.is_file())
    if run.returncode != 0:  # the error's first lines and the end of its trace
        print(run.stderr[:2000] + "\n...\n" + run.stderr[-1000:])
        checks.finish()
    return matplotlib.image.imread(str(png))[:, :, :3], run.stdout


def camera_of(printed):
    """The camera ./gelx view printed: {option: [numbers]} for direction, up, focus, extent"""
    words = printed.split("camera:")[1].split()
    options = [i for i, w in enumerate(words) if w.startswith("--")] + [len(words)]
    return {words[i][2:]: [float(w) for w in words[i + 1:j]]
            for i, j in zip(options, options[1:])}


def surface_facets(x, cells):
    """The boundary triangles of a tetrahedral mesh: (nodes with an outward normal's order,
    owning cell)"""
    faces = np.concatenate([cells[:, [1, 2, 3]], cells[:, [0, 3, 2]], cells[:, [0, 1, 3]],
                            cells[:, [0, 2, 1]]])
    owner = np.tile(np.arange(len(cells)), 4)
    _, first, count = np.unique(np.sort(faces, axis=1), axis=0, return_index=True,
                                return_counts=True)
    once = first[count == 1]
    faces, owner = faces[once], owner[once]
    # the order above is outward for a positively oriented cell; flip where a cell is not
    opposite = x[cells[owner]].sum(axis=1) - x[faces].sum(axis=1)
    normal = np.cross(x[faces[:, 1]] - x[faces[:, 0]], x[faces[:, 2]] - x[faces[:, 0]])
    inward = np.einsum("ij,ij->i", normal, opposite - x[faces[:, 0]]) > 0
    faces[inward] = faces[inward][:, [0, 2, 1]]
    return faces, owner


def colours_at_facets(picture, printed, step):
    """The field's colour where each visible surface triangle of the deformed block lands in
    the picture, by the printed camera (parallel projection): the warm-minus-cool share
    (r - b) / (r + g + b) of the pixels around the triangle's centre, which the lighting (a
    factor on r, g, b) leaves alone. [(cell value, share)] for triangles seen whole around
    their centre (their projection at least 4 pixels across there, in front of every other)."""
    series = FieldSeries(results)
    x0, cells = series.mesh(step)
    x = x0 + series.field("displacement", step)
    value = series.field("cauchy_stress_vm", step).ravel()
    camera = camera_of(printed)
    look = np.array(camera["direction"]) / np.linalg.norm(camera["direction"])
    up = np.array(camera["up"]) - np.dot(camera["up"], look) * look
    up /= np.linalg.norm(up)
    right = np.cross(look, up)
    height, width = picture.shape[:2]
    pixels = height / 2 / camera["extent"][0]
    relative = x - np.array(camera["focus"])
    screen = np.stack([width / 2 + pixels * relative @ right,
                       height / 2 - pixels * relative @ up], axis=1)
    depth = relative @ look
    faces, owner = surface_facets(x, cells)
    corners, depths = screen[faces], depth[faces]
    centre = corners.mean(axis=1)
    # barycentric coordinates of every centre in every triangle's projection
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    area = (b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0]
    found = []
    for k, p in enumerate(centre):
        if abs(area[k]) < 1e-9:
            continue  # seen edge-on
        wb = ((p - a)[:, 0] * (c - a)[:, 1] - (p - a)[:, 1] * (c - a)[:, 0]) / area
        wc = ((b - a)[:, 0] * (p - a)[:, 1] - (b - a)[:, 1] * (p - a)[:, 0]) / area
        covering = (wb >= 0) & (wc >= 0) & (wb + wc <= 1) & (np.abs(area) > 1e-9)
        front = depths[:, 0] + wb * (depths[:, 1] - depths[:, 0]) \
            + wc * (depths[:, 2] - depths[:, 0])
        if front[k] > front[covering].min() + 1e-9:
            continue  # behind another triangle
        # distance from the centre to the triangle's nearest edge, in pixels: its inradius
        sides = [np.linalg.norm(corners[k][(i + 1) % 3] - corners[k][i]) for i in range(3)]
        if abs(area[k]) / sum(sides) < 4:
            continue
        i, j = int(round(p[1])), int(round(p[0]))
        patch = picture[i - 1:i + 2, j - 1:j + 2].reshape(-1, 3)
        share = (patch[:, 0] - patch[:, 2]) / patch.sum(axis=1).clip(1e-6)
        found.append((value[owner[k]], share.mean()))
    return np.array(found), value.min(), value.max()


last, printed = render(-1)
checks.require(f"picture of {last.shape[1]} x {last.shape[0]} pixels (asked 1200 x 900)",
               last.shape[:2] == (900, 1200))
body = np.any(last < 0.98, axis=2)
checks.require(f"{body.mean():.1%} of the pixels are not background (5 % to 80 %)",
               0.05 < body.mean() < 0.8)
r, b = last[..., 0][body], last[..., 2][body]
blue, red = np.mean(b > r + 0.2), np.mean(r > b + 0.2)
checks.require(f"coloured by the field: {blue:.1%} blue-dominated and {red:.1%} red-dominated "
               f"pixels of the body (each at least 1 %)", blue > 0.01 and red > 0.01)
found, low, high = colours_at_facets(last, printed, -1)
np.set_printoptions(precision=3, suppress=True)
print("visible surface triangles: von Mises stress of the cell, warm-minus-cool share of the "
      "pixels at the centre\n", found)
ranks = [np.argsort(np.argsort(column)) for column in found[:, :2].T]
spearman = np.corrcoef(*ranks)[0, 1] if len(found) > 2 else 0
checks.require(f"{len(found)} surface triangles seen whole (at least 10): the colour at each "
               f"rises with its cell's stress (Spearman rank correlation {spearman:.3f}, at "
               f"least 0.98)", len(found) >= 10 and spearman >= 0.98)
middle = (low + high) / 2
wrong = [(v, c) for v, c in found if abs(v - middle) > 0.1 * (high - low)
         and (v > middle) != (c > 0)]
checks.require(f"the triangles with a stress more than 10 % of the range ({low:.3g} to "
               f"{high:.3g}) above its middle are warm-coloured, those below it cool (wrong: "
               f"{wrong})", not wrong)


def processes_of_group(group):
    """The live processes (not zombies) of a process group, by /proc: [(pid, command)]"""
    found = []
    for stat in pathlib.Path("/proc").glob("[0-9]*/stat"):
        try:
            # the command is in parentheses and may hold spaces: the fields follow the last ')'
            text = stat.read_text()
        except OSError:
            continue
        fields = text[text.rindex(")") + 2:].split()
        if fields[0] != "Z" and int(fields[2]) == group:
            found.append((int(stat.parent.name), text[text.index("(") + 1:text.rindex(")")]))
    return found


def under_way(group):
    """The processes of a render once its display server and pvbatch are up (a render takes
    2 s on a quiet machine: a fixed wait could outlast it), within 30 s"""
    for _ in range(600):
        running = processes_of_group(group)
        if {"Xvfb", "pvbatch"} <= {command for _, command in running}:
            break
        time.sleep(0.05)
    return running


interrupted = subprocess.Popen(view(0, out / "interrupted.png"), stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, start_new_session=True)
under_way(interrupted.pid)
os.killpg(interrupted.pid, signal.SIGINT)
interrupted.wait()
for _ in range(100):
    left = processes_of_group(interrupted.pid)
    if not left:
        break
    time.sleep(0.1)
checks.require(f"an interrupted render left no process behind within 10 s (left: "
               f"{[command for _, command in left]})", not left)
if left:
    os.killpg(interrupted.pid, signal.SIGKILL)  # not to hold up the rest of the suite

killed = subprocess.Popen(view(0, out / "killed.png"), stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL, start_new_session=True)
running = under_way(killed.pid)
displays = [[a for a in pathlib.Path(f"/proc/{pid}/cmdline").read_text().split("\0")
             if a.startswith(":")] for pid, command in running if command == "Xvfb"]
checks.require(f"the render's display {displays} is above :9 (hwloc's GL probe, in every MPI "
               f"process started without gelx's environment, opens :0 to :9)",
               len(displays) == 1 and len(displays[0]) == 1 and int(displays[0][0][1:]) >= 10)
for _ in range(3):  # the whole process group but the display server, SIGKILL: no trap runs
    for pid, command in processes_of_group(killed.pid):
        if command != "Xvfb":
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
killed.wait()
start = time.time()
first, _ = render(0, timeout=120)
print(f"after a render killed midway, the next took {time.time() - start:.0f} s")
try:
    os.killpg(killed.pid, signal.SIGKILL)  # its Xvfb, if it outlived the render
except ProcessLookupError:
    pass
changed = np.mean(np.any(np.abs(first - last) > 0.1, axis=2))
checks.require(f"the first step's picture differs from the last's in {changed:.1%} of the pixels "
               f"(at least 5 %)", changed > 0.05)
checks.finish()
