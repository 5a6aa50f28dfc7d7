"""A gel that swells in time (forms/_swelling.py: the coupled solvent diffusion and large
deformation of Hong, Zhao, Zhou & Suo) on P2-P1 Taylor-Hood tetrahedra (suffix p2p1), for the
fiber-reinforced gel film of demos/fiber_film."""
import _swelling

_out, forms, expressions = _swelling.build("tetrahedron", {"p2p1": 2})
# FFCx names the generated forms, expressions, coefficients and constants after module names
globals().update(_out)
