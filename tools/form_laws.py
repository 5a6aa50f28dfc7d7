"""Which form files each law of forms/materials.py reaches, through the modules they import
(forms/_mixed.py, forms/gel.py, ...) and the functions of materials.py that call it, and the
scenes (demos/SCENE) or tests that compile those files: what editing a law changes.

usage: python3 tools/form_laws.py
"""
import pathlib
import re

root = pathlib.Path(__file__).resolve().parents[1]
forms = root / "forms"
texts = {p.stem: p.read_text() for p in forms.glob("*.py")}
laws = re.findall(r"^def (\w+)\(F\b", texts["materials"], re.M)


def uses(module, law, seen=()):
    text = texts[module]
    if re.search(rf"\bmaterials\.{law}\b", text):
        return True
    imported = re.findall(r"^(?:import|from) (\w+)", text, re.M)
    return any(uses(m, law, seen + (module,)) for m in imported
               if m in texts and m not in seen and m != "materials")


# the functions of materials.py that call each other (a helper reaches what its callers reach)
bodies = {name: body for name, body in
          re.findall(r"^def (\w+)(\(.*?)(?=^def |\Z)", texts["materials"], re.M | re.S)}


def callers(law, found=None):
    found = found if found is not None else {law}
    for name, body in bodies.items():
        if name not in found and re.search(rf"\b{law}\(", body):
            found.add(name)
            callers(name, found)
    return found


# who compiles each form file: gelx_add_forms(<target> <file>...) in a scene's or the tests'
# CMakeLists.txt
compiled_by = {}
for cmake in list(root.glob("demos/*/CMakeLists.txt")) + [root / "tests" / "CMakeLists.txt"]:
    user = cmake.parent.name if cmake.parent.parent.name == "demos" else "tests"
    for files in re.findall(r"gelx_add_forms\(\s*\S+\s+([^)]*)\)", cmake.read_text()):
        for f in files.split():
            compiled_by.setdefault(f, set()).add(user)

for law in laws:
    reached = [m for m in sorted(texts) if m != "materials" and not m.startswith("_")
               and any(uses(m, f) for f in callers(law))]
    users = sorted(set().union(*(compiled_by.get(m, set()) for m in reached)))
    print(f"{law}: form files {', '.join(reached) or '(none)'}; used by "
          f"{', '.join(users) or '(nothing)'}")
