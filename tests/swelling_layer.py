"""Check the swelling gel (demos/swelling: solvent diffusion coupled to large deformation)
against closed forms of a layer bonded to a rigid substrate, computed here from the free
energy the form file writes, in principal stretches (thesis Eq. 4.28 with -mu (J - phi0)):

    U(l) = n/2 phi0 (phi0^(-2/3) (2 + l^2) - 3 - ln(l / phi0)) + (l - phi0) ln(1 - phi0/l)
           + chi phi0 (1 - phi0/l)

for the layer stretched by l through its thickness (held laterally, in units of kT/nu). In one
dimension the free surface leaves no stress through the thickness, so everywhere
mu = P(l) = dU/dl (derivatives by central differences here): the layer is at its local
equilibrium with the solvent at every instant, and the solvent's conservation,
dl/dt = d/dz (D (l - phi0) / l^2 dmu/dz), is one nonlinear diffusion equation.

1. The reference state is stress-free at mu0 = P(1) (the scene's mu0 from cpp/theory's Eq. 4.7:
   to 1e-9).
2. The linear limit: a small step of mu (5e-6 kT: the thickness changes by 1e-4) against
   Terzaghi's consolidation series, dh/dh_inf = 1 - sum 8/((2m+1)^2 pi^2)
   exp(-(2m+1)^2 pi^2 c_v t / (4 H^2)), with the coefficient c_v = D (1 - phi0) P'(1) and
   dh_inf = H (l_inf - 1), P(l_inf) = mu, the scene's smooth step of mu over --ramp_time
   superposed (Duhamel's integral, here): within 1 % at T_v = c_v t / H^2 = 0.01, 0.05, 0.2
   and 0.8; early on dh/dh_inf = 2 sqrt(T_v / pi), the uptake's sqrt(t).
3. The large jump: the layer in pure solvent (chi = 0.4: it swells 2.67-fold), whose thickness
   history is that of the nonlinear diffusion equation above in l, dl/dt = d/dz (K(l) dl/dz),
   K = D (l - phi0) P'(l) / l^2, l = 1 at t = 0, no flux at the substrate and at the surface
   P(l) = mu(t) (the smooth step), solved here by finite volumes (800 cells, scipy's BDF at
   rtol 1e-9; K with P' by hand, checked against the energy's second difference to 1e-4, its
   round-off 1e-5): within 1 % at the times of 10, 30, 60 and 90 % of the run's change
   (measured 0.6 % at the first on the scene's 40 graded cells, 0.28 % on 80); until the front
   reaches the substrate the uptake grows as sqrt(t) (its log-log slope 0.5 within 0.02 over
   t = 10 to 100 s, past the ramp). The swelling front, the reference depth where mu is
   half-way from mu0 to the surface's 0, at the same times within 2 % (the mesh's error:
   measured 1.0, 0.35, 0.23, 0.15 % on the scene's 40 cells, 0.32, 0.25, 0.15, 0.15 % on 80).
   The same with chi linear in phi, chi = 0.3 + 0.6 phi (P' by hand with chi + dchi_dphi
   (3 phi - 1) in chi's place, checked against the energy's second difference; measured 6.5e-3
   at the first time, 6.8e-3 for the front).
4. The equilibrium limit: the layer in pure solvent (mu = 0) followed to equilibrium, its
   thickness H l_inf with P(l_inf) = 0, to 1e-6, for chi = 0.2, 0.4, 0.6 at N nu = 1e-3; and
   the same by --path equilibrium, which solves for that state without time (by load steps
   in mu, which a transient left at its default 3000 s would miss by 56 %).

5. Free swelling: the eighth of a free cube (--sides free, all faces in pure solvent) followed
   to equilibrium swells isotropically, V/V0 = a^3 with dU_iso/da = 0 for the energy of the
   stretch a I, U_iso(a) = n/2 phi0 (3 phi0^(-2/3) a^2 - 3 - ln(a^3/phi0))
   + (a^3 - phi0) ln(1 - phi0/a^3) + chi phi0 (1 - phi0/a^3), to 1e-6 (2 x 2 x 2 cells: the
   state is homogeneous); and the same by --path equilibrium.

6. The elements on the linear limit's step (5e-6 kT, smoothed over 0.1 s, to 100 s, fields at
   4 times): diffusion keeps mu between mu0 and the surface's value, so mu below mu0 is the
   discretisation's. Taylor-Hood Q2-Q1 on the graded cells stays within 1 % of the step
   below mu0 (measured 6.7e-4 at t = 1.06 s); equal-order Q1-Q1 (--element q1q1), which is not
   inf-sup stable, dips at least 3 times deeper (measured 6.3e-3, 9.5 times).

7. chi linear in phi, chi(phi) = chi + dchi_dphi phi (--dchi_dphi; chi = 0.3, dchi_dphi = 0.6:
   the osmotic pressure then holds chi_bar = chi(phi) - (1 - phi) dchi_dphi, Eq. 4.20): mu0 of
   the reference state against P(1) of the energy with that chi (1e-9), and by --path
   equilibrium the layer's thickness in pure solvent (P(l_inf) = 0: l_inf = 4.63, against 2.67
   at chi = 0.4 constant) and the free cube's V/V0 (1e-6).

8. CVODE's test on the Newton correction (-swelling_newton_test correction): the large jump at
   chi = 0.4 passes the checks of 3 with it, in fewer Newton iterations than with the default
   test on the residual (measured 95 against 124: after the ramp one update a step suffices;
   its thickness moves by at most 5e-5 of itself, against 1.6e-6 for Newton to 1e-8).

usage: swelling_layer.py GELX_SWELLING WORK_DIR [MPIEXEC NP]
"""
import json
import math
import pathlib
import subprocess
import sys

