"""Builder shared by contact.py (P2 tetrahedra), contact_hex.py (Q2 hexahedra) and
contact_hex_q1.py (Q1 hexahedra): the contact-patch functional of gelx::RigidPlaneContact.

contact_area = int_{ds(1)} H(phi) |n_plane . cof(F) N| dA: the current area of the contact
patch (cof F N dA = n da, Nanson's formula), where phi is the contact level set
(RigidPlaneContact::contact_level_set; all its components are equal), positive in contact, and
`normal` the plane's normal. The Heaviside step is integrated with a degree-8 rule so that a
facet the patch edge crosses counts with the part of it where the interpolated phi > 0.
"""
import ufl
import materials


def build(cell, displacement_degree=2):
    mesh = ufl.Mesh(ufl.VectorElement("Lagrange", cell, 1))
    V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", cell, displacement_degree))
    u = ufl.Coefficient(V)  # displacement
    level_set = ufl.Coefficient(V)  # contact level set
    normal = ufl.Constant(mesh, shape=(3,))
    F = materials.deformation_gradient(u)
    N = ufl.FacetNormal(mesh)
    ds = ufl.ds(metadata={"quadrature_degree": 8})
    in_contact = ufl.conditional(ufl.gt(level_set[0], 0), 1, 0)
    area = in_contact * abs(ufl.dot(normal, ufl.cofac(F) * N)) * ds(1)
    return u, level_set, normal, area
