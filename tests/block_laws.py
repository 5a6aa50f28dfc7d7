"""The block scene's laws (--law) and structured mesh (--mesh box) against dolfinx's own solver.

The block, W x W x H = 1 x 1 x 2 mm on create_box's P2 tetrahedra (4 x 4 x 8 boxes of six),
clamped at the bottom, its top face lifted to the stretch 1.3 and turned by 30 degrees, is
solved here a second time with dolfinx's Python interface: each law's energy written anew in
this file (not taken from forms/materials.py), the same mesh, dolfinx's NewtonSolver (PETSc
LU, |R| <= 1e-12) over 8 equal load steps. A hyperelastic block under this load has one
equilibrium, so both reach the same state whatever their load steps: the stored energy and
the top face's axial force (the residual's action on a unit lift of the top face, the
reactions at its dofs) agree to round-off times the conditioning. Tolerance 1e-8 relative:
gelx stops at |R| <= 1e-10 |R0|, whose error in the energy is second order in the residual and
in the force ~1e-10 of the force; measured <= 7.2e-13.

- nh_log (dolfinx's hyperelasticity demo's law): G/2 (tr C - 3) - G ln J + lambda/2 (ln J)^2
- mr (mooney_share 0.3): C10 (I1_bar - 3) + C01 (I2_bar - 3) + K/2 (J - 1)^2
- le: G dev(eps):dev(eps) + K/2 tr(eps)^2

Controls that must differ by more than 100 times that tolerance: the default law (nh) on the
same box (its energy 1.7e-2 from nh_log's: the laws differ at the finite volume changes of
K/G = 10), and the default mesh (block.geo) with nh_log (3.4e-4 from the box's). An option
parsed but not applied fails one of these.

usage: block_laws.py GELX_BLOCK WORK_DIR MPIEXEC
"""
import json
import math
import pathlib
import shutil
import subprocess
import sys

import numpy as np

from checks import Checks

binary, work, mpiexec = sys.argv[1], pathlib.Path(sys.argv[2]), sys.argv[3]
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
checks = Checks()
W, H, h, G, K, SHARE, STRETCH, TWIST = 1.0, 2.0, 0.25, 1.0, 10.0, 0.3, 1.3, 30.0


def gelx(name, *options):
    """The block scene at 1 rank; its summary"""
    out = work / name
    p = subprocess.run([mpiexec, "-np", "1", binary, "--output", str(out), "--stretch",
                        str(STRETCH), "--twist", str(TWIST), "--h", str(h), "--G", str(G), "--K",
                        str(K), "--mooney_share", str(SHARE), *options],
                       capture_output=True, text=True)
    checks.require(f"{name}: exit code {p.returncode}", p.returncode == 0)
    if p.returncode != 0:
        print(p.stderr[-2000:])
        checks.finish()
    return json.loads((out / "summary.json").read_text())


def energy_density(law, F):
    import ufl
    d = 3
    I = ufl.Identity(d)
    J = ufl.det(F)
    C = F.T * F
    if law == "nh_log":
        lame = K - 2 * G / 3
        return G / 2 * (ufl.tr(C) - 3) - G * ufl.ln(J) + lame / 2 * ufl.ln(J)**2
    if law == "mr":
        C01, C10 = SHARE * G / 2, (1 - SHARE) * G / 2
        I1_bar = J**(-2 / 3) * ufl.tr(C)
        I2_bar = J**(-4 / 3) * (ufl.tr(C)**2 - ufl.tr(C * C)) / 2
        return C10 * (I1_bar - 3) + C01 * (I2_bar - 3) + K / 2 * (J - 1)**2
    if law == "le":
        eps = ufl.sym(F) - I
        return G * ufl.inner(ufl.dev(eps), ufl.dev(eps)) + K / 2 * ufl.tr(eps)**2
    raise ValueError(law)


