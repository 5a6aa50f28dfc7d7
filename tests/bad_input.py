"""Bad input to a scene ends with exactly one line 'gelx-SCENE: error: ...' on stderr, exit code 1
and no output folder; a run that fails after it started writing keeps its completed steps and
says "failed: ..." in summary.json; a valid --scene file is accepted and its values reach
summary.json.

Every real parameter that `--help` lists is given nan, inf and -inf, every integer one an
overflow and a fraction, every flag a non-boolean, so a newly declared parameter is covered
without editing this file. With MPIEXEC, the errors raised after MPI start-up are also run at
2 ranks: rank 0 alone reports them and no rank is left waiting in a collective.

usage: bad_input.py SCENE SCENE_BINARY WORK_DIR [MPIEXEC]
"""
import concurrent.futures
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

from checks import Checks

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "demos"))
from fields import FieldSeries, read_table  # noqa: E402  (demos/fields.py)

scene, binary, work = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
mpiexec = sys.argv[4] if len(sys.argv) > 4 else None
work.mkdir(parents=True, exist_ok=True)
checks = Checks()
error_prefix = f"gelx-{scene}: error: "
serial = scene == "flory_rehner"  # no MPI, no PETSc

# A mesh that ignores the scene's dimensions: the block's geometry with a fixed height of 3
tall_geo = work / "tall.geo"
tall_geo.write_text((pathlib.Path(__file__).resolve().parents[1] / "meshes" / "block.geo")
                    .read_text().replace("H = 2.0, ", "").replace("SetFactory", "H = 3;\nSetFactory"))