import numpy as np
from scipy.integrate import cumulative_trapezoid, solve_ivp
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq
from scipy.sparse import diags

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import FieldSeries, read_table  # noqa: E402  (demos/fields.py)

binary, work = sys.argv[1], pathlib.Path(sys.argv[2])
launcher = [sys.argv[3], "-np", sys.argv[4]] if len(sys.argv) > 4 else []
checks = Checks()
N_NU, LAMBDA0, H, D = 1e-3, 1.5, 1.0, 1e-3
PHI0 = LAMBDA0**-3


def energy(l, chi, dchi_dphi=0):
    phi = PHI0 / l
    return (N_NU / 2 * PHI0 * (PHI0**(-2 / 3) * (2 + l * l) - 3 - np.log(l / PHI0))
            + (l - PHI0) * np.log(1 - phi) + (chi + dchi_dphi * phi) * PHI0 * (1 - phi))


def stress(l, chi, dchi_dphi=0, h=1e-6):
    return (energy(l + h, chi, dchi_dphi) - energy(l - h, chi, dchi_dphi)) / (2 * h)


def stiffness(l, chi, dchi_dphi=0, h=1e-4):
    return (energy(l + h, chi, dchi_dphi) - 2 * energy(l, chi, dchi_dphi)
            + energy(l - h, chi, dchi_dphi)) / h**2


def dP(l, chi, dchi_dphi=0):
    """P'(l) by hand: the mobility's, where the differences' round-off (1e-8 of it) would make
    the finite-volume solver's own difference Jacobian useless. With chi(phi) the mixing
    energy's second derivative holds chi + dchi_dphi (3 phi - 1) in chi's place."""
    stiffness_chi = chi + dchi_dphi * (3 * PHI0 / l - 1)
    return (N_NU * PHI0**(1 / 3) + N_NU * PHI0 / (2 * l**2) + PHI0 / (l * (l - PHI0))
            - PHI0 / l**2 - 2 * stiffness_chi * PHI0**2 / l**3)


def run(name, *options):
    folder = work / name
    subprocess.run(launcher + [binary, "--output", str(folder), "--H", str(H),
                               "--lambda0", str(LAMBDA0), "--n", str(N_NU), "--D", str(D),
                               *options], check=True, stdout=subprocess.DEVNULL)
    summary = json.loads((folder / "summary.json").read_text())
    rows = read_table(folder / "steps.csv")
    return summary, rows


