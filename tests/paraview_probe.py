"""pvbatch script: what ParaView's own XDMF reader makes of a fields.xdmf, as one JSON line on
stdout (prefixed 'PROBE '): the reader, the time steps, and at the first and last step the data
set's class, its points and cells, and each array's centring, components and range.

usage: pvbatch paraview_probe.py FIELDS_XDMF
"""
import json
import sys

from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy

reader = simple.OpenDataFile(sys.argv[1])
times = [float(t) for t in reader.TimestepValues]


def arrays(attributes, centre):
    found = {}
    for i in range(attributes.GetNumberOfArrays()):
        values = vtk_to_numpy(attributes.GetArray(i)).reshape(attributes.GetArray(i).GetNumberOfTuples(), -1)
        found[attributes.GetArrayName(i)] = {"centre": centre, "components": values.shape[1],
                                             "min": values.min(axis=0).tolist(),
                                             "max": values.max(axis=0).tolist()}
    return found


steps = {}
for label, t in (("first", times[0]), ("last", times[-1])):
    reader.UpdatePipeline(t)
    data = servermanager.Fetch(reader)
    steps[label] = {"class": data.GetClassName()}
    if data.IsA("vtkDataSet"):
        steps[label].update(points=data.GetNumberOfPoints(), cells=data.GetNumberOfCells(),
                            arrays={**arrays(data.GetPointData(), "Node"),
                                    **arrays(data.GetCellData(), "Cell")})
print("PROBE " + json.dumps({"reader": reader.GetXMLName(), "times": times, "steps": steps}))
