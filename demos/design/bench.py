"""The cost of inverse design against the number of design parameters: the design scene's
default helix (R = 3, P = 6, the 20 x 1 x 1 strip on 40 x 2 x 2 Q2 cells) designed with 5, 10
and 20 slabs per layer (20, 40 and 80 parameters: stretch and angle of both layers), 1 rank.
Per run: BLMVM's iterations, the forward and adjoint solves and their times, the wall time per
iteration, and the helix reached. The adjoint's point: one adjoint solve per evaluation whatever
the number of parameters, so the cost per iteration does not grow with them; the iterations
may.

usage: bench.py BUILD_DIR OUTPUT_DIR
Results: OUTPUT_DIR/bench.csv and bench.md (the README table).
"""
import csv
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from studies import run_scene  # noqa: E402  (demos/studies.py)

build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
out.mkdir(parents=True, exist_ok=True)
rows = []
for slabs in (5, 10, 20):
    s = run_scene(build, "design", out / f"slabs{slabs}", 1, ["--slabs", str(slabs)])
    it = max(s["iterations"], 1)
    rows.append({"slabs": slabs, "parameters": s["num_parameters"], "num_dofs": s["num_dofs"],
                 "iterations": s["iterations"], "forward_solves": s["forward_solves"],
                 "adjoint_solves": s["adjoint_solves"],
                 "newton_iterations": s["newton_iterations"],
                 "forward_time": s["forward_time"], "adjoint_time": s["adjoint_time"],
                 "time_per_iteration": s["wall_time"] / it,
                 "adjoint_time_per_solve": s["adjoint_time"] / s["adjoint_solves"],
                 "wall_time": s["wall_time"], "radius_error": s["radius_error"],
                 "pitch_error": s["pitch_error"], "rms_distance": s["rms_distance"]})
with open(out / "bench.csv", "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
lines = ["| slabs | parameters | iterations | forward solves | adjoint solves | Newton "
         "| forward [s] | adjoint [s] | per iteration [s] | per adjoint [s] | R error | P error |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    lines.append(f"| {r['slabs']} | {r['parameters']} | {r['iterations']} | "
                 f"{r['forward_solves']} | {r['adjoint_solves']} | {r['newton_iterations']} | "
                 f"{r['forward_time']:.1f} | {r['adjoint_time']:.1f} | "
                 f"{r['time_per_iteration']:.2f} | {r['adjoint_time_per_solve']:.3f} | "
                 f"{r['radius_error']:.2%} | {r['pitch_error']:.2%} |")
(out / "bench.md").write_text("\n".join(lines) + "\n")
print("\n".join(lines))
