"""A gel that swells in time (forms/_swelling.py: the coupled solvent diffusion and large
deformation of Hong, Zhao, Zhou & Suo) on hexahedra: Q2-Q1 Taylor-Hood (suffix q2q1) and
equal-order Q1-Q1 (q1q1, not inf-sup stable: to show what that does), for the swelling and
crease scenes."""
import _swelling

_out, forms, expressions = _swelling.build("hexahedron", {"q2q1": 2, "q1q1": 1})
# FFCx names the generated forms, expressions, coefficients and constants after module names
globals().update(_out)
