"""pvbatch script: render a run's fields to PNG, the body deformed by its displacement and
coloured by one field, with a colour bar and the step's time. `./gelx view` runs it on a
virtual display (Debian's ParaView renders only on an X display); `--help` (under any
python3: ParaView is imported after it) lists the options and the fields of RESULTS.
Bad input (no results, an unknown field, a step out of range) ends in one line and exit code 1.
"""
import argparse
import json
import pathlib
import sys
import xml.etree.ElementTree as ET

cli = argparse.ArgumentParser(
    prog="./gelx view [SCENE]", add_help=False,
    description="A picture (PNG) of a run's results: the body deformed by its displacement, "
                "coloured by one field at one step. `./gelx view SCENE` reads results/SCENE "
                "with the scene's choices (demos/SCENE/view.json).")
cli.add_argument("results", type=pathlib.Path, help="a run's results folder (./gelx view: "
                 "--output DIR, default results/SCENE)")
cli.add_argument("-h", "--help", action="store_true", help="this help, and the fields of "
                 "RESULTS")
cli.add_argument("--defaults", type=pathlib.Path, help="a scene's picture "
                 "(demos/SCENE/view.json): defaults for the options below, by their names")
cli.add_argument("--file", default="fields.xdmf", help="the field series in RESULTS "
                 "(default fields.xdmf)")
cli.add_argument("--field", help="a point or cell array (default: a von Mises stress, else "
                 "the first cell array, else the displacement)")
cli.add_argument("--step", type=int, default=-1, help="index of the output, negative from the "
                 "end (default -1, the last)")
cli.add_argument("--load-name", default="t", help="what the outputs' time is in the label "
                 "(default t; a scene's view.json names its own: d/H, T, ...)")
cli.add_argument("--png", type=pathlib.Path, help="the picture (default "
                 "RESULTS/FIELD_stepK.png)")
cli.add_argument("--reflect", nargs="*", default=[], metavar="PLANE", help="mirror the "
                 "modelled part into the whole body (ParaView's Reflect planes: 'X Min', "
                 "'Y Min', ...), in order")
cli.add_argument("--focus", type=float, nargs=3, metavar=("X", "Y", "Z"), help="the point "
                 "the camera looks at (reference configuration; default: the body's centre)")
cli.add_argument("--extent", type=float, help="half the height the picture shows (default: "
                 "the whole body)")
cli.add_argument("--direction", type=float, nargs=3, default=[-1, 1, -0.7],
                 metavar=("X", "Y", "Z"), help="the direction the camera looks along "
                 "(default -1 1 -0.7: from the front right and above)")
cli.add_argument("--up", type=float, nargs=3, default=[0, 0, 1], metavar=("X", "Y", "Z"),
                 help="the camera's up vector (default +z)")
cli.add_argument("--size", type=int, nargs=2, default=[1200, 900], metavar=("W", "H"),
                 help="the picture's width and height in pixels (default 1200 900)")
args = cli.parse_args()
if args.defaults:
    # the scene's choices replace the defaults; the command line still overrides them
    cli.set_defaults(**json.loads(args.defaults.read_text()))
    args = cli.parse_args()
if args.help:
    cli.print_help()
    series = args.results / args.file
    try:
        grids = ET.parse(series).getroot().find("Domain/Grid").findall("Grid")
        names = [a.get("Name") for a in grids[-1].findall("Attribute")]
        print(f"\nfields of {series} ({len(grids)} outputs): {', '.join(names)}")
    except (OSError, ET.ParseError, AttributeError, IndexError):
        print(f"\n({series}: no readable results, so no fields to list)")
    sys.exit(0)

from paraview import simple  # noqa: E402  (after --help, which needs no ParaView)

xdmf = args.results / args.file


def fail(why):
    print(f"gelx view: {why}", file=sys.stderr)
    sys.exit(1)


if not xdmf.is_file():
    fail(f"no results: {xdmf} is missing (run the scene first)")
try:
    reader = simple.OpenDataFile(str(xdmf))
except Exception as e:  # ParaView raises a bare RuntimeError for an unreadable file
    fail(f"cannot read {xdmf}: {e}")
if reader is None:
    fail(f"cannot read {xdmf}")
# ParaView gives a list of the times, one float for a single step, or nothing for none
values = reader.TimestepValues
times = ([float(values)] if isinstance(values, (int, float)) else list(values or [])) or [0.0]
if not -len(times) <= args.step < len(times):
    fail(f"step {args.step} is out of range: {xdmf} has {len(times)} steps "
         f"(0 to {len(times) - 1}, or -1 for the last)")
time = times[args.step]
reader.UpdatePipeline(time)
point_arrays = list(reader.PointData.keys())
cell_arrays = list(reader.CellData.keys())
von_mises = [a for a in cell_arrays if a.endswith("_vm")]
field = args.field or (von_mises + cell_arrays + ["displacement"])[0]
if field not in point_arrays + cell_arrays:
    fail(f"no field '{field}' in {xdmf} (fields: {', '.join(point_arrays + cell_arrays)})")

body = reader
for plane in args.reflect:
    body = simple.Reflect(Input=body, Plane=plane, CopyInput=1)
if "displacement" in point_arrays:
    body = simple.WarpByVector(Input=body, Vectors=["POINTS", "displacement"], ScaleFactor=1.0)

view = simple.CreateView("RenderView")
view.ViewSize = args.size
view.ViewTime = time
view.UseColorPaletteForBackground = 0
view.Background = [1, 1, 1]
view.OrientationAxesVisibility = 1
view.OrientationAxesLabelColor = [0, 0, 0]
display = simple.Show(body, view)
centring = "POINTS" if field in point_arrays else "CELLS"
simple.ColorBy(display, (centring, field, "Magnitude"))
display.RescaleTransferFunctionToDataRange(True, False)
display.SetScalarBarVisibility(view, True)
bar = simple.GetScalarBar(simple.GetColorTransferFunction(field), view)
bar.Title = field
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0, 0, 0]
# outputs counted from 1, as the rows of steps.csv and the progress lines count them
output = args.step % len(times) + 1
label = simple.Text(Text=f"output {output} of {len(times)}, {args.load_name} = {time:.6g}")
label_display = simple.Show(label, view)
label_display.Color = [0, 0, 0]
label_display.WindowLocation = "Upper Left Corner"

view.CameraParallelProjection = 1
view.CameraFocalPoint = [0, 0, 0]
view.CameraPosition = [-d for d in args.direction]
view.CameraViewUp = args.up
simple.ResetCamera(view)  # the whole body, seen along the direction
if args.focus:
    shift = [f - c for f, c in zip(args.focus, view.CameraFocalPoint)]
    view.CameraPosition = [p + s for p, s in zip(view.CameraPosition, shift)]
    view.CameraFocalPoint = args.focus
if args.extent:
    view.CameraParallelScale = args.extent
png = args.png or args.results / f"{field}_output{output}.png"
simple.SaveScreenshot(str(png), view, ImageResolution=args.size)


def numbers(values):
    return " ".join(f"{v:.9g}" for v in values)


# The camera as the options that give this picture again (or a close-up of it)
print(f"gelx view: {png} ({field} at output {output} of {len(times)}, "
      f"{args.load_name} = {time:.6g}); camera: --direction {numbers(args.direction)} "
      f"--up {numbers(args.up)} --focus {numbers(view.CameraFocalPoint)} "
      f"--extent {view.CameraParallelScale:.9g}")
