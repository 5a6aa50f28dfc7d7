"""Closed forms the Python checks compare the scenes against, computed here from the run's input
parameters and never from what the program under test wrote. Equation numbers refer to the
thesis in shared/seed/.

- Flory-Rehner gel (chapter 4): free swelling (Eq. 4.7), the uniaxially constrained gel
  (Eq. 4.10), the chi(T) line of section 4.4.2 steps (1)-(2), the contraction ratios of
  Eq. 4.13-4.14;
- the inflated incompressible neo-Hookean thick spherical shell: p(lambda_a) and its maximum;
  the compressible Mooney-Rivlin shell's spherically symmetric solution (its radial equation
  integrated);
- Euler's critical load and the elastica of a clamped-free and a clamped-clamped column.

Roots are found by bisection on a bracket that a sign change proves, so nothing here depends
on a starting guess.
"""
import math

import numpy as np


def bisect(f, lo, hi, xtol=1e-15):
    """The root of f in [lo, hi], where f(lo) and f(hi) differ in sign, to an interval of
    xtol * max(1, |root|) (or until the midpoint no longer moves: double precision)."""
    f_lo, f_hi = f(lo), f(hi)
    if f_lo == 0:
        return lo
    if f_hi == 0:
        return hi
    if (f_lo > 0) == (f_hi > 0):
        raise ValueError(f"no sign change on [{lo}, {hi}]: f = {f_lo}, {f_hi}")
    while hi - lo > xtol * max(1.0, abs(lo)):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        f_mid = f(mid)
        if f_mid == 0:
            return mid
        if (f_mid > 0) == (f_lo > 0):
            lo, f_lo = mid, f_mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def unique_root(f, lo, hi, samples=2000):
    """The only root of f on (lo, hi): a scan of `samples` points must find exactly one sign
    change (a function with several roots there is an error, not a choice), then bisection."""
    x = np.linspace(lo, hi, samples)
    values = np.array([f(v) for v in x])
    changes = np.nonzero(np.sign(values[:-1]) * np.sign(values[1:]) <= 0)[0]
    if len(changes) != 1:
        raise ValueError(f"{len(changes)} sign changes on ({lo}, {hi}), expected one")
    k = changes[0]
    return bisect(f, x[k], x[k + 1])


# --- Flory-Rehner gel (thesis section 4.2) -------------------------------------------------
# phi is the polymer volume fraction V_m / V, n = N nu / V_m. The volume fractions met here
# lie in [0.1, 0.99], where -ln(1 - phi)/phi^2 - 1/phi loses at most two digits to
# cancellation (log1p keeps the logarithm itself exact).
PHI_RANGE = (1e-3, 1 - 1e-9)


def mixing(phi):
    """The Flory-Huggins part of Eq. 4.7 and 4.10: -ln(1 - phi)/phi^2 - 1/phi."""
    return -math.log1p(-phi) / phi**2 - 1 / phi


def chi_free_swelling(phi, n):
    """Eq. 4.7: chi of the free gel in equilibrium (zero osmotic pressure) at phi."""
    return 0.5 * n * (1 / phi - 2 * phi**(-5 / 3)) + mixing(phi)


def chi_uniaxial(phi, lambda_par, n):
    """Eq. 4.10: chi of the gel held at the longitudinal stretch lambda_par (from the dry
    state) with zero transverse stress, at phi."""
    return 0.5 * n * (1 / phi - 2 / (phi**2 * lambda_par)) + mixing(phi)


def phi_free_swelling(chi, n):
    """Eq. 4.7 inverted: the free gel's phi at chi."""
    return unique_root(lambda phi: chi_free_swelling(phi, n) - chi, *PHI_RANGE)


def phi_uniaxial(chi, lambda_par, n):
    """Eq. 4.10 inverted: the constrained gel's phi at chi."""
    return unique_root(lambda phi: chi_uniaxial(phi, lambda_par, n) - chi, *PHI_RANGE)


