"""Read the fields of a gelx run (fields.xdmf and the HDF5 files it names) with the XML parser and
h5py, independently of dolfinx, and its tables (steps.csv, ...): for plots and for checks of the
output.

    series = FieldSeries("results/pyramid")
    series.times                       # one per step
    x, cells = series.mesh(-1)         # node coordinates and cell-node connectivity of a step
    u = series.field("displacement", -1)
    rows = read_table("results/pyramid/steps.csv")   # [{column: text}], one a step
    units = table_units("results/pyramid/steps.csv") # {column: unit}
"""
import csv
import pathlib
import re
import xml.etree.ElementTree as ET

import h5py


def read_table(path):
    """The rows of a gelx table as {column: text}, past the comment line of its units. A last
    line without its newline is a row a killed run was writing (tables grow by appending):
    skipped."""
    with open(path) as f:
        return list(csv.DictReader(line for line in f
                                   if not line.startswith("#") and line.endswith("\n")))


def table_units(path):
    """{column: unit} from a gelx table's first line, "# units: step [1], end_distance [mm], ..."
    ({} when it has none)"""
    with open(path) as f:
        first = f.readline()
    if not first.startswith("# units:"):
        return {}
    return dict(re.findall(r"(\w+) \[([^\]]*)\]", first))


class FieldSeries:
    def __init__(self, folder):
        self.folder = pathlib.Path(folder)
        root = ET.parse(self.folder / "fields.xdmf").getroot()
        self.grids = root.find("Domain/Grid").findall("Grid")
        self.times = [float(g.find("Time").get("Value")) for g in self.grids]

    def names(self, step):
        """The fields stored at a step (its index, negative from the end)."""
        return [a.get("Name") for a in self.grids[step].findall("Attribute")]

    def _read(self, data_item):
        file, dataset = data_item.text.strip().split(":")
        with h5py.File(self.folder / file, "r") as h5:
            values = h5[dataset][:]
        expected = tuple(int(n) for n in data_item.get("Dimensions").split())
        if values.shape != expected:
            raise ValueError(f"{file}:{dataset} has shape {values.shape}, the index says "
                             f"{expected}")
        return values

    def mesh(self, step):
        """(x, cells): the node coordinates and each cell's nodes, of a step's grid."""
        grid = self.grids[step]
        return (self._read(grid.find("Geometry/DataItem")),
                self._read(grid.find("Topology/DataItem")))

    def field(self, name, step):
        """Values of a field at a step: one row per node or per cell (its Center)."""
        for a in self.grids[step].findall("Attribute"):
            if a.get("Name") == name:
                return self._read(a.find("DataItem"))
        raise KeyError(f"no field '{name}' at step {step} (fields: {self.names(step)})")

    def centre(self, name, step):
        """'Node' or 'Cell': where a field's values sit."""
        for a in self.grids[step].findall("Attribute"):
            if a.get("Name") == name:
                return a.get("Center")
        raise KeyError(name)