def dolfinx_block(law):
    """Energy and axial force at the end of the path, by dolfinx's Python interface (imported
    here, after the gelx runs: mpi4py starts MPI, and an mpiexec started from a process that
    runs MPI fails without a word)"""
    import dolfinx.fem.petsc
    import dolfinx.nls.petsc
    import ufl
    from dolfinx import fem, mesh
    from mpi4py import MPI
    n = [math.ceil(W / h), math.ceil(W / h), math.ceil(H / h)]
    domain = mesh.create_box(MPI.COMM_SELF, [[-W / 2, -W / 2, 0], [W / 2, W / 2, H]], n,
                             mesh.CellType.tetrahedron)
    V = fem.VectorFunctionSpace(domain, ("Lagrange", 2))
    u, v = fem.Function(V), ufl.TestFunction(V)
    F = ufl.Identity(3) + ufl.grad(u)
    psi = energy_density(law, F)
    dx = ufl.dx(metadata={"quadrature_degree": 4})  # gelx's: 2p for P2
    residual = ufl.derivative(psi * dx, u, v)
    tangent = ufl.derivative(residual, u, ufl.TrialFunction(V))
    fdim = 2
    bottom = mesh.locate_entities_boundary(domain, fdim, lambda x: np.isclose(x[2], 0))
    top = mesh.locate_entities_boundary(domain, fdim, lambda x: np.isclose(x[2], H))
    bottom_dofs = fem.locate_dofs_topological(V, fdim, bottom)
    top_dofs = fem.locate_dofs_topological(V, fdim, top)
    clamp, lift = fem.Function(V), fem.Function(V)
    bcs = [fem.dirichletbc(clamp, bottom_dofs), fem.dirichletbc(lift, top_dofs)]
    problem = dolfinx.fem.petsc.NonlinearProblem(residual, u, bcs, tangent)
    solver = dolfinx.nls.petsc.NewtonSolver(MPI.COMM_SELF, problem)
    solver.rtol, solver.atol, solver.convergence_criterion = 1e-14, 1e-12, "residual"
    solver.max_it = 30
    ksp = solver.krylov_solver
    ksp.setType("preonly")
    ksp.getPC().setType("lu")
    steps = 8
    for k in range(1, steps + 1):
        t = k / steps
        angle = math.radians(TWIST) * t

        def top_motion(x):
            return np.vstack([math.cos(angle) * x[0] - math.sin(angle) * x[1] - x[0],
                              math.sin(angle) * x[0] + math.cos(angle) * x[1] - x[1],
                              np.full(x.shape[1], (STRETCH - 1) * H * t)])
        lift.interpolate(top_motion)
        iterations, converged = solver.solve(u)
        assert converged, f"dolfinx's Newton did not converge at t = {t}"
    energy = fem.assemble_scalar(fem.form(psi * dx))
    # The axial force: the residual's action on a unit lift of the top face (its reactions)
    unit_lift = fem.Function(V)
    unit_lift.interpolate(lambda x: np.vstack([0 * x[0], 0 * x[0], np.isclose(x[2], H) * 1.0]))
    force = fem.assemble_scalar(fem.form(ufl.replace(residual, {v: unit_lift})))
    return energy, force


LAWS = ("nh_log", "mr", "le")
runs = {law: gelx(f"box_{law}", "--law", law, "--mesh", "box") for law in LAWS}
# Controls: the law and the mesh change the answer by far more than the tolerance
nh, geo = gelx("box_nh", "--mesh", "box"), gelx("geo_nh_log", "--law", "nh_log")
for law in LAWS:
    energy, force = dolfinx_block(law)
    checks.relative(f"{law}: gelx's energy [mJ] against dolfinx's", runs[law]["strain_energy"], energy,
                    1e-8)
    checks.relative(f"{law}: gelx's axial force [N] against dolfinx's",
                    runs[law]["axial_force"], force, 1e-8)
reference = runs["nh_log"]["strain_energy"]
change = abs(nh["strain_energy"] - reference) / reference
checks.require(f"control: nh's energy on the same box is {change:.3g} from nh_log's (> 1e-6)",
               change > 1e-6)
change = abs(geo["strain_energy"] - reference) / reference
checks.require(f"control: nh_log on block.geo is {change:.3g} from the box's (> 1e-6)",
               change > 1e-6)
checks.finish()
