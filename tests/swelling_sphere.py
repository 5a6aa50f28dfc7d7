"""The free gel sphere's slowest decay (demos/swelling --shape ellipsoid, W = H: the eighth
x, y, z > 0 of a sphere of radius a, in solvent on its surface) against the linear theory.

Linearised about the stress-free reference state, the gel is a poroelastic solid of
incompressible constituents: shear modulus G = N nu phi0^(1/3) (the I1 term of the energy;
units of kT/nu), oedometric modulus M = P'(1) (the layer's, as in tests/swelling_layer.py),
mobility D (1 - phi0). With a spherically symmetric field, equilibrium makes mu = M e + f(t)
(e = div u), so e diffuses, de/dt = c lap e with c = D (1 - phi0) M. At r = a, mu = mu_s and
sigma_rr = M e - 4 G u/r - mu = 0, where u(a)/a is a third of e's mean over the sphere: the
departure w = e - e_inf obeys M w(a) = 4/3 G mean(w). Modes w = j0(k r) exp(-c k^2 t) then
need x = k a to solve

    eta x^2 sin x = sin x - x cos x,    eta = M / (4 G),

so the volume's gap to equilibrium decays as exp(-t / tau), tau = a^2 / (x1^2 c), x1 the first
root (Tanaka and Fillmore's tau = a^2 / (pi^2 c) is the limit eta -> infinity, the shear
modulus negligible). At N nu = 1e-2 (eta = 2.35) x1 = 2.993: tau is 10 % longer than
Tanaka-Fillmore's, which the check tells apart.

1. A small step of mu (5e-6 kT, smoothed over 0.08 tau), followed at fixed BDF2 steps of
   tau / 32 (adaptive steps, whose absolute tolerances do not see the late gap, made the fit
   err by 0.4 %): the log of V_inf - V(t) (V_inf = a_inf^3 of the isotropic energy at the
   surface's mu, exact on any mesh) fitted by a line over t = 1.5 ... 3 tau (the second mode,
   x2 = 6.21, has fallen by e^-5 more than the first at 1.5 tau). On the faceted sphere of 4
   and 6 cells an edge the fitted tau is short by 3.3 % and 1.5 %, the mesh's error, which
   falls as h^2 (see the swelling README for 8 cells): the Richardson extrapolation of the two must be within 1 % of
   tau (measured 0.13 %; the steps' own error: 5e-4 at tau / 25, 8e-5 at tau / 50, 4 cells).
   Tanaka-Fillmore's tau is 9 % below the extrapolation.
2. tau proportional to a^2: the fitted tau / a^2 for a = 0.5, 1 and 2 mm, on the same mesh
   scaled and steps scaled with a^2, equal to 1e-8: in units of a and a^2 / c these are one
   problem, which a diffusivity or a length used inconsistently would break (measured 1e-11).

usage: swelling_sphere.py GELX_SWELLING WORK_DIR [MPIEXEC NP]
"""
import math
import pathlib
import subprocess
import sys

import numpy as np
from scipy.optimize import brentq

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)

binary, work = sys.argv[1], pathlib.Path(sys.argv[2])
launcher = [sys.argv[3], "-np", sys.argv[4]] if len(sys.argv) > 4 else []
checks = Checks()
N_NU, LAMBDA0, CHI, D, STEP = 1e-2, 1.5, 0.4, 1e-3, 5e-6
PHI0 = LAMBDA0**-3


def energy(l):
    """The layer's energy in its thickness stretch l (tests/swelling_layer.py)."""
    return (N_NU / 2 * PHI0 * (PHI0**(-2 / 3) * (2 + l * l) - 3 - np.log(l / PHI0))
            + (l - PHI0) * np.log(1 - PHI0 / l) + CHI * PHI0 * (1 - PHI0 / l))


def isotropic_energy(a):
    """The energy of the stretch a I."""
    return (N_NU / 2 * PHI0 * (3 * PHI0**(-2 / 3) * a * a - 3 - np.log(a**3 / PHI0))
            + (a**3 - PHI0) * np.log(1 - PHI0 / a**3) + CHI * PHI0 * (1 - PHI0 / a**3))


def derivative(f, x, h=1e-6):
    return (f(x + h) - f(x - h)) / (2 * h)


mu0 = derivative(energy, 1.0)
M = (energy(1 + 1e-4) - 2 * energy(1.0) + energy(1 - 1e-4)) / 1e-8
G = N_NU * PHI0**(1 / 3)
eta = M / (4 * G)
x1 = brentq(lambda x: eta * x * x * math.sin(x) - (math.sin(x) - x * math.cos(x)), 2.0,
            math.pi)
c = D * (1 - PHI0) * M
mu = mu0 + STEP
# the swelling ratio at equilibrium: d/da U_iso = 3 a^2 mu (the -mu (J - phi0) term)
a_inf = brentq(lambda a: derivative(isotropic_energy, a) - 3 * a * a * mu, 1 - 1e-3, 1 + 1e-3,
               xtol=1e-16)
print(f"eta = {eta:.4f}, x1 = {x1:.6f} (Tanaka-Fillmore: pi), c = {c:.6g} mm^2/s")


def decay_time(radius, cells):
    """The fitted decay time of V_inf - V on the sphere of `radius` with `cells` an edge."""
    tau = radius**2 / (x1 * x1 * c)
    folder = work / f"a{radius}_n{cells}"
    subprocess.run(launcher + [binary, "--output", str(folder), "--sides", "free", "--shape",
                               "ellipsoid", "--W", str(radius), "--H", str(radius), "--nx",
                               str(cells), "--nz", str(cells), "--grading", "1", "--n",
                               str(N_NU), "--chi", str(CHI), "--lambda0", str(LAMBDA0), "--D",
                               str(D), "--mu", repr(mu), "--ramp_time", str(0.08 * tau),
                               "--end_time", str(3.2 * tau), "--outputs", "1",
                               "-swelling_ts_adapt_type", "none", "-swelling_ts_dt",
                               repr(tau / 32)],
                   check=True, stdout=subprocess.DEVNULL)
    rows = read_table(folder / "steps.csv")
    t = np.array([float(r["time"]) for r in rows])
    gap = a_inf**3 - np.array([float(r["swelling_ratio"]) for r in rows])
    window = (t > 1.5 * tau) & (t < 3 * tau)
    checks.require(f"a = {radius}, {cells} cells: {window.sum()} steps in the fit's window",
                   window.sum() >= 8)
    fitted = -1 / np.polyfit(t[window], np.log(gap[window]), 1)[0]
    print(f"a = {radius} mm, {cells} cells an edge: tau = {fitted:.6g} s "
          f"({fitted / tau - 1:+.2e} against the theory's)")
    return fitted


tau = 1 / (x1 * x1 * c)
coarse, fine = decay_time(1.0, 4), decay_time(1.0, 6)
extrapolated = fine + (fine - coarse) / ((6 / 4)**2 - 1)
checks.relative(f"the decay time, extrapolated from 4 and 6 cells ({coarse:.6g}, {fine:.6g} s), "
                f"against a^2 / (x1^2 c) (Tanaka-Fillmore's a^2 / (pi^2 c) = "
                f"{1 / (math.pi**2 * c):.6g} s)", extrapolated, tau, 1e-2)
for radius in (0.5, 2.0):
    checks.relative(f"tau / a^2 at a = {radius} mm against a = 1 mm, 4 cells",
                    decay_time(radius, 4) / radius**2, coarse, 1e-8)
checks.finish()