# 1, 2: the linear limit at chi = 0.4
chi = 0.4
mu0 = stress(1.0, chi)
c_v = D * (1 - PHI0) * stiffness(1.0, chi)
step = 5e-6
l_inf = brentq(lambda l: stress(l, chi) - (mu0 + step), 1 - 1e-2, 1 + 1e-2, xtol=1e-15)
dh_inf = H * (l_inf - 1)
T_end, ramp = 1.0, 1.0
summary, rows = run("terzaghi", "--chi", str(chi), "--mu", repr(mu0 + step),
                    "--ramp_time", str(ramp), "--end_time", str(T_end * H * H / c_v))
checks.relative("mu0 of the reference state against P(1) of the energy", summary["mu0"], mu0,
                1e-9)
t = np.array([float(r["time"]) for r in rows])
dh = np.array([float(r["thickness"]) for r in rows]) - H


def consolidation(T_v):
    m = np.arange(200)
    k = (2 * m + 1) * math.pi / 2
    return 1 - np.sum(2 / k**2 * np.exp(-k**2 * T_v))


def ramped(time):
    """Duhamel: the smooth step a(s) = s^3 (10 - 15 s + 6 s^2), s = tau / ramp, superposed."""
    tau = np.linspace(0, min(time, ramp), 2001)
    s = tau / ramp
    rate = 30 * s**2 * (1 - s)**2 / ramp
    values = [consolidation(c_v * (time - x) / H**2) if time > x else 0.0 for x in tau]
    return np.trapz(rate * np.array(values), tau)


for T_v in (0.01, 0.05, 0.2, 0.8):
    time = T_v * H * H / c_v
    measured = np.interp(time, t, dh) / dh_inf
    checks.relative(f"dh/dh_inf at T_v = {T_v} (t = {time:.4g} s) against Terzaghi "
                    f"(early: 2 sqrt(T_v/pi) = {2 * math.sqrt(T_v / math.pi):.4f})",
                    measured, ramped(time), 1e-2)

# 3. The large jump against the finite-volume solution of the diffusion equation, at chi = 0.4
#    and with chi linear in phi


