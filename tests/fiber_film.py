"""Check the fiber_film scene (demos/fiber_film: a fiber-reinforced gel film, one layer of
fibers thick, contracting in time after a temperature step) against what holds whatever the
transient's details:

1. The equilibrium it tends to. Once the solvent has left (mu = 0 throughout), the film's
   displacement solves the elastic problem of the Flory-Rehner gel at chi(T_f) on the same
   mesh and P2 space, which demos/fiber_gel solves directly with its own kernels
   (forms/gel.py: the energy in u alone, chi(T), not the (u, mu) form of forms/_swelling.py)
   and the same conditions (--cell film: the face x = D/2 free, y = D/2 and z = L/2 plane at
   free macro displacements). The transient's last step (t_end = 1e-3 s, about 200 t95, where
   the slowest mode has decayed below round-off) must give its alpha_par and alpha_perp to
   1e-9 (both solves converge to Newton's tolerance: measured 1e-16).
2. That comparison can tell the film from the periodic cell: fiber_gel's default cell (the
   face x = D/2 plane too, an unbounded composite) contracts differently by more than 1e-4
   (measured 5.7e-4 in alpha_par), so the film's own conditions, not the cell's, are solved.
3. The transient is one: at the end of the temperature's ramp (1e-8 s, against t95 ~ 5e-6 s)
   alpha_perp has covered less than 20 % of its change (measured 7 %: the solvent cannot
   leave at once; what does is the drained skin, one cell of 5 nm of the 12.5 nm half film on
   this mesh). With the rate not carried to the forms through the constraint's prolongation
   (w' = 0) the run fails at its first step.
4. The Mandel-Cryer effect: the solvent's chemical potential in the mid-plane rises above its
   undrained value phi_i^2 (chi_f - chi_i) (the closed form at F = I, with chi_i and chi_f
   those of the free gel at phi_i and phi_i / alpha0^3, Eq. 4.7, 4.13) before it falls, as the
   drained skin contracts and squeezes the core (measured 1.15 times; at least 1.05 asked,
   against 1 for a diffusion that does not feel the deformation), and falls to the bath's 0
   (below 1e-6 of the undrained value at the end). Watched failing: with the ramp 1e-4 s
   (twenty t95: drained all along) the peak is 0.072 times the undrained value; the same run
   fails check 3 (100 %). With 1e-6 s it still peaks at 1.147 (check 3: 28.5 %).

The film of one layer of fibers (D = 25 nm thick), or with LAYERS (ctest: 2 at 2 ranks) a
thicker one (3 layers, 75 nm), whose further fibers translate at free macro unknowns in both
scenes. Measured values above are for one layer; for two: 3e-12 in 1 (the slowest mode, 9
times slower, not quite gone at t_end), 2.0e-4 in 2, 2.3 % in 3 and 1.12 times in 4.

usage: fiber_film.py GELX_FIBER_FILM GELX_FIBER_GEL WORK_DIR [MPIEXEC NP [LAYERS]]
"""
import json
import math
import pathlib
import subprocess
import sys

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)

film_binary, gel_binary, work = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
launcher = [sys.argv[4], "-np", sys.argv[5]] if len(sys.argv) > 5 else []
layers = sys.argv[6] if len(sys.argv) > 6 else "1"
checks = Checks()


def run(binary, name, args):
    folder = work / name
    subprocess.run(launcher + [binary, "--output", str(folder)] + args, check=True,
                   stdout=subprocess.DEVNULL)
    return json.loads((folder / "summary.json").read_text()), folder


film, folder = run(film_binary, "transient", ["--layers", layers])
rows = read_table(folder / "steps.csv")
p = film["parameters"]
same = ["--l", str(p["l"]), "--L", str(p["L"]), "--D", str(p["D"]), "--d", str(p["d"]),
        "--h_fiber", str(p["h_fiber"]), "--h_far", str(p["h_far"]), "--alpha0", str(p["alpha0"])]
equilibrium, _ = run(gel_binary, "equilibrium_film",
                     same + ["--cell", "film", "--layers", layers])
cell, _ = run(gel_binary, "equilibrium_cell", same)

# 1. The equilibrium
for key in ("alpha_par", "alpha_perp"):
    checks.absolute(f"{key} at t = {film['time']:.3g} s against fiber_gel --cell film",
                    film[key], equilibrium[key], 1e-9)

# 2. The film is not the periodic cell
difference = abs(equilibrium["alpha_par"] - cell["alpha_par"])
checks.require(f"the film's alpha_par differs from the periodic cell's by {difference:.3g} "
               f"(>= 1e-4)", difference >= 1e-4)

# 3. A transient
ramp_end = next(r for r in rows if float(r["time"]) >= p["ramp_time"])
covered = (1 - float(ramp_end["alpha_perp"])) / (1 - film["alpha_perp"])
checks.require(f"at the ramp's end (t = {float(ramp_end['time']):.3g} s) alpha_perp has covered "
               f"{100 * covered:.3g} % of its change (< 20 %)", 0 < covered < 0.2)

# 4. The mid-plane's solvent: undrained, above it, drained
def chi_free(phi, n):
    """chi of the free gel in equilibrium at volume fraction phi, thesis Eq. 4.7"""
    return 0.5 * n * (1 / phi - 2 * phi ** (-5 / 3)) - math.log(1 - phi) / phi ** 2 - 1 / phi


# chi(T) takes the free gel from phi_i at T_i to phi_i / alpha0^3 at T_f (Eq. 4.7, 4.13)
phi_i, n = p["phi_i"], p["n_nu_vm"]
undrained = phi_i ** 2 * (chi_free(phi_i / p["alpha0"] ** 3, n) - chi_free(phi_i, n))
peak = max(float(r["mu_midplane"]) for r in rows)
checks.require(f"the mid-plane's mu peaks at {peak / undrained:.4g} times the undrained "
               f"phi_i^2 (chi_f - chi_i) = {undrained:.5g} (>= 1.05: Mandel-Cryer)",
               peak >= 1.05 * undrained)
checks.absolute("the mid-plane's mu at the end over the undrained value",
                float(rows[-1]["mu_midplane"]) / undrained, 0.0, 1e-6)

print(f"t = {film['time']:.3g} s: alpha_par = {film['alpha_par']:.10g}, alpha_perp = "
      f"{film['alpha_perp']:.10g}; periodic cell: {cell['alpha_par']:.10g}, "
      f"{cell['alpha_perp']:.10g}")
checks.finish()