# Each scene's own refusals: (case name, arguments, what the error line must say). The cases
# named in TWO_RANKS are raised after MPI start-up and are repeated at 2 ranks.
CASES = {
    "block": [
        ("missing_mesh", ["--mesh", str(work / "no-such.geo")], "not found"),
        ("negative_modulus", ["--G", "-1"], "must be positive"),
        ("stretch_not_a_number", ["--stretch", "long"], "is not a finite number"),
        ("dt_above_dt_max", ["--dt", "0.5", "--dt_max", "0.25"], "dt_min <= dt <= dt_max"),
        ("unknown_linear_solver", ["-newton_linear_solver", "cholesky"],
         "unknown option set (direct, amg, fieldsplit)"),
        ("fieldsplit_not_mixed", ["-newton_linear_solver", "fieldsplit"],
         "needs a mixed displacement-pressure space"),
        ("malformed_mesh", ["--mesh", "/etc/passwd"],
         "mesh file '/etc/passwd': gmsh: '/etc/passwd', line 1: syntax error"),
        # at least 2e27 cells: refused before gmsh meshes (which would not end)
        ("absurd_mesh_size", ["--h", "1e-9"], "the mesh would have at least 2e+27 cells"),
        ("mesh_of_other_height", ["--mesh", str(tall_geo)],
         "the mesh spans z from 0 to 3, but --height makes it 0 to 2"),
        # refused when the Newton solver reads its options, before any step and any output (a
        # whole run before, then the first step)
        ("misspelt_option", ["--h", "0.5", "-newton_snes_rtoll", "1e-8"],
         "no solver object read the option(s) -newton_snes_rtoll (misspelt? the solver of "
         "prefix 'newton_' has read its options)"),
    ],
    "pyramid": [
        ("W_equal_L", ["--W", "8", "--L", "8"], "W must exceed the pyramid width L"),
        ("W_below_L", ["--W", "4"], "W must exceed the pyramid width L"),
        ("t_zero", ["--t", "0"], "'t' = 0: must be positive"),
        ("t_negative", ["--t", "-1"], "'t' = -1: must be positive"),
        ("cells_zero", ["--cells", "0"], "'cells' = 0: must be at least 1"),
        ("d_max_zero", ["--d_max", "0"], "'d_max' = 0: must be in (0, 1)"),
        ("d_max_one", ["--d_max", "1"], "'d_max' = 1: must be in (0, 1)"),
        ("unknown_law", ["--law", "ogden"], "'law' = ogden: must be nh, mr or le"),
        # a transfinite mesh: no mesh size bounds it, the scene's cell count does (gmsh
        # meshed until killed before)
        ("absurd_cells", ["--cells", "100000"], "the mesh would have at least 4e+15 cells "
         "(the scene's structured mesh)"),
    ],
    "inflation": [
        ("B_equal_A", ["--B", "1"], "B must exceed the inner radius A"),
        ("B_below_A", ["--A", "2", "--B", "1.5"], "B must exceed the inner radius A"),
        ("K_zero", ["--K", "0"], "'K' = 0: must be positive"),
        ("K_negative", ["--K", "-5"], "'K' = -5: must be positive"),
        ("inertia_without_factorisation", ["-arclength_linear_solver", "amg"],
         "stability inertia reads the inertia of a factorisation"),
        ("fieldsplit_not_mixed", ["-arclength_linear_solver", "fieldsplit",
                                  "-arclength_stability", "eigenvalue"],
         "needs a mixed displacement-pressure space"),
    ],
    "buckling": [
        ("ty_equal_tx", ["--ty", "1"], "the depth ty must exceed the width tx"),
        ("ty_below_tx", ["--tx", "2", "--ty", "1.5"], "the depth ty must exceed the width tx"),
        ("nu_half", ["--nu", "0.5"], "'nu' = 0.5: must be in (-1, 0.5)"),
        ("nu_minus_one", ["--nu", "-1"], "'nu' = -1: must be in (-1, 0.5)"),
    ],
    "fiber_gel": [
        ("phi_i_one", ["--phi_i", "1"], "must lie in (0, 1)"),
        ("phi_f_beyond_one", ["--phi_i", "0.6"], "phi_i / alpha0^3 must stay below 1"),
        ("negative_diameter", ["--d", "-10"], "must be positive"),
        ("negative_mesh_size", ["--h_fiber", "-1"], "must be positive"),
        ("cell_narrower_than_fiber", ["--D", "10"], "D must exceed the fiber diameter d"),
        ("fiber_longer_than_cell", ["--l", "40", "--L", "30"], "l must lie in [d, L]"),
        ("full_cell_with_rod", ["--cell", "full"], "needs a fiber shorter than the cell"),
        ("layers_of_a_cell", ["--layers", "2"], "layers of fibers other than one make a film"),
        ("order_three", ["--order", "3"], "must be 1 or 2"),
        ("chi_one_number", ["--chi", "0.5"], "'chi' = 0.5: must be 'fit' or two numbers 'A,B'"),
        ("chi_with_alpha0", ["--chi", "-0.7,0.0043", "--alpha0", "0.7"],
         "--chi gives chi(T), from which phi_i and alpha0 follow: give neither with it"),
    ],
    "flory_rehner": [
        ("negative_n_nu_vm", ["--n_nu_vm", "-0.1"], "every value must be positive"),
        ("nan_in_n_nu_vm", ["--n_nu_vm", "0.1,nan"], "'nan' in the list '0.1,nan' is not a finite"),
        ("garbage_in_n_nu_vm", ["--n_nu_vm", "0.1x"], "'0.1x' in the list '0.1x' is not a finite"),
        ("empty_item_in_n_nu_vm", ["--n_nu_vm", "0.1,"], "has an empty item"),
        ("phi_i_max_one", ["--phi_i_max", "1.0"], "must lie in (0, 1)"),
        ("phi_f_beyond_one", ["--alpha0", "0.77"], "must stay below alpha0^3"),
        ("grid_min_above_max", ["--eps_min", "0.5", "--eps_max", "0.2"], "min < max"),
        ("one_peo_value", ["--peo_chi_A", "0.5"], "needs all seven"),
    ],
    "swelling": [
        ("dry_reference", ["--lambda0", "1"], "must exceed 1 (the dry state is singular)"),
        ("negative_diffusivity", ["--D", "-1e-3"], "'D' = -0.001: must be positive"),
        ("supersaturated_solvent", ["--mu", "0.1"], "must be at most 0 (the pure solvent's)"),
        ("mu_below_reference", ["--mu", "-0.5"], "is below mu0"),
        ("flat_grading", ["--grading", "0.5"], "must be at least 1"),
        ("bonded_ellipsoid", ["--shape", "ellipsoid"], "is a free body: give --sides free"),
        ("unknown_shape", ["--shape", "cylinder"], "must be box or ellipsoid"),
        ("spinodal_reference", ["--chi", "0.85", "--dchi_dphi", "1"],
         "enters its spinodal at phi = 0.296296"),
        ("spinodal_on_the_way", ["--lambda0", "1.2", "--chi", "0.75", "--dchi_dphi", "0.5"],
         "enters its spinodal at phi = 0.4946"),
        ("unknown_newton_test", ["-swelling_newton_test", "cvode"],
         "-swelling_newton_test cvode: must be residual or correction"),
        ("misspelt_ts_option", ["-swelling_ts_bdf_ordr", "3"],
         "no solver object read the option(s) -swelling_ts_bdf_ordr"),
    ],
    "fiber_film": [
        ("spinodal_step", ["--alpha0", "0.8"], "into its spinodal"),
        ("negative_diffusivity", ["--diffusivity", "-1"], "'diffusivity' = -1: must be positive"),
        ("phi_f_beyond_one", ["--phi_i", "0.75"], "phi_i / alpha0^3 must stay below 1"),
        ("cell_narrower_than_fiber", ["--D", "10"], "D must exceed the fiber diameter d"),
        ("no_temperature_step", ["--T_f", "298"], "T_f must differ from T_i"),
        ("no_layers", ["--layers", "0"], "'layers' = 0: must be at least 1"),
        ("unknown_newton_test", ["-fiber_film_newton_test", "exact"],
         "-fiber_film_newton_test exact: must be residual or correction"),
    ],
    "design": [
        ("stretch_bounds_crossed", ["--stretch_min", "1.1", "--stretch_max", "0.9"],
         "stretch_min must be below stretch_max"),
        ("angle_bound_at_right_angle", ["--angle_max", "1.6"],
         "'angle_max' = 1.6: must lie in (0, pi/2)"),
        ("odd_layers", ["--nz", "3"], "'nz' = 3: must be even"),
        ("fewer_cells_than_slabs", ["--nx", "5", "--slabs", "10"],
         "nx must be at least the number of slabs"),
        ("negative_radius", ["--radius", "-1"], "'radius' = -1: must be positive"),
        ("zero_pitch", ["--pitch", "0"], "'pitch' = 0: must be positive"),
        ("perversion_turns_of_two_lengths",
         ["--shape", "perversion", "--length", "30", "--turns_after", "3"],
         "the perversion's helices need turns of one length"),
        ("perversion_radius_beyond_turn", ["--shape", "perversion", "--length", "30"],
         "radius must be below the turn's length / 2 pi"),
        ("perversion_between_slabs",
         ["--shape", "perversion", "--length", "30", "--radius", "1.2", "--slabs", "4"],
         "perversion_at must be a slab boundary"),
        ("perversion_of_rates", ["--shape", "perversion", "--objective", "centreline"],
         "the perversion needs --objective placement"),
    ],
    "bistrip": [
        ("unknown_layer_kind", ["--section", "B 9x3, Q 9x3"], "unknown kind 'Q'"),
        ("layer_without_size", ["--section", "B 9x3, A 9"], "write KIND WIDTHxTHICKNESS"),
        ("stretch_zero", ["--stretch", "0"], "'stretch' = 0: must be positive"),
        ("unstable_bonded_state", ["--stretch", "0.4", "--nz", "20"],
         "the bonded strip is unstable"),
        ("negative_modulus", ["--G", "-1.5"], "'G' = -1.5: must be positive"),
        ("unknown_law", ["--law", "ogden"], "must be nh or mr"),
        ("mooney_share_of_neo_hookean", ["--mooney_share", "0.3"],
         "--mooney_share applies to --law mr only"),
        ("mooney_share_one", ["--law", "mr", "--mooney_share", "1"], "must be in [0, 1)"),
        ("degree_three", ["--degree", "3"], "'degree' = 3: must be 1 or 2"),
        ("unknown_ends", ["--ends", "glued"], "must be clamped or free"),
        ("end_distance_beyond_L", ["--end_distance", "300"], "end_distance must be below L"),
        ("seed_mode_not_computed", ["--modes", "2", "--seed_mode", "3"],
         "seed_mode must be one of the computed modes"),
        ("noise_without_mode", ["--seed", "random", "--noise", "0.01"],
         "--noise adds to a seeded mode: --seed mode"),
        # 300 mm slab: the first critical shortening 73 % off (ran to the end before, rc 0)
        ("one_slab", ["--nz", "1"], "--nz 1 makes slabs of 300 mm, more than 3.5 times the "
         "section's thickness 4.7 mm: the strip's buckling is not resolved (use --nz 19"),
        # 6 hexahedra a slab
        ("absurd_nz", ["--nz", "100000000"], "the mesh would have at least 6e+08 cells "
         "(the scene's structured mesh)"),
    ],
}
TWO_RANKS = {"block": ["missing_mesh", "dt_above_dt_max", "fieldsplit_not_mixed",
                       "malformed_mesh", "absurd_mesh_size", "mesh_of_other_height",
                       "misspelt_option"],
             "pyramid": ["W_below_L", "absurd_cells"],
             "inflation": ["B_equal_A"], "buckling": ["ty_equal_tx"],
             "fiber_gel": ["cell_narrower_than_fiber", "phi_f_beyond_one"],
             "bistrip": ["unknown_layer_kind", "end_distance_beyond_L"],
             "swelling": ["mu_below_reference"], "design": ["fewer_cells_than_slabs"],
             "fiber_film": ["spinodal_step"]}