def large_jump(name, chi, dchi_dphi=0, *options, label=""):
    """The checks of 3 on a run with `options`; returns its Newton iterations."""
    label = (label or f"large jump, chi = {chi}") + (f" + {dchi_dphi} phi" if dchi_dphi else "")
    mu0 = stress(1.0, chi, dchi_dphi)
    l_inf = brentq(lambda l: stress(l, chi, dchi_dphi), 1 + 1e-9, 20.0, xtol=1e-15)
    summary, rows = run(name, "--chi", str(chi), "--dchi_dphi", str(dchi_dphi), "--mu", "0",
                        "--ramp_time", str(ramp), "--end_time", "3000", *options)
    t = np.array([float(r["time"]) for r in rows])
    dh = np.array([float(r["thickness"]) for r in rows]) - H

    # Finite volumes on the scene's grading (cells shrinking towards the surface, where the
    # swollen skin is micrometres thin early on), the flux in the Kirchhoff variable
    # Phi(l) = int K dl, exact between cells whatever K's variation (with K's face average,
    # the skin's small K made 800 even cells err by 3 % at 25 s): 200, 800 and 3200 cells gave
    # 0.016225, 0.016234, 0.016234 mm at 24.55 s (chi = 0.4)
    cells = 800
    faces = H * (1 - (1 - np.linspace(0, 1, cells + 1))**2)
    size = np.diff(faces)
    gap = np.diff(np.concatenate((0.5 * (faces[1:] + faces[:-1]), [H])))
    for l in (1.0, 1.5, 2.5):
        checks.relative(f"{label}: P'({l}) by hand against the energy's second difference",
                        dP(l, chi, dchi_dphi), stiffness(l, chi, dchi_dphi), 1e-4)

    def mobility(l):
        return D * (l - PHI0) / l**2 * dP(l, chi, dchi_dphi)

    table = np.linspace(0.9, l_inf + 0.1, 200001)
    kirchhoff = CubicSpline(table, cumulative_trapezoid(mobility(table), table, initial=0))

    def surface_stretch(time):
        s = min(time / ramp, 1.0)
        mu = mu0 * (1 - s**3 * (10 - 15 * s + 6 * s * s))
        return brentq(lambda l: stress(l, chi, dchi_dphi) - mu, 1 - 1e-3, l_inf + 1e-3,
                      xtol=1e-14)

    def rate(time, l):
        potential = kirchhoff(np.concatenate((l, [surface_stretch(time)])))
        flux = np.concatenate(([0.0], -np.diff(potential) / gap))  # none through the substrate
        return -np.diff(flux) / size

    pattern = diags([1, 1, 1], [-1, 0, 1], shape=(cells, cells))
    times = np.interp([0.1, 0.3, 0.6, 0.9], dh / dh[-1], t)
    solution = solve_ivp(rate, (0, times[-1]), np.ones(cells), method="BDF", t_eval=times,
                         rtol=1e-9, atol=1e-12, jac_sparsity=pattern)
    front = np.array([float(r["front_depth"]) for r in rows])
    centres = 0.5 * (faces[1:] + faces[:-1])

    def front_depth(l):
        """The reference depth below the surface where mu = P(l) is half-way from mu0 to the
        surface's 0, on the cells' centres and the surface, linearly between them."""
        z = np.concatenate(([H], centres[::-1]))
        mu = np.concatenate(([0.0], stress(l[::-1], chi, dchi_dphi)))
        k = np.argmax(mu < mu0 / 2)
        return H - (z[k - 1] + (mu0 / 2 - mu[k - 1]) / (mu[k] - mu[k - 1]) * (z[k] - z[k - 1]))

    for time, l in zip(times, solution.y.T):
        checks.relative(f"{label}: h - H at t = {time:.4g} s against the diffusion equation",
                        np.interp(time, t, dh), (l * size).sum() - H, 1e-2)
        checks.relative(f"{label}: the front's depth at t = {time:.4g} s against the diffusion "
                        "equation's", np.interp(time, t, front), front_depth(l), 2e-2)
    early = (t > 10 * ramp) & (t < 100 * ramp)
    slope = np.polyfit(np.log(t[early]), np.log(dh[early]), 1)[0]
    checks.absolute(f"{label}: the uptake's log-log slope over t = 10 ... 100 s (sqrt(t): 0.5)",
                    slope, 0.5, 0.02)
    return summary["newton_iterations"]


newton_residual_test = large_jump("large_jump", 0.4)
large_jump("large_jump_chi_of_phi", 0.3, 0.6)
# 8. The same jump with each step's Newton iteration stopped by CVODE's test on the correction
#    against TS's tolerance (gelx::TransientProblem) instead of 1e-3 of the first residual
newton_correction_test = large_jump("large_jump_correction_test", 0.4, 0,
                                    "-swelling_newton_test", "correction",
                                    label="large jump, chi = 0.4, CVODE's correction test")
checks.require(f"the correction test took {newton_correction_test} Newton iterations, fewer "
               f"than the residual's test ({newton_residual_test}): it stops after one update "
               "that is small against TS's tolerance", newton_correction_test
               < newton_residual_test)

# 4. The equilibrium limit in pure solvent
for chi in (0.2, 0.4, 0.6):
    l_inf = brentq(lambda l: stress(l, chi), 1 + 1e-9, 20.0, xtol=1e-15)
    c_v = D * (l_inf - PHI0) / l_inf**2 * stiffness(l_inf, chi)
    summary, rows = run(f"equilibrium_chi{chi}", "--chi", str(chi), "--mu", "0",
                        "--ramp_time", "1", "--end_time", str(20 * H * H * l_inf**2 / c_v))
    checks.relative(f"chi = {chi}: the thickness at equilibrium against H lambda_inf = "
                    f"{H * l_inf:.9f} (P(lambda_inf) = 0)", summary["thickness"], H * l_inf,
                    1e-6)
    summary, rows = run(f"equilibrium_path_chi{chi}", "--chi", str(chi), "--mu", "0",
                        "--path", "equilibrium")
    checks.relative(f"chi = {chi}, --path equilibrium: the thickness against H lambda_inf",
                    summary["thickness"], H * l_inf, 1e-6)
