"""What the scenes' study scripts (bench.py, sweep.py) share: running a compiled scene under
MPI and reading its summary, and Richardson extrapolation over mesh levels."""
import json
import os
import subprocess

# Open MPI refuses root without these (CI and the dev machines run as root); more ranks than
# cores are allowed so that a 2-rank study also runs on a 1-core machine; no binding, which
# puts every run's rank 0 on core 0, so that two 1-rank runs side by side shared one core
MPI_ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_MCA_hwloc_base_binding_policy="none")


def run_scene(build, scene, folder, ranks, options, reuse=False):
    """Run build/demos/<scene>/gelx-<scene> on `ranks` MPI ranks with `options` (a list of
    strings) into `folder`, quietly; return its summary.json. With `reuse`, a folder that
    already holds a completed run is not run again (an interrupted study resumes)."""
    summary_file = folder / "summary.json"
    if not (reuse and summary_file.exists()
            and json.loads(summary_file.read_text())["status"] == "completed"):
        exe = build / "demos" / scene / f"gelx-{scene}"
        subprocess.run(["mpirun", "-np", str(ranks), str(exe), "--output", str(folder),
                        *options],
                       check=True, stdout=subprocess.DEVNULL, env=MPI_ENV)
    return json.loads(summary_file.read_text())


def richardson(h, v):
    """Limit and order of v(h) = v0 + c h^p from three levels, coarse to fine, or the finest
    value and nan when the three do not converge monotonically at an order p > 0.1."""
    (h1, h2, h3), (v1, v2, v3) = h, v
    ratio = (v2 - v3) / (v1 - v2) if v1 != v2 else -1
    slowest = (h2**0.1 - h3**0.1) / (h1**0.1 - h2**0.1)  # the ratio at p = 0.1
    if not 0 < ratio < slowest:
        return v3, float("nan")
    lo, hi = 0.1, 8.0  # bisection on p: the ratio falls as p grows
    for _ in range(200):
        p = 0.5 * (lo + hi)
        if (h2**p - h3**p) / (h1**p - h2**p) > ratio:
            lo = p
        else:
            hi = p
    c = (v1 - v2) / (h1**p - h2**p)
    return v3 - c * h3**p, p
