"""Figures of a bistrip run (thesis chapter 3), written into its results folder:

    modes.png              the buckling modes (Fig. 3.1c)
    shapes.png             the strip at six end distances, coloured by von Mises stress (Fig. 3.5)
    shapes_normalized.png  the same shapes stretched to one length (Fig. 3.4a)
    slab_energy.png        the scaled slab energy E~(n) near 20, 15 and 9 cm (Fig. 3.4b)
    sections.png           the energy density over three cross-sections (Fig. 3.6)
    path.png               end force, strip energies, kinetic ratio and perversions against
                           the end distance

A --ends free run (summary.json tells) gets centreline.png alone: the bent bilayer seen from
the side. A figure whose input is missing or still empty is skipped with a line saying so:
sections.csv exists only when a perversion was found, and a run still going may be short of
any file.

usage: plot.py OUTPUT_DIR
"""
import json
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.cm import ScalarMappable  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.colors import Normalize  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from fields import FieldSeries, read_table  # noqa: E402  (demos/fields.py)

# The six faces of a hexahedron in the XDMF (VTK) node order, each a ring of four nodes
HEX_FACES = np.array([[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6],
                      [3, 0, 4, 7]])
VIEW_ELEVATION = np.radians(35)


def present(path):
    """Whether a file holds data: a CSV table a row, a field series (its .xdmf) a step."""
    if not path.exists():
        return False
    if path.suffix == ".xdmf":
        return len(FieldSeries(path.parent).times) > 0
    return len(read_table(path)) > 0


def table(out, name):
    return read_table(out / name)


def column(rows, key):
    return np.array([float(r[key]) for r in rows])


def boundary_faces(cells):
    """(faces, owner): the faces that belong to one cell only, as node rings, and that cell."""
    faces = cells[:, HEX_FACES].reshape(-1, 4)
    _, first, count = np.unique(np.sort(faces, axis=1), axis=0, return_index=True,
                                return_counts=True)
    outer = first[count == 1]
    return faces[outer], outer // len(HEX_FACES)


def drawn_faces(points, cells, values, norm, cmap):
    """The strip's outer quadrilaterals seen from its +x side, tilted down by VIEW_ELEVATION
    (an orthographic view, its axis z horizontal): their screen corners, far ones first (the
    painter's order), and their colours, darkened as they turn away from the viewer."""
    faces, owner = boundary_faces(cells)
    c, s = np.cos(VIEW_ELEVATION), np.sin(VIEW_ELEVATION)
    towards, up = np.array([c, s, 0]), np.array([-s, c, 0])
    corners = points[faces]
    normal = np.cross(corners[:, 2] - corners[:, 0], corners[:, 3] - corners[:, 1])
    facing = np.abs(normal @ towards) / np.linalg.norm(normal, axis=1)
    colours = cmap(norm(values[owner]))
    colours[:, :3] *= (0.5 + 0.5 * facing)[:, None]
    order = np.argsort(corners.mean(axis=1) @ towards)
    screen = np.stack([corners[..., 2], corners @ up], axis=-1)
    return screen[order], colours[order]


def stacked_strips(strips, colour_label, norm, cmap):
    """The strips (title, points, cells, cell values) one below the other in one view, to one
    scale, with one colour bar."""
    drawn = [drawn_faces(points, cells, values, norm, cmap) for _, points, cells, values in strips]
    length = max(screen[..., 0].max() for screen, _ in drawn)
    # Room for the widest strip and a title line above it
    spacing = 1.2 * max(np.ptp(screen[..., 1]) for screen, _ in drawn) + 0.03 * length
    fig, ax = plt.subplots(figsize=(11, 1 + 8 * spacing * len(strips) / length))
    for k, ((title, *_), (screen, colours)) in enumerate(zip(strips, drawn)):
        screen[..., 1] += -k * spacing - screen[..., 1].mean()
        ax.add_collection(PolyCollection(screen, facecolors=colours, edgecolors="none"))
        ax.text(0, screen[..., 1].max() + 0.005 * length, title, fontsize=9)
    ax.set_xlim(-0.02 * length, 1.02 * length)
    ax.set_ylim(-(len(strips) - 0.5) * spacing, 0.6 * spacing)
    ax.set_aspect("equal")
    ax.set_axis_off()
    fig.colorbar(ScalarMappable(norm, cmap), ax=ax, label=colour_label, shrink=0.7)
    return fig