# A valid scene file per scene (values other than the defaults, for a run of a few seconds),
# with the status its run must end in. The buckling run stops after max_steps on its straight
# path, before the bifurcation: the run failure this scene can be asked for.
SCENE_FILES = {
    "block": ({"h": "0.5", "stretch": "1.3", "twist": "45", "degree": "1"}, "completed"),
    "pyramid": ({"cells": "1", "tip_levels": "1", "d_max": "0.1", "dt": "0.25", "dt_max": "0.5",
                 "extrapolate": "false"}, "completed"),
    "inflation": ({"h": "0.25", "descend_to": "0.99"}, "completed"),
    "buckling": ({"max_steps": "3", "modes": "2"}, "failed: no bifurcation found"),
    "fiber_gel": ({"l": "20", "L": "35", "D": "25", "h_fiber": "3", "h_far": "8"}, "completed"),
    "bistrip": ({"ends": "free", "stretch": "1.02", "L": "60", "nz": "20"}, "completed"),
    "swelling": ({"nz": "10", "chi": "0.5", "end_time": "100", "ramp_time": "2"}, "completed"),
    "fiber_film": ({"h_far": "8", "end_time": "1e-6", "ramp_time": "1e-7"}, "completed"),
    "design": ({"length": "4", "nx": "4", "slabs": "2", "radius": "2", "pitch": "3"},
               "completed"),
    "flory_rehner": ({"n_phi": "20", "n_eps": "11", "n_nu_vm": "0.01", "peo_n_grid": "5",
                      "alpha0": "0.77", "phi_i_max": "0.45"}, "completed"),
}


