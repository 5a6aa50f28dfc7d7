"""Objectivity (frame indifference) of every law in forms/materials.py.

A rigid rotation Q superposed on the deformation, F -> Q F, must leave the strain-energy density
unchanged and rotate the Cauchy stress, sigma(Q F) = Q sigma(F) Q^T. The laws are evaluated
exactly as the form files use them: the UFL of materials.py, with F a ufl.variable so that the
stress is ufl.diff, compiled by FFCx and evaluated by dolfinx.fem.Expression on one cell. F, Q,
F0 and the pressure are dolfinx Constants whose values change between samples, so each law is
compiled once. The small-strain laws are not objective (their docstrings say so): their energy
must change under the same rotations, which shows that the check can see a non-objective law.

usage: objectivity.py
"""
import pathlib
import sys

import numpy as np
from mpi4py import MPI

import dolfinx.fem
import dolfinx.mesh
import ufl

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "forms"))
import materials  # noqa: E402  (forms/materials.py)

# 1e-12 relative: psi and sigma are some hundred floating-point operations on the entries of F
# and of Q F (|F| < 2, det F > 0.5: no strong cancellation), so they carry a round-off of
# ~100 eps = 2e-14 (measured: <= 2.3e-14 for sigma, whose entries are compared with its largest);
# a non-objective term a millionth the size of a finite rotation's effect would still show.
TOLERANCE = 1e-12
# The smallest relative energy change that the small-strain laws must show under the rotations
# below (angles >= pi/8): sym(Q) - I alone is a strain of 1 - cos(pi/8) = 0.076.
NON_OBJECTIVE_CHANGE = 1e-2

rng = np.random.default_rng(20240611)


def random_deformation_gradients(count):
    """F = I + A with entries of A uniform in [-0.3, 0.3] (|F - I| ~ 0.5), kept if det F > 0.5:
    well inside the admissible set of every law (the gel needs det F > phi0)."""
    gradients = []
    while len(gradients) < count:
        F = np.eye(3) + rng.uniform(-0.3, 0.3, (3, 3))
        if np.linalg.det(F) > 0.5:
            gradients.append(F)
    return gradients


def random_rotations(count):
    """Rodrigues rotations about uniformly distributed axes by angles in [pi/8, pi]."""
    rotations = []
    for _ in range(count):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        angle = rng.uniform(np.pi / 8, np.pi)
        K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
        rotations.append(np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K)
    return rotations


mesh = dolfinx.mesh.create_unit_cube(MPI.COMM_SELF, 1, 1, 1)
F_constant = dolfinx.fem.Constant(mesh, np.eye(3))
Q_constant = dolfinx.fem.Constant(mesh, np.eye(3))
# The prestretch: non-symmetric, det F0 = 1.23, so det(F F0^-1) > 0.4 for the samples below
F0_constant = dolfinx.fem.Constant(mesh, np.array([[1.1, 0.3, -0.1],
                                                   [-0.2, 0.95, 0.25],
                                                   [0.15, -0.1, 1.05]]))
p_constant = dolfinx.fem.Constant(mesh, 0.7)  # a fixed pressure of the mixed laws

G, K, C10, C01, bulk_compliance = 1.0, 10.0, 0.3, 0.2, 0.05
n, phi0, chi, kT_nu = 0.02, 0.3, 0.5, 1.0
nh = materials.neo_hookean_compressible
objective_laws = {
    "neo_hookean_compressible": lambda F: nh(F, G, K),
    "neo_hookean_log": lambda F: materials.neo_hookean_log(F, G, K),
    "mooney_rivlin_compressible": lambda F: materials.mooney_rivlin_compressible(F, C10, C01, K),
    "neo_hookean_incompressible (fixed p)":
        lambda F: materials.neo_hookean_incompressible(F, p_constant, G, bulk_compliance),
    "mooney_rivlin_incompressible (fixed p)":
        lambda F: materials.mooney_rivlin_incompressible(F, p_constant, C10, C01,
                                                         bulk_compliance),
    "flory_rehner_gel": lambda F: materials.flory_rehner_gel(F, n, phi0, chi, kT_nu),
    "prestretched(neo_hookean_compressible, F0)":
        lambda F: materials.prestretched(nh, F, F0_constant, G, K),
}
small_strain_laws = {
    "linear_elastic": lambda F: materials.linear_elastic(F, G, K),
    "linear_elastic_incompressible (fixed p)":
        lambda F: materials.linear_elastic_incompressible(F, p_constant, G, bulk_compliance),
}


