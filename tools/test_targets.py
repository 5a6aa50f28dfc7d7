"""The build targets the tests ctest selected need: the executables of the build tree that their
commands name (a scene's gelx-SCENE, a test program), fixtures included. Reads
`ctest -N --show-only=json-v1` on stdin and the build's target list (`cmake --build BUILD
--target help`) from the file TARGETS; prints one target per line.

usage: ctest --test-dir BUILD -N [selection] --show-only=json-v1 | test_targets.py BUILD TARGETS
"""
import json
import pathlib
import sys

build = pathlib.Path(sys.argv[1]).resolve()
# "... name" lines, or "name: phony" with other generators
known = {line.split()[-1].rstrip(":") for line in open(sys.argv[2]) if line.strip()}
named = {pathlib.Path(word).name
         for test in json.load(sys.stdin)["tests"] for word in test.get("command", [])
         if build in pathlib.Path(word).parents}
# CMake names each executable after its target
print("\n".join(sorted(named & known)))
