"""The bistrip's --noise: a random imperfection of stated amplitude added to the seeded mode.

The mirror-symmetric mode 1 keeps a deterministic path symmetric to round-off; --noise A adds
the random shape of --seed random (--harmonics sines along the strip, the generator seeded by
--random_seed) at amplitude A to break it (demos/bistrip/README.md, "With inertia"). The check
rebuilds that shape here from its definition, independently of the scene: std::mt19937's raw
draws are numpy's legacy MT19937 with the same seed, v_x(z) = sum_k a_k sin(k pi z / L),
v_y(z) = sum_k b_k sin(k pi z / L), normalised by the largest component over the Q2 nodes (the
vertices and mid-slab layers), and compares the seeded meshes' node shifts with A v:
- without the mode (--imperfection 0) the shift is A v at every vertex (round-off: 1e-12 mm);
- with the mode, the shift the noise adds is the same (the two seeds superpose);
- another --random_seed gives another shape, mirror-asymmetric about mid-length.
Each run stops after one step of the flow (the mesh is written with the first output).

usage: bistrip_noise.py SCENE_BINARY WORK_DIR [MPIEXEC]
"""
import pathlib
import subprocess
import sys

import h5py
import numpy as np

from checks import Checks

binary, work = sys.argv[1], pathlib.Path(sys.argv[2])
launcher = [sys.argv[3], "-np", "1"] if len(sys.argv) > 3 else []
L, NZ, HARMONICS, NOISE = 300.0, 20, 12, 2e-3
checks = Checks()


def seeded_nodes(name, *options):
    """The seeded mesh's vertices of a run of the scene with these options."""
    folder = work / name
    subprocess.run(launcher + [binary, "--output", str(folder), "--nz", str(NZ), "--modes", "1",
                               "--harmonics", str(HARMONICS), "--stop_after_steps", "1",
                               *options], check=True, stdout=subprocess.DEVNULL)
    (mesh_file,) = sorted((folder / "fields").glob("mesh_*.h5"))[:1]
    with h5py.File(mesh_file, "r") as f:
        return np.array(f["Mesh/mesh/geometry"])


def random_shape(seed, z):
    """Bistrip::random_imperfection's shape (x, y components) at the heights z."""
    bits = np.random.MT19937(0)
    bits._legacy_seeding(seed)  # std::mt19937(seed): the same raw 32-bit draws
    draws = 2.0 * bits.random_raw(2 * HARMONICS) / 4294967295.0 - 1
    a, b = draws[0::2], draws[1::2]
    k = np.arange(1, HARMONICS + 1)
    sines = np.sin(np.outer(z, k) * np.pi / L)
    return sines @ a, sines @ b


def expected_shift(seed, z):
    """NOISE times the shape normalised by its largest component over the Q2 nodes, whose
    heights are the vertex layers and the mid-slab layers of the uniform slabs."""
    largest = max(np.abs(c).max() for c in random_shape(seed, np.linspace(0, L, 2 * NZ + 1)))
    vx, vy = random_shape(seed, z)
    return NOISE * np.column_stack([vx, vy, np.zeros_like(z)]) / largest


work.mkdir(parents=True, exist_ok=True)
plain = seeded_nodes("plain", "--imperfection", "0")
noise = seeded_nodes("noise", "--imperfection", "0", "--noise", str(NOISE))
mode = seeded_nodes("mode")
mode_noise = seeded_nodes("mode_noise", "--noise", str(NOISE))
other = seeded_nodes("other_seed", "--imperfection", "0", "--noise", str(NOISE),
                     "--random_seed", "2")

z = plain[:, 2]
for name, shift, seed in (("--noise alone", noise - plain, 1),
                          ("--noise beside mode 1", mode_noise - mode, 1),
                          ("--random_seed 2", other - plain, 2)):
    error = np.abs(shift - expected_shift(seed, z)).max()
    checks.require(f"{name}: the seeded shift is NOISE times the rebuilt random shape at "
                   f"{len(z)} vertices (largest {np.abs(shift).max():.6g} mm, error "
                   f"{error:.2e} mm, tol 1e-12 mm)", error <= 1e-12)
difference = np.abs((other - plain) - (noise - plain)).max()
checks.require(f"--random_seed 2 moves the nodes otherwise than seed 1 ({difference:.3g} mm "
               f"apart, at least NOISE / 10)", difference >= NOISE / 10)
# Mirror asymmetry of the noise's lateral shift: pair each vertex layer z with L - z
layers = np.unique(np.round(z, 9))
shift = noise - plain
lateral = np.array([shift[np.abs(z - zl) < 1e-9, :2].mean(axis=0) for zl in layers])
asymmetry = min(np.abs(lateral - lateral[::-1]).max(), np.abs(lateral + lateral[::-1]).max())
checks.require(f"the noise is neither mirror-symmetric nor antisymmetric about mid-length "
               f"(largest departure from both {asymmetry:.3g} mm, at least NOISE / 10)",
               asymmetry >= NOISE / 10)
checks.finish()
