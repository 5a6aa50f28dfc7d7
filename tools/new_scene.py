"""`./gelx new NAME [--from SCENE]`: a new scene, demos/NAME, copied from demos/SCENE (default
block), with forms of its own, so that it builds and runs at once and its law can be edited
without touching the scene it came from.

What is copied and renamed:
- the scene's C++ sources, headers, CMakeLists.txt, view.json and plot.py (not its README,
  benchmarks, parameter studies or pictures: those describe the original);
- each forms file the scene's gelx_add_forms compiles, forms/F.py, to forms/NAME.py (one file)
  or forms/NAME_F.py (several). FFCx names what it generates after the file, so the sources'
  `form_F_...`, `functionspace_form_F_...`, `expression_F_...` and `#include "F.h"` follow;
- the scene's targets: gelx-SCENE... becomes gelx-NAME..., a library named after the scene
  (gelx_scene_SCENE) after NAME, any other library (gelx_forms_column) gets _NAME appended.
A README.md says where the scene came from and what to edit first.

usage: new_scene.py ROOT NAME SCENE
"""
import pathlib
import re
import shutil
import sys

root, name, origin = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3]
demos, forms_dir = root / "demos", root / "forms"


def fail(why):
    print(f"gelx new: {why}", file=sys.stderr)
    sys.exit(1)


if not re.fullmatch(r"[a-z][a-z0-9_]*", name):
    fail(f"'{name}' is not a scene name: lower-case letters, digits and '_', a letter first")
if (demos / name).exists():
    fail(f"demos/{name} exists already")
source = demos / origin
if not (source / "CMakeLists.txt").is_file():
    fail(f"no scene '{origin}' to start from (demos/{origin}/CMakeLists.txt)")

cmake = (source / "CMakeLists.txt").read_text()
form_files = [f for call in re.findall(r"gelx_add_forms\(\s*\S+\s+([^)]*)\)", cmake)
              for f in call.split()]
clash = [f for f in form_files if (forms_dir / f"{name}.py").exists()
         or (forms_dir / f"{name}_{f}.py").exists()]
if clash:
    fail(f"forms/{name}*.py exists already")
form_name = {f: name if len(form_files) == 1 else f"{name}_{f}" for f in form_files}

# The targets the scene defines, renamed
targets = re.findall(r"(?:add_executable|add_library|gelx_add_forms)\(\s*(\S+)", cmake)


def renamed_target(target):
    if target.startswith(f"gelx-{origin}"):
        return f"gelx-{name}" + target[len(f"gelx-{origin}"):]
    if origin in target:
        return target.replace(origin, name)
    return f"{target}_{name}"


target_name = {t: renamed_target(t) for t in targets}


def rename(text):
    """The scene's identifiers in a source, CMake or Python file, renamed"""
    for old, new in sorted(target_name.items(), key=lambda item: -len(item[0])):
        text = re.sub(rf"(?<![\w-]){re.escape(old)}(?![\w-])", new, text)
    text = re.sub(rf"\b(demos|results)/{origin}\b", rf"\1/{name}", text)
    for old, new in form_name.items():
        text = re.sub(rf"\b(functionspace_form|form|expression|coefficient)_{old}_",
                      rf"\1_{new}_", text)
        text = re.sub(rf'#include "{old}\.h"', f'#include "{new}.h"', text)
        text = re.sub(rf"forms/{old}\.py\b", f"forms/{new}.py", text)
        if old != new:
            text = re.sub(rf"(gelx_add_forms\(\s*\S+\s[^)]*?)\b{old}\b", rf"\1{new}", text)
    return text


(demos / name).mkdir()
copied = []
for path in sorted(source.iterdir()):
    if path.is_file() and (path.suffix in (".cpp", ".h") or path.name in
                           ("CMakeLists.txt", "view.json", "plot.py")):
        (demos / name / path.name).write_text(rename(path.read_text()))
        copied.append(path.name)
for old, new in form_name.items():
    shutil.copyfile(forms_dir / f"{old}.py", forms_dir / f"{new}.py")
forms_list = ", ".join(f"`forms/{f}.py`" for f in form_name.values())
(demos / name / "README.md").write_text(
    f"# {name}: a scene of one's own, started from {origin}\n\n"
    f"Made by `./gelx new {name} --from {origin}`: demos/{origin}'s driver and build, with its "
    f"forms copied to {forms_list}.\n\n"
    f"- Run it: `./gelx run {name}` (its parameters: `./gelx run {name} --help`); the results "
    f"go to `results/{name}/`.\n"
    f"- Change the law in {forms_list} (the energy density `psi`; see `forms/materials.py` "
    f"for the laws there are) and run again: only this scene is rebuilt.\n"
    f"- Change the geometry, the parameters and the boundary conditions in `main.cpp`; "
    f"`docs/new-scene.md` walks through each part.\n")
print(f"gelx new: demos/{name} ({', '.join(copied)}, README.md) and {forms_list}, from "
      f"demos/{origin}")
