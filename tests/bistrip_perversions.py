"""Check demos/bistrip/perversions.py (the sweep's analysis) on constructed data with known
answers, no scene run:

- tracking: five perversions drift by up to 2 mm per output (tolerance 5 mm), then two at the
  left annihilate (their surviving neighbour is 49 mm away, beyond near = 30 mm), a pair is
  created between two others, and that pair vanishes next to a survivor 8 mm away
  (coalescence, 3 -> 1). The central perversion keeps one identity throughout. Events and
  identities are exact (integers, kinds), so no tolerance;
- winding: a width vector turning by 100 degrees per output about z at a perversion that
  drifts along the strip; the unwrapped winding over 8 outputs is 700 degrees, exact up to the
  linear interpolation of d1 between samples 0.5 mm apart. The frame angle varies by 1 degree
  per mm along Z, so the interpolated vector's angle errs by far less than 1e-6 degrees at
  sample points and the drift is put on sample points: tolerance 1e-9 degrees (round-off);
- helix or V: a circular helix (R = 3 mm, pitch 12 mm, 10 turns) has the torsion
  c / (R^2 + c^2), c = P / 2 pi, so its frame turns tau s / 2 pi over its arc length s; the
  trapezoidal integral of a constant is exact up to the polygon's chords being shorter than
  the arcs (relative 1 - sinc(step/2) ~ 1e-4 for 200 samples per turn): tolerance 1e-3. Its
  lateral spread ratio is 1 over whole turns (to 1e-3 with the discrete samples). A planar
  arch (a V seen from the side, twist 0) is "V-shape" with ratio 0; a line wavering 0.05 mm
  about its axis is "straight".
"""
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos" / "bistrip"))
from checks import Checks  # noqa: E402
import perversions  # noqa: E402

checks = Checks()

# 1. Tracking and events
path = [[50, 100, 150, 200, 250],
        [51, 101, 150, 199, 249],     # drift
        [150, 198, 248],              # 51, 101 annihilate (survivor 150 is 49 mm away)
        [150, 198, 230, 240, 248],    # a pair created
        [150, 198, 246]]              # 230, 240 coalesce into 248 (8 mm away)
ids, found = perversions.track(path, tolerance=5, near=30)
got = [(e["output"], e["kind"], e["positions"], e["survivor"]) for e in found]
expected = [(2, "annihilation", [51, 101], None), (3, "creation", [230, 240], None),
            (4, "coalescence", [230, 240], 248)]
checks.require(f"events {got} (expected {expected})", got == expected)
centre = [ids[k][path[k].index(150)] for k in range(len(path))]
checks.require(f"the central perversion keeps its identity: {centre}", len(set(centre)) == 1)
right = [ids[0][4], ids[1][4], ids[2][2], ids[3][4], ids[4][2]]
checks.require(f"the rightmost perversion keeps its identity: {right}", len(set(right)) == 1)

# 2. Winding
Z = np.arange(0, 300.5, 0.5)
outputs = 8
at = [100 + 2 * k for k in range(outputs)]  # the perversion drifts 2 mm per output
angles = []
for k in range(outputs):
    theta = np.radians(100 * k + (Z - at[k]))  # 1 degree per mm along the strip
    width = np.column_stack([np.cos(theta), np.sin(theta), np.zeros_like(Z)])
    angles.append([perversions.frame_angle(Z, width, at[k])])
turned = perversions.windings([[0]] * outputs, angles)[0]
checks.absolute("winding over 8 outputs (degrees)", turned[-1] - turned[0], 700, 1e-9)

# 3. Helix or V
R, P, turns, per_turn = 3.0, 12.0, 10, 200
c = P / (2 * np.pi)
phi = np.linspace(0, 2 * np.pi * turns, turns * per_turn + 1)
helix = np.column_stack([R * np.cos(phi), R * np.sin(phi), c * phi])
tau = c / (R**2 + c**2)
arc = turns * np.hypot(2 * np.pi * R, P)
h = perversions.shape(helix, np.full(len(phi), tau))
checks.relative("helix: frame turns", h["frame_turns"], tau * arc / (2 * np.pi), 1e-3)
checks.absolute("helix: lateral spread ratio", h["lateral_ratio"], 1.0, 1e-3)
checks.require(f"helix classified as {h['shape']}", h["shape"] == "helix/perversions")
s = np.linspace(0, 1, 201)
arch = np.column_stack([20 * np.sin(np.pi * s), np.zeros_like(s), 200 * s])
v = perversions.shape(arch, np.zeros_like(s))
checks.absolute("planar arch: lateral spread ratio", v["lateral_ratio"], 0.0, 1e-12)
checks.require(f"planar arch classified as {v['shape']}", v["shape"] == "V-shape")
wavy = np.column_stack([0.05 * np.sin(np.pi * s), 0.05 * np.cos(3 * np.pi * s), 250 * s])
straight = perversions.shape(wavy, np.zeros_like(s))
checks.require(f"a line within 0.1 mm of its axis classified as {straight['shape']}",
               straight["shape"] == "straight")
checks.finish()
