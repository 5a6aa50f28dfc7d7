"""Incompressible neo-Hookean (Eq. 1.10) and Mooney-Rivlin solids in mixed u-p form on P2-P1
Taylor-Hood tetrahedra. Coefficient w = (u, p); constants G (neo-Hookean), C10, C01
(Mooney-Rivlin), bulk_compliance = 1/K (0: exactly incompressible). See forms/README.md."""
import _mixed

_out, forms, expressions = _mixed.build("tetrahedron")
w, G, C10, C01, bulk_compliance = (_out[k] for k in ("w", "G", "C10", "C01", "bulk_compliance"))
residual_nh, tangent_nh, stress_nh, psi_nh = (_out[k] for k in
                                              ("residual_nh", "tangent_nh", "stress_nh", "psi_nh"))
residual_mr, tangent_mr, stress_mr, psi_mr = (_out[k] for k in
                                              ("residual_mr", "tangent_mr", "stress_mr", "psi_mr"))
det_F = _out["det_F"]