def run(args, ranks=1, timeout=120):
    """Run the scene; None if it does not end within `timeout` seconds (a rank left waiting)."""
    command = ([mpiexec, "-q", "-np", str(ranks)] if ranks > 1 else []) + [binary] + args
    try:
        return subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None


def one_error_line(what, p, expect, ranks=1):
    """Exit code exactly 1 and one stderr line naming the scene and containing `expect`."""
    if p is None:
        checks.require(f"{what} at {ranks} rank(s): no end within the time limit", False)
        return
    lines = p.stderr.splitlines()
    checks.require(f"{what} at {ranks} rank(s): exit code {p.returncode}, stderr {lines!r}",
                   p.returncode == 1 and len(lines) == 1 and lines[0].startswith(error_prefix)
                   and expect in lines[0])


def refuse(cases, ranks=1):
    """Input errors: one error line, exit code 1, and no output folder. The runs go four at a
    time: each spends about half its wall time waiting for MPI start-up."""
    def attempt(case):
        name, args, expect = case
        out = work / f"{name}_np{ranks}"
        shutil.rmtree(out, ignore_errors=True)
        return run(["--output", str(out)] + args, ranks), out

    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        results = list(pool.map(attempt, cases))
    for (name, _, expect), (p, out) in zip(cases, results):
        one_error_line(name, p, expect, ranks)
        checks.require(f"{name} at {ranks} rank(s): output folder "
                       f"{'created' if out.exists() else 'not created'}", not out.exists())


