"""Number checks shared by the Python tests: print each measured value beside its reference and
close with the line 'N passed, M failed'."""
import sys


class Checks:
    def __init__(self):
        self.passed = 0
        self.failed = 0

    def require(self, what, ok):
        self.passed += bool(ok)
        self.failed += not ok
        print(("PASS  " if ok else "FAIL  ") + what)

    def absolute(self, what, value, reference, tol):
        err = abs(value - reference)
        self.require(f"{what}: {value:.12g} (reference {reference:.12g}, error {err:.2e}, "
                     f"tol {tol:.1e})", err <= tol)

    def relative(self, what, value, reference, tol):
        err = abs(value - reference) / abs(reference)
        self.require(f"{what}: {value:.15g} (reference {reference:.15g}, relative error "
                     f"{err:.2e}, tol {tol:.1e})", err <= tol)

    def newton_tolerance(self, rows, what="every step"):
        """What tolerances resting on "Newton converges to |R| <= 1e-10 |R0|" rely on: every
        row of steps.csv (its newton_residual, newton_residual0) met max(1e-12, 1e-10 |R0|)."""
        worst = max(float(r["newton_residual"]) / max(1e-12, 1e-10 * float(r["newton_residual0"]))
                    for r in rows) if rows else float("inf")
        self.require(f"{what}: Newton met |R| <= max(1e-12, 1e-10 |R0|) ({len(rows)} steps, "
                     f"worst {worst:.3g} of it)", worst <= 1)

    def time_split(self, summary):
        """summary.json's split of the wall time: every part measured (not negative), the
        solvers' parts non-zero in a run that solves, and the parts adding up to no more than
        the wall time (other >= 0): a PETSc event counted twice (one nested in another)
        would make 'other' negative."""
        split = summary["time_split"]
        self.require("time split: " + ", ".join(f"{k} {v:.3g} s" for k, v in split.items())
                     + f" of {summary['wall_time']:.3g} s; assembly and solve > 0, none < 0",
                     split["assembly"] > 0 and split["solve"] > 0
                     and min(split.values()) >= 0)

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        sys.exit(1 if self.failed else 0)