def compile_law(law):
    """One expression holding psi(F), psi(Q F), sigma(F) and sigma(Q F) (9 entries each)."""
    values = []
    for gradient in (F_constant, Q_constant * F_constant):
        F = ufl.variable(gradient)
        psi = law(F)
        sigma = materials.cauchy_stress(psi, F)
        values.append([psi] + [sigma[i, j] for i in range(3) for j in range(3)])
    psi_F, *sigma_F = values[0]
    psi_QF, *sigma_QF = values[1]
    return dolfinx.fem.Expression(ufl.as_vector([psi_F, psi_QF] + sigma_F + sigma_QF),
                                  np.array([[0.25, 0.25, 0.25]]))


def rotation_errors(law, gradients, rotations):
    """Relative changes |psi(Q F) - psi(F)| / |psi(F)| and max|sigma(Q F) - Q sigma(F) Q^T| /
    max|sigma(F)| over all pairs (F, Q)."""
    expression = compile_law(law)
    energy_changes, stress_errors = [], []
    for F in gradients:
        for Q in rotations:
            F_constant.value[:] = F
            Q_constant.value[:] = Q
            values = expression.eval(np.array([0], dtype=np.int32))[0]
            psi_F, psi_QF = values[:2]
            sigma_F, sigma_QF = values[2:11].reshape(3, 3), values[11:].reshape(3, 3)
            energy_changes.append(abs(psi_QF - psi_F) / abs(psi_F))
            stress_errors.append(np.abs(sigma_QF - Q @ sigma_F @ Q.T).max()
                                 / np.abs(sigma_F).max())
    return np.array(energy_changes), np.array(stress_errors)


def main():
    # 1. Samples: deformation gradients and finite rotations
    gradients, rotations = random_deformation_gradients(6), random_rotations(6)
    pairs = len(gradients) * len(rotations)
    checks = Checks()
    checks.require(f"{pairs} pairs (F, Q): det F in [{min(map(np.linalg.det, gradients)):.3f}, "
                   f"{max(map(np.linalg.det, gradients)):.3f}], |F - I| up to "
                   f"{max(np.linalg.norm(F - np.eye(3)) for F in gradients):.3f}, "
                   f"max |Q^T Q - I| = "
                   f"{max(np.abs(Q.T @ Q - np.eye(3)).max() for Q in rotations):.1e}, "
                   f"det Q = 1", all(abs(np.linalg.det(Q) - 1) < 1e-14 for Q in rotations))

    # 2. The hyperelastic laws: energy invariant, stress rotated
    for name, law in objective_laws.items():
        energy_changes, stress_errors = rotation_errors(law, gradients, rotations)
        checks.absolute(f"{name}: max |psi(QF) - psi(F)| / |psi(F)|", energy_changes.max(), 0.0,
                        TOLERANCE)
        checks.absolute(f"{name}: max |sigma(QF) - Q sigma(F) Q^T| / max|sigma(F)|",
                        stress_errors.max(), 0.0, TOLERANCE)

    # 3. Negative control: the small-strain laws' energy changes under the same rotations
    for name, law in small_strain_laws.items():
        energy_changes, _ = rotation_errors(law, gradients, rotations)
        checks.require(f"{name} is not objective: |psi(QF) - psi(F)| / |psi(F)| in "
                       f"[{energy_changes.min():.3g}, {energy_changes.max():.3g}], every pair "
                       f"above {NON_OBJECTIVE_CHANGE:g} (and so above the tolerance "
                       f"{TOLERANCE:g} of step 2)", energy_changes.min() > NON_OBJECTIVE_CHANGE)
    checks.finish()


main()
