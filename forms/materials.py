"""Material laws of gelx: strain-energy densities as UFL expressions of the deformation gradient.

Every scene's form file builds its residual and tangent from one of these energies with
`ufl.derivative`, and exports the Cauchy stress and the energy density for output, so a law is
written once, here, and nowhere else. Equation numbers refer to the thesis in shared/seed/.
"""
import basix
import ufl


def deformation_gradient(u):
    """F = I + Grad u, marked as a UFL variable so that stresses are ufl.diff(psi, F)."""
    d = len(u)
    return ufl.variable(ufl.Identity(d) + ufl.grad(u))


def neo_hookean_compressible(F, G, K):
    """Compressible neo-Hookean solid, thesis Eq. 3.1.

    U = G/2 (I1_bar - 3) + K/2 (J - 1)^2 with I1_bar = J^(-2/3) tr(F^T F):
    G is the initial shear modulus, K the bulk modulus.
    """
    J = ufl.det(F)
    I1_bar = J**(-2.0 / 3.0) * ufl.tr(F.T * F)
    return G / 2 * (I1_bar - 3) + K / 2 * (J - 1)**2


def first_piola(psi, F):
    """P = dpsi/dF."""
    return ufl.diff(psi, F)


def cauchy_stress(psi, F):
    """sigma = J^-1 P F^T."""
    return first_piola(psi, F) * F.T / ufl.det(F)


def quadrature_degree(displacement_degree):
    """Quadrature degree for hyperelastic residuals and tangents.

    The integrands are rational in Grad u, so no degree is exact; 2p (4 for P2) keeps the
    quadrature error below the discretisation error (the manufactured-solution test checks
    that the optimal rates survive it) at a fraction of FFCx's estimated degree.
    """
    return 2 * displacement_degree


def quadrature_points(cell, degree):
    """Points of the default Basix scheme of the given degree: the points FFCx integrates on,
    where the solver checks det F > 0 to reject inverted iterates."""
    points, _ = basix.make_quadrature(basix.cell.string_to_type(cell), degree)
    return points


def centroid(cell):
    """Reference-cell midpoint: the interpolation point of a DG0 field (cell-wise output)."""
    return {"tetrahedron": [[0.25, 0.25, 0.25]], "hexahedron": [[0.5, 0.5, 0.5]]}[cell]
