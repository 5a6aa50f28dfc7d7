"""Run each parser fuzzer (libFuzzer) over its corpus, then fuzz from it for a fixed number of
inputs with a fixed seed (so that a run is repeatable), or for a time, and require that no input
crashed it, tripped a sanitizer or broke a property the fuzzer checks (fuzz_support.h: refused
only with one line, and a scene file that replays what was accepted).

The corpus (CORPUS/NAME) holds valid inputs and every input that once made a fuzzer fail,
so each of those bugs is tested on every run. New inputs the fuzzer finds go into WORK/NAME,
not into the source tree. A failing input is left in WORK as crash-* and printed.

usage: fuzz.py CORPUS WORK FUZZER... [--runs N | --seconds S]
       (ctest fuzz_parsers: 30000 runs each; ./gelx bench fuzz: benchmarks/fuzz.py)
"""
import pathlib
import re
import shutil
import subprocess
import sys


def option(args, name, default):
    if name not in args:
        return default
    i = args.index(name)
    value = int(args[i + 1])
    del args[i:i + 2]
    return value


args = sys.argv[1:]
runs = option(args, "--runs", 30000)
seconds = option(args, "--seconds", 0)
if seconds:
    runs = 0  # no bound on the count: the time bounds the run
corpus, work, fuzzers = pathlib.Path(args[0]), pathlib.Path(args[1]), args[2:]
failed = []
for fuzzer in fuzzers:
    name = pathlib.Path(fuzzer).name
    seeds = sorted((corpus / name).iterdir())
    found = work / name
    shutil.rmtree(found, ignore_errors=True)
    found.mkdir(parents=True)
    # -max_len: the corpus' inputs are under 200 bytes, and a parser's bugs need no more;
    # -timeout: one input parsed for 10 s is a hang (a loop that does not end)
    bound = [f"-max_total_time={seconds}"] if seconds else [f"-runs={runs}"]
    p = subprocess.run([fuzzer, *bound, "-seed=1", "-max_len=512", "-timeout=10",
                        "-rss_limit_mb=2048", f"-artifact_prefix={work}/{name}-",
                        str(found), str(corpus / name)],
                       capture_output=True, text=True, timeout=max(1200, 2 * seconds))
    read = re.search(r"INFO: seed corpus: files: (\d+)", p.stderr)
    done = re.search(r"Done (\d+) runs in (\d+) second", p.stderr)
    coverage = re.findall(r"cov: (\d+) ft: (\d+)", p.stderr)
    ok = (p.returncode == 0 and read and int(read[1]) == len(seeds) and done
          and int(done[1]) >= runs)
    print(f"{name}: {len(seeds)} corpus inputs read ({read and read[1]}), "
          f"{done and done[1]} runs in {done and done[2]} s, exit {p.returncode}, "
          f"{coverage and coverage[-1][0]} edges covered, "
          f"{len(list(found.iterdir()))} new inputs: {'ok' if ok else 'FAILED'}")
    if not ok:
        failed.append(name)
        print("\n".join(line for line in p.stderr.splitlines()
                        if not line.startswith(("#", "INFO:")))[-4000:])
        for artifact in work.glob(f"{name}-*"):
            print(f"failing input {artifact}: {artifact.read_bytes()[:300]!r}")
if failed:
    sys.exit(f"FAILED: {', '.join(failed)}")
print("PASSED")
