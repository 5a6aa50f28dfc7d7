"""The Flory-Rehner gel of forms/gel.py (thesis Eq. 4.28; P1 and P2 tetrahedra), compiled under
its own name for the fiber_gel scene (demos/fiber_gel), so the scene owns its kernels and the
physics stays in one file: the same residual, tangent, stress, energy density, J and
admissibility margin J - phi0, generated as form_fiber_gel_* and expression_fiber_gel_*."""
from gel import *  # noqa: F401,F403 -- FFCx exports the module-level forms and expressions
