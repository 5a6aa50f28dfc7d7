"""Every command in the READMEs' fenced blocks runs as written: each `./gelx run SCENE ...` and
each `[mpirun -np N] build/demos/SCENE/gelx-... ...` line (continued lines joined, comments
dropped) is run with the built executable, its output in a scratch folder and
`--stop_after_steps 1` added, so that it stops after its first step: its parameters, PETSc options,
mesh, solver set-up and first step must work (exit code 0 and a summary.json that says
"completed"); `--help` lines must list the parameters. Lines that are not runs (`./gelx test`,
`bench`, `sweep`: their own tests and benchmarks), and lines with placeholders or a file the
reader supplies, are listed as skipped, with the reason.

usage: readme_commands.py SOURCE_DIR BUILD_DIR MPIEXEC OUT_DIR
"""
import concurrent.futures
import json
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import time

from checks import Checks

source, build, mpiexec, out = (pathlib.Path(a) for a in sys.argv[1:5])
checks = Checks()
shutil.rmtree(out, ignore_errors=True)
readmes = [source / "README.md"] + sorted((source / "demos").glob("*/README.md")) \
    + [source / "forms" / "README.md"] + sorted((source / "docs").glob("*.md"))


def commands(readme):
    """The command lines of the fenced blocks, continued lines joined"""
    for block in re.findall(r"^```[^\n]*\n(.*?)^```", readme.read_text(), re.S | re.M):
        for line in re.sub(r"\\\n\s*", " ", block).splitlines():
            line = line.split(" #")[0].strip()
            if line.startswith(("./gelx", "build/", "mpirun")) and "gelx" in line:
                yield line


def executable(words):
    """(ranks, executable, arguments) of a command, or (None, why, None) when it is not run"""
    if words[:2] == ["./gelx", "run"]:
        scene = words[2] if len(words) > 2 and not words[2].startswith("-") else "pyramid"
        args = words[3:] if len(words) > 2 and words[2] == scene else words[2:]
        ranks = "1"
        if "--np" in args:
            i = args.index("--np")
            ranks = args[i + 1]
            args = args[:i] + args[i + 2:]
        return ranks, build / "demos" / scene / f"gelx-{scene}", args
    if words[0] == "./gelx":
        return None, f"'./gelx {words[1]}' is not a run (it has its own tests)", None
    ranks = "1"
    if words[0] == "mpirun":
        ranks, words = words[2], words[3:]
    return ranks, build / words[0].removeprefix("build/"), words[1:]


# Collect the runs, then run them two at a time (the machines have two cores; ctest runs the
# suite one test after the other)
runs, run_count = [], 0
for readme in readmes:
    for line in commands(readme):
        where = f"{readme.relative_to(source)}: {line}"
        words = shlex.split(line)
        ranks, exe, args = executable(words)
        if ranks is None:
            print(f"SKIP  {where}: {exe}")
            continue
        if any(w in ("N", "OUT", "NAME") or "$" in w for w in words) or "my_peo.scene" in line:
            print(f"SKIP  {where}: a placeholder or a file the reader supplies")
            continue
        checks.require(f"{where}: the executable {exe.relative_to(build)} is built", exe.is_file())
        if not exe.is_file():
            continue
        if args == ["--help"]:
            p = subprocess.run([str(exe), "--help"], capture_output=True, text=True)
            listed = len(re.findall(r"^\s+--\w+", p.stdout, re.M))
            checks.require(f"{where}: exit code {p.returncode}, {listed} parameters listed",
                           p.returncode == 0 and listed > 0)
            continue
        run_count += 1
        folder = out / f"run{run_count}"
        # the README's own --output (a path for the reader) is replaced by the scratch folder
        if "--output" in args:
            i = args.index("--output")
            args = args[:i] + args[i + 2:]
        runs.append((where, exe, folder,
                     [str(mpiexec), "-np", ranks, str(exe), "--output", str(folder), *args]))


def run(where, exe, folder, command):
    flory_rehner = exe.name == "gelx-flory_rehner"  # no path: it runs whole (0.8 s)
    extra = [] if flory_rehner else ["--stop_after_steps", "1"]
    start = time.time()
    p = subprocess.run(command + extra, capture_output=True, text=True, timeout=900)
    summary = folder / "summary.json"
    status = json.loads(summary.read_text()).get("status", "") if summary.is_file() else ""
    ok = p.returncode == 0 and (flory_rehner or status.startswith("completed"))
    return where, p, status, ok, time.time() - start


with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
    for where, p, status, ok, seconds in pool.map(lambda r: run(*r), runs):
        checks.require(f"{where}: exit code {p.returncode}, status '{status}' ({seconds:.0f} s)",
                       ok)
        if not ok:
            print(p.stderr[-1500:])
checks.require(f"{run_count} commands run", run_count > 20)
checks.finish()