def plot_modes(out):
    modes = FieldSeries(out / "modes")
    strips = []
    for k, row in enumerate(table(out, "eigenvalues.csv")):
        x, cells = modes.mesh(k)
        mode = modes.field("mode", k)
        # A mode's largest component is 1: drawn at a tenth of L, its shape shows
        size = np.linalg.norm(mode, axis=1)[cells].mean(axis=1)
        strips.append((f"mode {row['mode']}: critical end distance "
                       f"{float(row['critical_end_distance']) / 10:.2f} cm, {row['symmetry']}",
                       x + 0.1 * x[:, 2].max() * mode, cells, size / size.max()))
    return stacked_strips(strips, "|mode| (cell mean, scaled to its largest)", Normalize(0, 1),
                          plt.cm.viridis)


def plot_shapes(out, normalized):
    series = FieldSeries(out)
    # Output i of fields.xdmf is row i of steps.csv
    t = column(table(out, "steps.csv"), "end_distance")[:len(series.times)]
    # The last output of each end distance (the final one is written again after the hold),
    # then six of them spread over the run, the last always among them
    distinct = [i for i in range(len(t)) if i + 1 == len(t) or t[i + 1] != t[i]]
    shown = [distinct[j] for j in np.unique(np.linspace(0, len(distinct) - 1, 6).round())
             .astype(int)]
    strips = []
    for i in shown:
        x, cells = series.mesh(i)
        points = x + series.field("displacement", i)
        if normalized:
            points[:, 2] *= x[:, 2].max() / t[i]
        strips.append((f"end distance {t[i] / 10:.1f} cm", points, cells,
                       series.field("cauchy_stress_vm", i).ravel()))
    top = max(values.max() for *_, values in strips)
    fig = stacked_strips(strips, "von Mises stress (MPa)", Normalize(0, top), plt.cm.jet)
    if normalized:
        fig.axes[0].set_title("each shape stretched along its axis to the strip's length "
                              "(Fig. 3.4a)", fontsize=9)
    return fig


def perversions_of(row):
    return [float(z) for z in row["perversion_positions"].split(";") if z]