def parameters_from_help():
    """name -> (kind, default) from the --help lines '  --name  default  kind  help'."""
    p = run(["--help"])
    lines = [line for line in p.stdout.splitlines() if line.startswith("  --")]
    table = {}
    for line in lines:
        m = re.match(r"  --(\S+) +(\S+) +(real|integer|flag|text) ", line)
        if m:
            table[m[1]] = (m[3], m[2])
    checks.require(f"--help: exit code {p.returncode}, {len(lines)} parameters listed, "
                   f"{len(table)} read with their kind",
                   p.returncode == 0 and len(lines) > 0 and len(table) == len(lines))
    return table


def read_summary(folder):
    path = folder / "summary.json"
    return json.loads(path.read_text()) if path.exists() else {}


def data_rows(steps_csv):
    """The data rows of a steps.csv: 0 when it holds its header only or was not written"""
    return len(read_table(steps_csv)) if steps_csv.exists() else 0


def typed(kind, text):
    return {"real": float, "integer": int, "flag": lambda t: t == "true", "text": str}[kind](text)


# 1. Every parameter the scene declares, given a value of the wrong kind
parameters = parameters_from_help()
reals = [n for n, (kind, _) in parameters.items() if kind == "real"]
integers = [n for n, (kind, _) in parameters.items() if kind == "integer"]
flags = [n for n, (kind, _) in parameters.items() if kind == "flag"]
texts = [n for n, (kind, _) in parameters.items() if kind == "text"]
print(f"real parameters: {' '.join(reals)}")
cases = [(f"{n}_{v.replace('-', 'minus_')}", [f"--{n}", v], f"'{n}': '{v}' is not a finite number")
         for n in reals for v in ["nan", "inf", "-inf"]]
cases += [(f"{n}_{label}", [f"--{n}", v], f"'{n}': '{v}' is not an integer")
          for n in integers for label, v in [("overflow", "99999999999"), ("fraction", "2.5")]]
cases += [(f"{n}_not_boolean", [f"--{n}", "maybe"], f"'{n}': 'maybe' is not true or false")
          for n in flags]

# 2. The same through the scene file, and the ways a command line or scene file goes wrong
first = reals[0]
nan_file, garbled_file = work / "nan.scene", work / "garbled.scene"
nan_file.write_text(f"# a scene file\n{first} = nan\n")
garbled_file.write_text(f"{first} = {parameters[first][1]}\nthis line has no equals sign\n")
bad_source_file = work / "bad_source.scene"
bad_source_file.write_text("source forms/materials.py = 0123abc\n")
cases += [
    ("trailing_garbage", [f"--{first}", "1.5x"], f"'{first}': '1.5x' is not a finite number"),
    ("real_overflow", [f"--{first}", "1e999"], f"'{first}': '1e999' is not a finite number"),
    ("nan_in_scene_file", ["--scene", str(nan_file)], f"'{first}': 'nan' is not a finite number"),
    ("missing_value", [f"--{first}"], f"option --{first} needs a value"),
    ("unknown_option", ["--stiffness", "3"], "unknown parameter 'stiffness'"),
    ("stray_argument", ["stray"], "unexpected argument 'stray'"),
    ("missing_scene_file", ["--scene", str(work / "no-such.scene")], "cannot read scene file"),
    ("garbled_scene_file", ["--scene", str(garbled_file)],
     f"{garbled_file}:2: expected 'name = value'"),
    # the record of what a run was computed from (gelx/io/sources.h) takes a whole SHA-256
    ("short_source_hash", ["--scene", str(bad_source_file)],
     f"{bad_source_file}:1: expected 'source PATH = SHA-256 in 64 hex digits'"),
    ("scene_file_is_a_folder", ["--scene", str(work)], "cannot read scene file"),
    # A word that is neither a parameter, a PETSc option nor an option's value: PETSc would
    # ignore it, and scene.txt could not replay it (tests/fuzz found "-2.5" after --offset)
    ("stray_negative_number", ["-5"], "unexpected argument '-5'"),
    ("petsc_value_with_space", ["-x_ksp_type", "a b"],
     "PETSc argument 'a b' holds a space, which a scene file cannot hold"),
    # Texts a scene file could not replay, or summary.json hold
    (f"{texts[0]}_with_hash", [f"--{texts[0]}", "a#b"],
     f"'{texts[0]}': the text holds '#', which starts a comment in a scene file"),
    (f"{texts[0]}_not_utf8", [f"--{texts[0]}", os.fsdecode(b"caf\xe9")],
     f"'{texts[0]}': the text is not UTF-8"),
]
refuse(cases + CASES[scene])

