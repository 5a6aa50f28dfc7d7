"""Compare the quantities of interest of two runs' summary.json (e.g. 2 ranks against 1, or a
symmetry-reduced domain against a larger one), and check what must differ between them.

Two runs that agree are only evidence when they are two different runs: if the option under
test were parsed but not applied, B would be A again and every quantity would agree. So each
comparison of a different method also names what that method must change (issue #30):
  --ratio KEY R           B's KEY is R times A's (exactly: counts of cells of a reduction)
  --fewer KEY             B's KEY is smaller than A's (unknowns of a constrained space)
  --values KEY VA VB      A's KEY is VA and B's is VB (e.g. the SNES type that solved)
  --krylov                A solved directly, B iteratively: over the steps.csv beside each
                          summary, A's linear iterations are at most its Newton iterations
                          (one application of LU per solve; the count leaves out each step's
                          predictor solve: measured 17 for 22 on the block, 5 steps) and B's
                          at least twice its Newton iterations (Krylov to 1e-10 takes many)

Both runs must have completed; a run stopped on purpose once it holds what is compared
(--stop_after_steps: status "completed: stopped after N steps") counts.

usage: compare_summaries.py A/summary.json B/summary.json RTOL KEY [KEY ...] [checks above]
"""
import argparse
import json
import pathlib
import sys

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import read_table  # noqa: E402  (demos/fields.py)

parser = argparse.ArgumentParser()
parser.add_argument("a", type=pathlib.Path)
parser.add_argument("b", type=pathlib.Path)
parser.add_argument("rtol", type=float)
parser.add_argument("keys", nargs="+")
parser.add_argument("--ratio", nargs=2, action="append", default=[], metavar=("KEY", "R"))
parser.add_argument("--fewer", action="append", default=[], metavar="KEY")
parser.add_argument("--values", nargs=3, action="append", default=[],
                    metavar=("KEY", "VA", "VB"))
parser.add_argument("--krylov", action="store_true")
args = parser.parse_args()

a, b = (json.load(open(p)) for p in (args.a, args.b))
checks = Checks()
# A key one run lacks (a run stopped before it, or a misspelt name) is a failed check with its
# name, not a traceback
named = set(args.keys) | {key for key, _ in args.ratio} | set(args.fewer)
missing = [f"{key} (not in {path})" for key in sorted(named)
           for run, path in ((a, args.a), (b, args.b)) if key not in run]
if missing:
    checks.require("keys in both summaries: " + ", ".join(missing), False)
    checks.finish()
checks.require(f"both runs completed ({a.get('status')}, {b.get('status')}) with "
               f"{a.get('mpi_ranks')} and {b.get('mpi_ranks')} ranks",
               all(str(run.get("status")).startswith("completed") for run in (a, b)))
for key in args.keys:
    checks.relative(f"{key}, {args.b} against {args.a}", b[key], a[key], args.rtol)

# What must differ
for key, ratio in args.ratio:
    checks.require(f"{key}: B/A = {b[key]}/{a[key]} is {ratio}",
                   b[key] * 1.0 == float(ratio) * a[key])
for key in args.fewer:
    checks.require(f"{key}: B's {b[key]} fewer than A's {a[key]}", b[key] < a[key])
for key, value_a, value_b in args.values:
    checks.require(f"{key}: A's '{a.get(key)}' is '{value_a}', B's '{b.get(key)}' is '{value_b}'",
                   a.get(key) == value_a and b.get(key) == value_b)
if args.krylov:
    def totals(summary_path):
        rows = read_table(summary_path.parent / "steps.csv")
        return (sum(int(r["newton_iterations"]) for r in rows),
                sum(int(r["linear_iterations"]) for r in rows))
    newton_a, linear_a = totals(args.a)
    newton_b, linear_b = totals(args.b)
    checks.require(f"A solved directly: {linear_a} linear iterations for {newton_a} Newton "
                   "iterations (at most one each)", newton_a > 0 and 0 < linear_a <= newton_a)
    checks.require(f"B solved iteratively: {linear_b} linear iterations for {newton_b} Newton "
                   "iterations (at least twice)", newton_b > 0 and linear_b >= 2 * newton_b)
checks.finish()
