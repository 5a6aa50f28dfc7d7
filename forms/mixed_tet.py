"""Incompressible neo-Hookean (Eq. 1.10), Mooney-Rivlin and small-strain linear solids in mixed
u-p form on P2-P1 Taylor-Hood tetrahedra. Coefficient w = (u, p); constants G (neo-Hookean,
linear), C10, C01 (Mooney-Rivlin), bulk_compliance = 1/K (0: exactly incompressible). See
forms/README.md."""
import _mixed

_out, forms, expressions = _mixed.build("tetrahedron")
# FFCx names the generated forms, expressions, coefficients and constants after module names
globals().update(_out)
