"""Contact-patch area on Q1 hexahedra (see _contact.py): coefficients u (displacement) and
level_set (RigidPlaneContact::contact_level_set), constant normal; facets tagged 1."""
import _contact

u, level_set, normal, contact_area = _contact.build("hexahedron", displacement_degree=1)
forms = [contact_area]