class GelHeating:
    """The fiber_gel scene's gel (section 4.4.2): stress free at phi_i and T_i; chi = chi_A +
    chi_B T is the line through (T_i, chi_i) and (T_f, chi_f), with chi_i and chi_f the free
    gel's chi (Eq. 4.7) at phi_i and at phi_f = phi_i / alpha0^3 (steps (1)-(2))."""

    def __init__(self, n, phi_i, alpha0, T_i, T_f):
        self.n, self.phi_i, self.T_i, self.T_f = n, phi_i, T_i, T_f
        chi_i = chi_free_swelling(phi_i, n)
        chi_f = chi_free_swelling(phi_i / alpha0**3, n)
        self.chi_B = (chi_f - chi_i) / (T_f - T_i)
        self.chi_A = chi_i - self.chi_B * T_i

    @classmethod
    def from_parameters(cls, p):
        """From the parameters of a fiber_gel summary.json (the run's input): chi(T) fitted to
        phi_i and alpha0 (--chi fit), or given (--chi A,B), when phi_i and alpha0 are the free
        gel's states at T_i and T_f (Eq. 4.7 inverted)."""
        if p.get("chi", "fit") == "fit":
            return cls(p["n_nu_vm"], p["phi_i"], p["alpha0"], p["T_i"], p["T_f"])
        chi_A, chi_B = (float(x) for x in p["chi"].split(","))
        phi_i = phi_free_swelling(chi_A + chi_B * p["T_i"], p["n_nu_vm"])
        phi_f = phi_free_swelling(chi_A + chi_B * p["T_f"], p["n_nu_vm"])
        return cls(p["n_nu_vm"], phi_i, (phi_i / phi_f)**(1 / 3), p["T_i"], p["T_f"])

    def chi(self, T):
        return self.chi_A + self.chi_B * T

    def free_contraction(self):
        """Eq. 4.13: alpha0 = (phi_i / phi_f)^(1/3), phi_f solving Eq. 4.7 at chi(T_f)."""
        return (self.phi_i / phi_free_swelling(self.chi(self.T_f), self.n))**(1 / 3)

    def uniaxial_transverse_contraction(self):
        """Eq. 4.14 for the gel held at its initial length (alpha_par = 1) without prestrain:
        lambda_par = phi_i^(-1/3), so that the gel is stress free at T_i (phi'_i = phi_c =
        phi_i). With phi = 1 / (lambda_perp^2 lambda_par) and lambda_par fixed,
        alpha_perp = lambda_perp,f / lambda_perp,i = (phi'_i / phi'_f)^(1/2)."""
        lambda_par = self.phi_i**(-1 / 3)
        phi_i = phi_uniaxial(self.chi(self.T_i), lambda_par, self.n)
        phi_f = phi_uniaxial(self.chi(self.T_f), lambda_par, self.n)
        return math.sqrt(phi_i / phi_f)


# --- Inflated incompressible neo-Hookean thick spherical shell ------------------------------
# Inner radius A, outer B in the reference state; hoop stretches lambda_a = a/A, lambda_b = b/B.
# Incompressibility: b^3 - a^3 = B^3 - A^3, i.e. lambda_b^3 = 1 + (lambda_a^3 - 1)(A/B)^3.
# Radial equilibrium, d sigma_rr/dr = 2 (sigma_tt - sigma_rr)/r with sigma_tt - sigma_rr =
# lambda W'(lambda) / 2, integrated across the wall
# with sigma_rr = -p at r = a and 0 at r = b, and changed to the hoop stretch lambda = r/R
# (dr/r = dlambda / (lambda (1 - lambda^3)) at fixed wall volume), gives
#     p = int_{lambda_b}^{lambda_a} W'(lambda) / (lambda^3 - 1) dlambda,
# W(lambda) = G/2 (2 lambda^2 + lambda^-4 - 3) the neo-Hookean energy in equibiaxial stretch,
# W' = 2G (lambda - lambda^-5) and W' / (lambda^3 - 1) = 2G (lambda^-2 + lambda^-5).


def shell_outer_stretch(lambda_a, A, B):
    return (1 + (lambda_a**3 - 1) * (A / B)**3)**(1 / 3)


def shell_pressure_over_G(lambda_a, A, B):
    """p/G at inner hoop stretch lambda_a: 2 [-1/lambda - lambda^-4/4] from lambda_b to
    lambda_a."""
    lambda_b = shell_outer_stretch(lambda_a, A, B)
    antiderivative = lambda x: -1 / x - x**-4 / 4
    return 2 * (antiderivative(lambda_a) - antiderivative(lambda_b))


