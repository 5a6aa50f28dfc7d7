"""pvbatch script: what ParaView's own XDMF reader makes of a fields.xdmf, as one JSON line on
stdout (prefixed 'PROBE '): the reader, the time steps, and at the first and last step the data
set's class, its points and cells, each array's centring, components and range, each array's
values at four named places (the points and cells of least and greatest x + 2y + 3z), and the
arrays ParaView takes as tensors.

usage: pvbatch paraview_probe.py FIELDS_XDMF
"""
import json
import sys

import numpy as np

from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy

reader = simple.OpenDataFile(sys.argv[1])
values = reader.TimestepValues  # one float when the file holds one step
times = [float(values)] if isinstance(values, (int, float)) else [float(t) for t in values]


def arrays(attributes, centre):
    found = {}
    for i in range(attributes.GetNumberOfArrays()):
        values = vtk_to_numpy(attributes.GetArray(i)).reshape(attributes.GetArray(i).GetNumberOfTuples(), -1)
        found[attributes.GetArrayName(i)] = {"centre": centre, "components": values.shape[1],
                                             "min": values.min(axis=0).tolist(),
                                             "max": values.max(axis=0).tolist()}
    return found


def named(data):
    """Each array's values where the data set itself says: at the points of least and greatest
    x + 2y + 3z (ties are unlikely on these meshes), at the cells of least and greatest such
    centroid (the mean of their points), with those points' and centroids' coordinates."""
    points = vtk_to_numpy(data.GetPoints().GetData())
    offsets = vtk_to_numpy(data.GetCells().GetOffsetsArray())
    connectivity = vtk_to_numpy(data.GetCells().GetConnectivityArray())
    centroids = np.array([points[connectivity[a:b]].mean(axis=0)
                          for a, b in zip(offsets[:-1], offsets[1:])])
    at = {}
    for attributes, where, xyz in ((data.GetPointData(), "Node", points),
                                   (data.GetCellData(), "Cell", centroids)):
        order = xyz @ [1.0, 2.0, 3.0]
        for end, index in (("least", int(np.argmin(order))), ("greatest", int(np.argmax(order)))):
            values = {attributes.GetArrayName(i):
                      [float(v) for v in attributes.GetArray(i).GetTuple(index)]
                      for i in range(attributes.GetNumberOfArrays())}
            at[f"{where} {end}"] = {"xyz": [float(v) for v in xyz[index]], "values": values}
    return at


steps = {}
for label, t in (("first", times[0]), ("last", times[-1])):
    reader.UpdatePipeline(t)
    data = servermanager.Fetch(reader)
    steps[label] = {"class": data.GetClassName()}
    if data.IsA("vtkDataSet"):
        steps[label].update(points=data.GetNumberOfPoints(), cells=data.GetNumberOfCells(),
                            arrays={**arrays(data.GetPointData(), "Node"),
                                    **arrays(data.GetCellData(), "Cell")},
                            named=named(data),
                            # the arrays ParaView takes as tensors (its tensor filters' input)
                            tensors=[a.GetTensors().GetName() for a in
                                     (data.GetPointData(), data.GetCellData()) if a.GetTensors()])
print("PROBE " + json.dumps({"reader": reader.GetXMLName(), "times": times, "steps": steps}))