# 5. Free swelling of a cube
chi = 0.4


def isotropic_energy(a, chi, dchi_dphi=0):
    phi = PHI0 / a**3
    return (N_NU / 2 * PHI0 * (3 * PHI0**(-2 / 3) * a * a - 3 - np.log(a**3 / PHI0))
            + (a**3 - PHI0) * np.log(1 - phi) + (chi + dchi_dphi * phi) * PHI0 * (1 - phi))


a = brentq(lambda a: (isotropic_energy(a + 1e-6, chi) - isotropic_energy(a - 1e-6, chi)) / 2e-6,
           1 + 1e-6, 5.0, xtol=1e-15)
summary, rows = run("free_cube", "--chi", str(chi), "--mu", "0", "--sides", "free", "--W",
                    str(H), "--nx", "2", "--nz", "2", "--end_time", "1e8")
checks.relative(f"free cube, chi = {chi}: V/V0 at equilibrium against a^3 = {a**3:.9f} "
                f"(dU_iso/da = 0)", summary["swelling_ratio"], a**3, 1e-6)
summary, rows = run("free_cube_path", "--chi", str(chi), "--mu", "0", "--sides", "free", "--W",
                    str(H), "--nx", "2", "--nz", "2", "--path", "equilibrium")
checks.relative("free cube, --path equilibrium: V/V0 against a^3", summary["swelling_ratio"],
                a**3, 1e-6)

# 6. Equal order against Taylor-Hood: mu's largest dip below mu0, in units of the step
mu0 = stress(1.0, chi)
dips = {}
for element in ("q2q1", "q1q1"):
    run(f"element_{element}", "--chi", str(chi), "--element", element, "--mu",
        repr(mu0 + step), "--ramp_time", "0.1", "--end_time", "100", "--outputs", "4")
    series = FieldSeries(work / f"element_{element}")
    dips[element] = max((mu0 - series.field("chemical_potential", k).min()) / step
                        for k in range(len(series.times)))
checks.require(f"Q2-Q1: mu's largest dip below mu0 is {dips['q2q1']:.2e} of the step "
               "(at most 1e-2)", dips["q2q1"] <= 1e-2)
checks.require(f"Q1-Q1: its dip {dips['q1q1']:.2e} is at least 3 times Q2-Q1's",
               dips["q1q1"] >= 3 * dips["q2q1"])

# 7. chi linear in phi, chi(phi) = chi + dchi_dphi phi: the reference state's mu0 and the
#    equilibrium in pure solvent of the layer and of the free cube, from the energy with that
#    chi (as 1 and 4, 5), to 1e-9 and 1e-6
chi, dchi_dphi = 0.3, 0.6
l_inf = brentq(lambda l: stress(l, chi, dchi_dphi), 1 + 1e-9, 20.0, xtol=1e-15)
summary, rows = run("chi_of_phi_layer", "--chi", str(chi), "--dchi_dphi", str(dchi_dphi),
                    "--mu", "0", "--path", "equilibrium")
checks.relative(f"chi = {chi} + {dchi_dphi} phi: mu0 against P(1) of the energy",
                summary["mu0"], stress(1.0, chi, dchi_dphi), 1e-9)
checks.relative(f"chi = {chi} + {dchi_dphi} phi: the layer's thickness at equilibrium against "
                f"H lambda_inf = {H * l_inf:.9f}", summary["thickness"], H * l_inf, 1e-6)
a = brentq(lambda a: (isotropic_energy(a + 1e-6, chi, dchi_dphi)
                      - isotropic_energy(a - 1e-6, chi, dchi_dphi)) / 2e-6,
           1 + 1e-6, 5.0, xtol=1e-15)
summary, rows = run("chi_of_phi_cube", "--chi", str(chi), "--dchi_dphi", str(dchi_dphi),
                    "--mu", "0", "--sides", "free", "--W", str(H), "--nx", "2", "--nz", "2",
                    "--path", "equilibrium")
checks.relative(f"chi = {chi} + {dchi_dphi} phi: the free cube's V/V0 against a^3 = {a**3:.9f}",
                summary["swelling_ratio"], a**3, 1e-6)
checks.finish()
