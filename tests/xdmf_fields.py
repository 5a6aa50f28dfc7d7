"""Read a scene's fields.xdmf / fields.h5 (dolfinx's XDMF output) with the XML parser and h5py,
independently of dolfinx: the node coordinates and one field's nodal values at one output step."""
import pathlib
import xml.etree.ElementTree as ET

import h5py


def hdf5_path(data_item):
    """The dataset path of an XDMF DataItem 'fields.h5:/Function/...'."""
    return data_item.text.strip().split(":", 1)[1]


class XdmfOutput:
    """The XML tree of OUTPUT_DIR/fields.xdmf and its HDF5 file."""

    def __init__(self, out):
        self.folder = pathlib.Path(out)
        self.domain = ET.parse(self.folder / "fields.xdmf").getroot().find("Domain")
        self.mesh_grid = self.domain.find("Grid[@Name='mesh']")

    def steps(self, name):
        """The Uniform grids of field `name`, one per output step, in output order."""
        return self.domain.find(f"Grid[@Name='{name}']").findall("Grid")

    def _mesh_array(self, item):
        with h5py.File(self.folder / "fields.h5", "r") as h5:
            return h5[hdf5_path(self.mesh_grid.find(f"{item}/DataItem"))][:]

    def geometry(self):
        """Node coordinates, (nodes, 3)."""
        return self._mesh_array("Geometry")

    def topology(self):
        """Cells' node indices, (cells, nodes per cell)."""
        return self._mesh_array("Topology")

    def field(self, name, step=-1):
        """(time, nodal values) of field `name` at output step `step` (default: the last)."""
        grid = self.steps(name)[step]
        with h5py.File(self.folder / "fields.h5", "r") as h5:
            values = h5[hdf5_path(grid.find("Attribute/DataItem"))][:]
        return float(grid.find("Time").get("Value")), values