# 3. At 2 ranks: a parse error, and the scene's errors raised after MPI start-up
if mpiexec and not serial:
    refuse([(f"{first}_nan", [f"--{first}", "nan"], "is not a finite number")]
           + [c for c in CASES[scene] if c[0] in TWO_RANKS[scene]], ranks=2)

# 4. A valid scene file: its values reach summary.json
values, status = SCENE_FILES[scene]
scene_file = work / "valid.scene"
scene_file.write_text("# a short run\n" + "".join(f"{k} = {v}  # not the default\n"
                                                  for k, v in values.items()))
out = work / "valid_scene_file"
shutil.rmtree(out, ignore_errors=True)
p = run(["--scene", str(scene_file), "--output", str(out)], timeout=600)
if status == "completed":
    checks.require(f"valid scene file: exit code {p and p.returncode}, stderr "
                   f"{p and p.stderr.splitlines()!r}", p and p.returncode == 0 and p.stderr == "")
else:
    one_error_line("valid scene file, run failure", p, status[len("failed: "):])
summary = read_summary(out)
checks.require(f"valid scene file: summary status {summary.get('status')!r} "
               f"(expected {status!r}...)", summary.get("status", "").startswith(status))
for name, text in values.items():
    kind, default = parameters[name]
    value = summary.get("parameters", {}).get(name)
    checks.require(f"valid scene file: summary parameter {name} = {value!r} (file {text}, "
                   f"default {default})",
                   value == typed(kind, text) and typed(kind, default) != typed(kind, text))

# 5. Run failures after the output was started: the completed steps stay readable
if scene == "buckling":
    # steps.csv keeps the max_steps points of the straight path, all below the critical load
    # (eigenvalues.csv), which is why the path found no bifurcation
    rows = read_table(out / "steps.csv")
    critical = float(read_table(out / "eigenvalues.csv")[0]["critical_load_over_euler"])
    loads = [float(r["load_factor"]) for r in rows]
    checks.require(f"no bifurcation: steps.csv holds {len(rows)} points on paths "
                   f"{sorted({r['path'] for r in rows})}, loads {loads} rising and below the "
                   f"critical load {critical:.6g} (max_steps {values['max_steps']})",
                   len(rows) == int(values["max_steps"])
                   and all(r["path"] == "straight" for r in rows)
                   and all(a < b for a, b in zip(loads, loads[1:])) and loads[-1] < critical)
    checks.require(f"no bifurcation: summary records {summary.get('arclength_steps')} path "
                   f"steps", summary.get("arclength_steps") == len(rows))

