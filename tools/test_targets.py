"""The build targets the tests ctest selected need: the executables of the build tree that their
commands name (a scene's gelx-SCENE, a test program), fixtures included. Reads
`ctest -N --show-only=json-v1` on stdin and the build's target list (`cmake --build BUILD
--target help`) from the file TARGETS; prints one target per line, or `all` when a selected
test's program is not built yet (ctest lists no command for it).

usage: ctest --test-dir BUILD -N [selection] --show-only=json-v1 | test_targets.py BUILD TARGETS
"""
import json
import pathlib
import sys

build = pathlib.Path(sys.argv[1]).resolve()
# "... name" lines, or "name: phony" with other generators
known = {line.split()[-1].rstrip(":") for line in open(sys.argv[2]) if line.strip()}
tests = json.load(sys.stdin)["tests"]
# A test whose command is a test program itself has no command in ctest's listing until that
# program is built (ctest cannot find the executable): then only the whole build will do
if any("command" not in test for test in tests):
    print("all")
    sys.exit(0)
# A test given the build tree itself (readme_commands) runs whatever it finds there
if any(pathlib.Path(word).resolve() == build for test in tests for word in test["command"]):
    print("all")
    sys.exit(0)
named = {pathlib.Path(word).name for test in tests for word in test["command"]
         if build in pathlib.Path(word).parents}
# CMake names each executable after its target, and a shared library lib<target>.so (one a
# test preloads)
named |= {name[3:-3] for name in named if name.startswith("lib") and name.endswith(".so")}
print("\n".join(sorted(named & known)))