def plot_slab_energy(out):
    slabs = table(out, "slab_energy.csv")
    # slab_energy.csv is written after steps.csv: a running job's last row may be ahead
    written = max(int(r["output"]) for r in slabs)
    steps = [r for r in table(out, "steps.csv") if int(r["output"]) <= written]
    d = column(steps, "end_distance")
    # The last output within 5 mm of each thesis distance (half the output spacing), and the
    # final one
    latest = {target: len(d) - 1 - int(np.argmin(np.abs(d[::-1] - target)))
              for target in (200, 150, 90)}
    chosen = sorted({i for target, i in latest.items() if abs(d[i] - target) < 5}
                    | {len(d) - 1})
    fig, ax = plt.subplots(figsize=(8, 4))
    for colour, i in enumerate(chosen):
        profile = [r for r in slabs if r["output"] == steps[i]["output"]]
        n, z = column(profile, "slab"), column(profile, "z")
        ax.plot(n, column(profile, "energy_scaled"), "-", color=f"C{colour}",
                label=f"{d[i] / 10:.1f} cm, {steps[i]['perversions']} perversion(s)")
        # A perversion at reference position Z, in slab units (slab n's centre sits at n)
        for Z in perversions_of(steps[i]):
            ax.axvline(np.interp(Z, z, n), color=f"C{colour}", ls="--", lw=0.8)
    ax.set_xlabel("slab n")
    ax.set_ylabel("E~(n) = E(n) / min E - 1")
    ax.set_title("slab energy along the strip (Fig. 3.4b); dashed: perversions", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def plot_sections(out):
    rows = table(out, "sections.csv")
    sites = ["helix", "perversion_edge", "perversion_centre"]  # the thesis' sites 1, 2, 3
    fig, axes = plt.subplots(1, 3, figsize=(12, 3), layout="constrained")
    # Strip A (prestretched) holds far more energy than B: each strip its own scale, as in the
    # thesis, shared by the three sites
    for strip, cmap in (("A", "magma"), ("B", "viridis")):
        psi = column([r for r in rows if r["strip"] == strip], "energy_density")
        levels = np.linspace(psi.min(), psi.max(), 21)
        for ax, site in zip(axes, sites):
            points = [r for r in rows if r["site"] == site and r["strip"] == strip]
            ax.tricontourf(column(points, "x"), column(points, "y"),
                           column(points, "energy_density"), levels=levels, cmap=cmap)
            ax.set_title(f"{site.replace('_', ' ')} (slab {points[0]['slab']})", fontsize=10)
        fig.colorbar(ScalarMappable(Normalize(psi.min(), psi.max()), cmap), ax=axes,
                     label=f"strip {strip}: energy density (MPa)")
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
    axes[0].set_ylabel("y (mm): B below 0, A above")
    return fig


def plot_path(out):
    rows = table(out, "steps.csv")
    d = column(rows, "end_distance") / 10
    length = column(table(out, "centreline.csv"), "Z").max() / 10
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(7, 9))
    axes[0].plot(d, column(rows, "end_force"), "o-", ms=3)
    axes[0].set_ylabel("end force (N, > 0: tension)")
    for strip in "AB":
        energy = column(rows, f"strain_energy_{strip}")
        axes[1].plot(d, energy - energy[0], "o-", ms=3, label=f"strip {strip}")
    axes[1].set_ylabel(f"strain energy since {d[0]:.1f} cm (mJ)")
    axes[1].legend(fontsize=8)
    axes[2].semilogy(d, column(rows, "kinetic_ratio"), "o-", ms=3)
    axes[2].set_ylabel("kinetic / strain energy")
    for r, distance in zip(rows, d):
        positions = perversions_of(r)
        axes[3].plot([distance] * len(positions), np.array(positions) / 10, "k.")
    axes[3].set_ylim(0, length)
    axes[3].set_ylabel("perversion position Z (cm)")
    count = axes[3].twinx()
    count.step(d, column(rows, "perversions"), where="mid", color="C3")
    count.yaxis.set_major_locator(MaxNLocator(integer=True))
    count.set_ylabel("perversions", color="C3")
    axes[3].set_xlabel("end distance (cm), decreasing to the right as the ends approach")
    axes[3].invert_xaxis()
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def plot_free_centreline(out):
    rows = table(out, "centreline.csv")
    y, z = column(rows, "y"), column(rows, "z")
    # The circle closest to the centreline (least squares in y² + z² = 2 a y + 2 b z + c)
    a, b, c = np.linalg.lstsq(np.column_stack([2 * y, 2 * z, np.ones_like(y)]), y**2 + z**2,
                              rcond=None)[0]
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(z, y, "-")
    ax.set_aspect("equal")
    ax.set_xlabel("z (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"free bilayer, side view: radius of curvature {np.sqrt(c + a**2 + b**2):.4g}"
                 " mm (circle fit)", fontsize=10)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def main(out):
    """Every figure whose inputs the run folder holds."""
    summary = out / "summary.json"
    free = summary.exists() and json.loads(summary.read_text())["parameters"]["ends"] == "free"
    # (figure, its inputs, how to draw it)
    figures = [("centreline.png", ["centreline.csv"], plot_free_centreline)] if free else [
        ("modes.png", ["eigenvalues.csv", "modes/fields.xdmf"], plot_modes),
        ("shapes.png", ["fields.xdmf"], lambda o: plot_shapes(o, normalized=False)),
        ("shapes_normalized.png", ["fields.xdmf"], lambda o: plot_shapes(o, normalized=True)),
        ("slab_energy.png", ["slab_energy.csv", "steps.csv"], plot_slab_energy),
        ("sections.png", ["sections.csv"], plot_sections),
        ("path.png", ["steps.csv", "centreline.csv"], plot_path)]
    for name, inputs, draw in figures:
        missing = [f for f in inputs if not present(out / f)]
        if missing:
            print(f"skipped {name}: {', '.join(missing)} missing or empty in {out}")
            continue
        draw(out).savefig(out / name, dpi=120, bbox_inches="tight")
        print(f"wrote {out / name}")


if __name__ == "__main__":  # sweep.py imports the figures
    main(pathlib.Path(sys.argv[1]))