def shell_pressure_slope(lambda_a, A, B):
    """d(p/G)/d lambda_a: the integrand at lambda_a minus at lambda_b times d lambda_b/d
    lambda_a = (A/B)^3 lambda_a^2 / lambda_b^2."""
    lambda_b = shell_outer_stretch(lambda_a, A, B)
    integrand = lambda x: 2 * (x**-2 + x**-5)
    return (integrand(lambda_a)
            - integrand(lambda_b) * (A / B)**3 * lambda_a**2 / lambda_b**2)


def shell_pressure_maximum(A, B):
    """(lambda_a, p/G) at the maximum: the slope's root. The slope is 2 (1 - (A/B)^3) > 0 at
    lambda_a = 1 and tends to 2 lambda_a^-2 (1 - B/A) < 0 for large lambda_a; the scan in
    unique_root proves a single sign change on (1, 10)."""
    lambda_a = unique_root(lambda x: shell_pressure_slope(x, A, B), 1.0 + 1e-9, 10.0)
    return lambda_a, shell_pressure_over_G(lambda_a, A, B)


# --- The compressible Mooney-Rivlin shell, spherically symmetric -------------------------------
# The scenes' shells are compressible (U = C10 (I1_bar - 3) + C01 (I2_bar - 3) + K/2 (J - 1)^2,
# forms/materials.py); at K/G = 1000 their walls, stretched to 4-5, change volume by a few per
# cent, enough to move the far branch of the N-shaped law by 10 % in stretch from the
# incompressible closed form. Their spherically symmetric solution r(R) is the radial
# equilibrium d sigma_r/dr = 2 (sigma_t - sigma_r)/r with dr/dR = lambda_r, integrated here
# inward from the free outer surface (sigma_r(B) = 0) by RK4 in R, with the outer radius r(B)
# found by the secant method so that r(A) = lambda_a A; then p = -sigma_r(A). At each point
# lambda_r solves sigma_r(lambda_r, lambda_t) = sigma_r by Newton's method. 200 steps: the
# pressure agrees with 400 steps to 1e-14, and with the incompressible closed form to 1e-8 at
# K/G = 1e8.


def _principal_cauchy(stretches, C10, C01, K):
    """The principal Cauchy stresses of the compressible Mooney-Rivlin solid at principal
    stretches (l1, l2, l3): sigma_i = l_i dU/dl_i / J."""
    l1, l2, l3 = stretches
    J = l1 * l2 * l3
    I1 = l1**2 + l2**2 + l3**2
    I2 = (l1 * l2)**2 + (l2 * l3)**2 + (l3 * l1)**2
    def sigma(l):
        return (C10 * J**(-2 / 3) * (2 * l * l - 2 / 3 * I1)
                + C01 * J**(-4 / 3) * (2 * l * l * (I1 - l * l) - 4 / 3 * I2)
                + K * (J - 1) * J) / J
    return sigma(l1), sigma(l2)


def _radial_stretch(sigma_r, lambda_t, guess, C10, C01, K):
    """lambda_r with sigma_r(lambda_r, lambda_t, lambda_t) = sigma_r (Newton, central
    differences: sigma_r increases monotonically with lambda_r)."""
    lr = guess
    for _ in range(50):
        s = _principal_cauchy((lr, lambda_t, lambda_t), C10, C01, K)[0]
        h = 1e-7 * lr
        slope = (_principal_cauchy((lr + h, lambda_t, lambda_t), C10, C01, K)[0]
                 - _principal_cauchy((lr - h, lambda_t, lambda_t), C10, C01, K)[0]) / (2 * h)
        step = (s - sigma_r) / slope
        lr -= step
        if abs(step) < 1e-14 * lr:
            break
    return lr


def _shoot(r_B, A, B, C10, C01, K, steps=200):
    """(r(A), sigma_r(A)) from r(B) = r_B, sigma_r(B) = 0."""
    def rates(R, r, sigma_r, guess):
        lt = r / R
        lr = _radial_stretch(sigma_r, lt, guess, C10, C01, K)
        sigma_t = _principal_cauchy((lt, lr, lt), C10, C01, K)[0]
        return lr, lr * 2 * (sigma_t - sigma_r) / r, lr
    r, s, R = r_B, 0.0, B
    h = (A - B) / steps
    guess = (B / r_B)**2
    for _ in range(steps):
        k1r, k1s, guess = rates(R, r, s, guess)
        k2r, k2s, _ = rates(R + h / 2, r + h / 2 * k1r, s + h / 2 * k1s, guess)
        k3r, k3s, _ = rates(R + h / 2, r + h / 2 * k2r, s + h / 2 * k2s, guess)
        k4r, k4s, _ = rates(R + h, r + h * k3r, s + h * k3s, guess)
        r += h / 6 * (k1r + 2 * k2r + 2 * k3r + k4r)
        s += h / 6 * (k1s + 2 * k2s + 2 * k3s + k4s)
        R += h
    return r, s


