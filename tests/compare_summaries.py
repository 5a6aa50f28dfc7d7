"""Compare the quantities of interest of two runs' summary.json (e.g. 2 ranks against 1, or a
symmetry-reduced domain against a larger one).

usage: compare_summaries.py A/summary.json B/summary.json RTOL KEY [KEY ...]
"""
import json
import sys

from checks import Checks

a, b = (json.load(open(p)) for p in sys.argv[1:3])
rtol = float(sys.argv[3])
checks = Checks()
checks.require(f"both runs completed ({a.get('status')}, {b.get('status')}) with "
               f"{a['mpi_ranks']} and {b['mpi_ranks']} ranks",
               a.get("status") == b.get("status") == "completed")
for key in sys.argv[4:]:
    checks.relative(f"{key}, {sys.argv[2]} against {sys.argv[1]}", b[key], a[key], rtol)
checks.finish()
