"""The laws of mixed_hex.py on Q1-P0 hexahedra: trilinear displacement, a constant pressure per
cell (the element of ABAQUS' hybrid bricks C3D8H, which the thesis used). Not inf-sup stable,
the lower order of the pyramid scene's work-precision benchmark."""
import _mixed

_out, forms, expressions = _mixed.build("hexahedron", displacement_degree=1)
# FFCx names the generated forms, expressions, coefficients and constants after module names
globals().update(_out)
