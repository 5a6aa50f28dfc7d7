"""Builder shared by mixed_tet.py, mixed_hex.py and mixed_hex_q1.py: incompressible laws in
mixed displacement-pressure form, on Taylor-Hood pairs (P2-P1 tetrahedra, Q2-Q1 hexahedra) or,
for displacement degree 1, on Q1-P0 hexahedra (a constant pressure per cell: the element of
ABAQUS' hybrid bricks C3D8H that the thesis used).

FFCx names coefficients and constants after the module-level variables that hold them, so each
form file puts what build() returns into its module namespace.
"""
import ufl
import materials


def build(cell, displacement_degree=2):
    mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
    pressure = (ufl.FiniteElement("Lagrange", cell, 1) if displacement_degree == 2
                else ufl.FiniteElement("DG", cell, 0))
    element = ufl.MixedElement([ufl.VectorElement("Lagrange", cell, displacement_degree),
                                pressure])
    W = ufl.FunctionSpace(mesh, element)
    w = ufl.Coefficient(W)  # (u, p): displacement and pressure (mean Cauchy stress)
    u, p = ufl.split(w)
    F = materials.deformation_gradient(u)
    c = {name: ufl.Constant(mesh) for name in ("G", "C10", "C01", "bulk_compliance")}
    degree = materials.quadrature_degree(displacement_degree)
    dx = ufl.dx(metadata={"quadrature_degree": degree})
    J = ufl.det(F)
    # law: (Lagrangian, its volume change, its Cauchy stress)
    small_strain = materials.linear_elastic_incompressible(F, p, c["G"], c["bulk_compliance"])
    laws = {"nh": materials.neo_hookean_incompressible(F, p, c["G"], c["bulk_compliance"]),
            "mr": materials.mooney_rivlin_incompressible(F, p, c["C10"], c["C01"],
                                                         c["bulk_compliance"]),
            "le": small_strain}
    volume_change = {"nh": J - 1, "mr": J - 1, "le": ufl.tr(materials.small_strain(F))}
    stress = {"nh": materials.cauchy_stress(laws["nh"], F),
              "mr": materials.cauchy_stress(laws["mr"], F),
              "le": materials.linear_elastic_stress(small_strain, F)}
    out = {"w": w, **c}
    forms, expressions = [], []
    centroid = materials.centroid(cell)
    for name, lagrangian in laws.items():
        energy = materials.mixed_stored_energy(lagrangian, volume_change[name], p,
                                               c["bulk_compliance"])
        residual = ufl.derivative(lagrangian * dx, w, ufl.TestFunction(W))
        tangent = ufl.derivative(residual, w, ufl.TrialFunction(W))
        # The total energy: the functional the residual is the derivative of, with its
        # quadrature, so that d(energy)/d(load) is the reaction exactly for the discrete
        # problem; at a solution it equals int psi dX (the pressure equation makes
        # int p (c - bulk_compliance p) dX vanish)
        total = lagrangian * dx
        out.update({f"residual_{name}": residual, f"tangent_{name}": tangent,
                    f"stress_{name}": stress[name], f"psi_{name}": energy,
                    f"energy_{name}": total})
        forms += [residual, tangent, total]
        expressions += [(stress[name], centroid), (energy, centroid)]
    out["det_F"] = J
    expressions.append((J, materials.quadrature_points(cell, degree)))
    # The current volume (int J dX): the incompressibility that the pressure enforces weakly
    out["volume"] = J * dx
    forms.append(out["volume"])
    # -1/G int p q dX, zero in the displacement rows: its pressure block preconditions the Schur
    # complement -B A^-1 B^T of the fieldsplit linear solver, to which it is spectrally
    # equivalent for an incompressible solid of shear modulus G (the Stokes analogy); the sign
    # is the Schur complement's (A is positive definite)
    _, q = ufl.split(ufl.TestFunction(W))
    _, r = ufl.split(ufl.TrialFunction(W))
    out["pressure_mass"] = -r * q / c["G"] * dx
    forms.append(out["pressure_mass"])
    return out, forms, expressions