if scene == "block":
    # Divergence: a first small step, then a jump to the full load that 4 Newton iterations
    # cannot reach, with cut-back disabled
    out = work / "forced_divergence"
    shutil.rmtree(out, ignore_errors=True)  # its summary must be this run's
    p = run(["--output", str(out), "--h", "0.5", "--dt", "0.05", "--dt_grow", "20",
             "--dt_max", "1", "--max_cutbacks", "0", "-newton_snes_max_it", "4"],
            timeout=600)
    one_error_line("forced_divergence", p, "(results of the completed steps are kept)")
    summary = read_summary(out)
    checks.require(f"forced_divergence: summary status {summary.get('status', '')[:40]!r}..., "
                   f"{summary.get('steps')} completed step",
                   summary.get("status", "").startswith("failed: ") and summary["steps"] == 1)
    fields = FieldSeries(out)
    u = fields.field("displacement", 0)
    checks.require(f"forced_divergence: fields.xdmf readable with {len(fields.times)} step, "
                   f"displacement of shape {u.shape}", len(fields.times) == 1 and u.shape[1] == 3)
    rows = read_table(out / "steps.csv")
    checks.require(f"forced_divergence: steps.csv has {len(rows)} data row", len(rows) == 1)

    # MUMPS reads its options at the first factorisation: a misspelt one ends the run at the
    # first step's end, not after its last (one row kept)
    out = work / "misspelt_mumps_option"
    shutil.rmtree(out, ignore_errors=True)  # its summary must be this run's
    p = run(["--output", str(out), "--h", "0.5", "--dt", "0.05", "-newton_mat_mumps_icntl_99",
             "1"], timeout=600)
    one_error_line("misspelt_mumps_option", p, "no solver object read the option(s) "
                   "-newton_mat_mumps_icntl_99 (misspelt?")
    summary = read_summary(out)
    rows = data_rows(out / "steps.csv")
    checks.require(f"misspelt_mumps_option: stopped after the first step: {rows} data row of "
                   f"20, summary status {summary.get('status', '')[:50]!r}...",
                   rows == 1 and summary.get("status", "").startswith("failed: no solver"))

if scene == "bistrip":
    # A damped path whose time steps fall below -dynamics_min_step stops with one line and a
    # failed summary instead of stepping on (here at once: the first step, T / 50, is below
    # the floor of T / 2)
    out = work / "step_floor"
    shutil.rmtree(out, ignore_errors=True)  # its summary must be this run's
    p = run(["--output", str(out), "--nz", "20", "--end_distance", "290", "--modes", "1",
             "-dynamics_min_step", "0.5"], timeout=300)
    one_error_line("step_floor", p, "below -dynamics_min_step 0.5 s")
    summary = read_summary(out)
    checks.require(f"step_floor: summary status {summary.get('status', '')[:60]!r}...",
                   summary.get("status", "").startswith("failed: damped dynamics stopped"))

if scene == "flory_rehner":
    # N nu / V_m = 1e300 has no swollen state in (0, 1): the first map fails after the folder
    # was made
    out = work / "no_root"
    shutil.rmtree(out, ignore_errors=True)
    p = run(["--output", str(out), "--n_nu_vm", "1e300", "--n_phi", "5", "--n_eps", "5"])
    one_error_line("no_root", p, "no root in (0, 1)")
    summary = read_summary(out)
    checks.require(f"no_root: summary status {summary.get('status')!r}",
                   summary.get("status", "").startswith("failed: ")
                   and "no root" in summary.get("status", ""))

if scene == "swelling":
    # BoomerAMG's interpolation of the rigid-body modes asked for on the fieldsplit's u block:
    # hypre crashes on the mixed space's numbering (SEGV, exit code 59, PETSc's page of
    # lines), so gelx refuses it with one line once the solver reads its options, which the
    # scene sets up before its output folder
    out = work / "vec_interp_on_mixed_u"
    shutil.rmtree(out, ignore_errors=True)
    p = run(["--output", str(out), "--nz", "4", "--end_time", "1", "-swelling_linear_solver",
             "fieldsplit", "-swelling_fieldsplit_u_pc_type", "hypre",
             "-swelling_fieldsplit_u_pc_hypre_boomeramg_vec_interp_variant", "3"], timeout=300)
    one_error_line("vec_interp_on_mixed_u", p,
                   "needs a node's displacement components numbered together")
    checks.require(f"vec_interp_on_mixed_u: output folder "
                   f"{'created' if out.exists() else 'not created'}", not out.exists())
checks.finish()
