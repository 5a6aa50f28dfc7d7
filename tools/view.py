"""pvbatch script: render a run's fields to PNG, the body deformed by its displacement and
coloured by one field, with a colour bar and the step's time. `./gelx view` runs it under a
virtual display (Debian's ParaView renders only on an X display).

usage: pvbatch view.py RESULTS [--defaults JSON] [--file XDMF] [--field NAME] [--step K]
                       [--png PATH] [--reflect PLANE ...] [--focus X Y Z] [--extent E]
                       [--direction X Y Z] [--up X Y Z] [--size W H]
  RESULTS     a run's results folder
  --defaults  a scene's picture (demos/SCENE/view.json): defaults for the options below, by
              their names
  --file      the field series in RESULTS (default fields.xdmf)
  --field     a point or cell array (default: a von Mises stress, else the first cell array,
              else the displacement)
  --step      index of the time step, negative from the end (default -1, the last)
  --png       the picture (default RESULTS/FIELD_stepK.png)
  --reflect   mirror the modelled part into the whole body (ParaView's Reflect planes:
              'X Min', 'Y Min', ...), in order
  --focus, --extent   the camera looks at X Y Z (reference configuration) and shows 2 E of
              height (default: the whole body)
  --direction, --up   the direction the camera looks along, and its up vector (default
              (-1, 1, -0.7), from the front right and above; +z up)
  --size      the picture's width and height in pixels (default 1200 900)
Bad input (no results, an unknown field, a step out of range) ends in one line and exit code 1.
"""
import argparse
import json
import pathlib
import sys

from paraview import simple

cli = argparse.ArgumentParser()
cli.add_argument("results", type=pathlib.Path)
cli.add_argument("--defaults", type=pathlib.Path)
cli.add_argument("--file", default="fields.xdmf")
cli.add_argument("--field")
cli.add_argument("--step", type=int, default=-1)
cli.add_argument("--png", type=pathlib.Path)
cli.add_argument("--reflect", nargs="*", default=[])
cli.add_argument("--focus", type=float, nargs=3)
cli.add_argument("--extent", type=float)
cli.add_argument("--direction", type=float, nargs=3, default=[-1, 1, -0.7])
cli.add_argument("--up", type=float, nargs=3, default=[0, 0, 1])
cli.add_argument("--size", type=int, nargs=2, default=[1200, 900])
args = cli.parse_args()
if args.defaults:
    # the scene's choices replace the defaults; the command line still overrides them
    cli.set_defaults(**json.loads(args.defaults.read_text()))
    args = cli.parse_args()
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
label = simple.Text(Text=f"step {args.step % len(times)} of {len(times) - 1}, t = {time:.6g}")
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
png = args.png or args.results / f"{field}_step{args.step % len(times)}.png"
simple.SaveScreenshot(str(png), view, ImageResolution=args.size)
print(f"gelx view: {png} ({field} at step {args.step % len(times)}, t = {time:.6g})")
