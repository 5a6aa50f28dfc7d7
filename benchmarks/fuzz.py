"""The input parsers' fuzzers run long (issue #32): each libFuzzer target of tests/fuzz for a
time (default 10 minutes each; --seconds S), from the corpus ctest uses, with the same
properties checked (tests/fuzz/fuzz.py). Prints per fuzzer the runs, the edges covered and the
new inputs found; an input that fails is left in OUT as NAME-crash-* and printed: fix the bug,
then copy the input into tests/fuzz/corpus/NAME so that ctest fuzz_parsers keeps it fixed.

usage: fuzz.py BUILD OUT [--seconds S]     (./gelx bench fuzz)
"""
import pathlib
import subprocess
import sys

build, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
seconds = sys.argv[sys.argv.index("--seconds") + 1] if "--seconds" in sys.argv else "600"
source = pathlib.Path(__file__).resolve().parents[1] / "tests" / "fuzz"
fuzzers = sorted(str(f) for f in (build / "tests" / "fuzz" / "bin").iterdir())
out.mkdir(parents=True, exist_ok=True)
sys.exit(subprocess.run([sys.executable, str(source / "fuzz.py"), str(source / "corpus"),
                         str(out), *fuzzers, "--seconds", seconds]).returncode)