def compressible_shell_pressure(lambda_a, A, B, C10, C01, K):
    """The cavity pressure of the compressible Mooney-Rivlin shell at inner hoop stretch
    lambda_a (> 1), its spherically symmetric solution (see above)."""
    x0 = shell_outer_stretch(lambda_a, A, B) * B  # the incompressible outer radius
    x1 = 1.001 * x0
    f0 = _shoot(x0, A, B, C10, C01, K)[0] - lambda_a * A
    for _ in range(50):
        f1 = _shoot(x1, A, B, C10, C01, K)[0] - lambda_a * A
        if f1 == f0:
            break
        x0, x1, f0 = x1, x1 - f1 * (x1 - x0) / (f1 - f0), f1
        if abs(x1 - x0) < 1e-13 * x1:
            break
    return -_shoot(x1, A, B, C10, C01, K)[1]


def golden_extremum(f, lo, hi, sign, xtol=1e-7):
    """(x, f(x)) at the extremum of f in [lo, hi] (sign +1 a maximum, -1 a minimum), golden
    section: f must be unimodal there."""
    g = (math.sqrt(5) - 1) / 2
    a, b = lo, hi
    while b - a > xtol * b:
        x1, x2 = b - g * (b - a), a + g * (b - a)
        if sign * f(x1) < sign * f(x2):
            a = x1
        else:
            b = x2
    x = 0.5 * (a + b)
    return x, f(x)


# --- Euler column and the elastica -------------------------------------------------------------
EFFECTIVE_LENGTH_FACTOR = {"clamped-free": 2.0, "clamped-clamped": 0.5}


def euler_load(p):
    """pi^2 E I / (K L)^2 for the parameters of a buckling summary.json: E = 2G(1 + nu),
    I = ty tx^3 / 12 about the weak axis (the column buckles across tx), K by the ends."""
    E = 2 * p["G"] * (1 + p["nu"])
    I = p["ty"] * p["tx"]**3 / 12
    return math.pi**2 * E * I / (EFFECTIVE_LENGTH_FACTOR[p["ends"]] * p["L"])**2


def complete_elliptic_k(k):
    """K(k) = pi / (2 AGM(1, sqrt(1 - k^2))) (modulus k, not parameter m = k^2)."""
    # The AGM converges quadratically: 8 iterations reach round-off for k <= 0.99
    a, b = 1.0, math.sqrt(1 - k * k)
    for _ in range(8):
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2 * a)


def cantilever_elastica(k):
    """The inextensible cantilever (length l, tip load P along the undeformed axis) with tip
    rotation alpha, k = sin(alpha / 2): sqrt(P / EI) l = K(k), so P / P_cr = (2 K(k) / pi)^2
    with P_cr = pi^2 EI / (2 l)^2, and tip deflection delta / l = 2 k / K(k).
    Returns (delta / l, P / P_cr)."""
    K = complete_elliptic_k(k)
    return 2 * k / K, (2 * K / math.pi)**2


# 2k / K(k) increases from 0 up to k = 0.84 (delta / l = 0.806, alpha = 114 degrees); below
# k = 0.8 (delta / l = 0.80) the inverse is unique, and the columns here stay well below
ELASTICA_K_MAX = 0.8


def elastica_load_ratio(deflection_over_L, ends):
    """P / P_cr of the elastica at the column's largest lateral deflection over its length L.
    Clamped-free: the cantilever's tip. Clamped-clamped: by symmetry each quarter of the column
    (between an end and the inflection point next to it, and between that point and mid-span)
    is a cantilever of length L/4 whose tip deflection is half the mid-span deflection d, so
    delta / (L/4) = 2 d / L; its P_cr, pi^2 EI / (L/2)^2, is the column's."""
    cantilever_deflection = deflection_over_L * (2 if ends == "clamped-clamped" else 1)
    k = bisect(lambda k: cantilever_elastica(k)[0] - cantilever_deflection, 0.0, ELASTICA_K_MAX)
    return cantilever_elastica(k)[1]
