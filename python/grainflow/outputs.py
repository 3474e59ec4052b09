"""A run's outputs in memory: ``load_run(folder)`` reads what ``grainflow run`` wrote.

Every table of the folder (``timeseries.csv``, ``profiles.csv``, ``final_state.csv``,
``discharge.csv``, ``geometry.csv``, ``stresses.csv``, ...) becomes a dict {column: numpy array}
under the file's name without its extension, with the same column names and units as the file
(docs/OUTPUTS.md; the units line is kept under ``units``); ``summary.json`` and ``run_log.json``
become dicts; the HDF5 files (``trajectory.h5``, ``zone_series.h5``) dicts {dataset path: array}.
"""
import csv
import json
import os

import numpy as np


class Table(dict):
    """A CSV table: {column: numpy array}, in the file's column order; ``units`` is the file's
    ``# units: ...`` line (without the ``# ``), or ``""``."""

    units = ""

    @property
    def columns(self):
        return list(self.keys())

    def rows(self):
        """The number of data rows."""
        return 0 if not self else len(next(iter(self.values())))


def _column(values):
    try:
        return np.array([float(v) for v in values], dtype=np.float64)
    except ValueError:
        return np.array(values, dtype=object)


def read_table(path):
    """One CSV file of a run as a :class:`Table`."""
    units = []
    with open(path, newline="") as f:
        lines = [line for line in f]
    body = []
    for line in lines:
        if line.startswith("#"):
            units.append(line[1:].strip())
        elif line.strip():
            body.append(line)
    table = Table()
    table.units = "\n".join(units)
    if not body:
        return table
    reader = csv.reader(body)
    header = next(reader)
    rows = list(reader)
    for k, name in enumerate(header):
        table[name] = _column([row[k] if k < len(row) else "" for row in rows])
    return table


def read_hdf5(path):
    """An HDF5 file as {dataset path: numpy array} (attributes under ``attrs``)."""
    import h5py  # only when a run wrote one

    out = {"attrs": {}}
    with h5py.File(path, "r") as f:
        out["attrs"] = {k: f.attrs[k] for k in f.attrs}

        def visit(name, node):
            if isinstance(node, h5py.Dataset):
                out[name] = node[()]

        f.visititems(visit)
    return out


class RunOutputs:
    """What a run wrote, in memory. ``outputs["timeseries"]["time"]`` or
    ``outputs.timeseries["time"]``; ``outputs.names()`` lists what there is."""

    def __init__(self, folder):
        self.folder = os.fspath(folder)
        self._items = {}
        for name in sorted(os.listdir(self.folder)):
            path = os.path.join(self.folder, name)
            stem, ext = os.path.splitext(name)
            if not os.path.isfile(path) or name == "checkpoint.h5":
                continue
            if ext == ".csv":
                self._items[stem] = path
            elif ext == ".json":
                self._items[stem] = path
            elif ext == ".h5":
                self._items[stem] = path
            elif name == "resolved_case.toml":
                self._items["resolved_case"] = path
        analysis = os.path.join(self.folder, "analysis")
        if os.path.isdir(analysis):
            for name in sorted(os.listdir(analysis)):
                stem, ext = os.path.splitext(name)
                if ext in (".csv", ".json"):
                    self._items["analysis/" + stem] = os.path.join(analysis, name)
        self._loaded = {}

    def names(self):
        return list(self._items)

    def __contains__(self, name):
        return name in self._items

    def __getitem__(self, name):
        if name not in self._items:
            raise KeyError(f"{self.folder}: no output '{name}' (there are: {', '.join(self._items)})")
        if name not in self._loaded:
            path = self._items[name]
            if path.endswith(".csv"):
                self._loaded[name] = read_table(path)
            elif path.endswith(".json"):
                with open(path) as f:
                    self._loaded[name] = json.load(f)
            elif path.endswith(".h5"):
                self._loaded[name] = read_hdf5(path)
            else:
                with open(path) as f:
                    self._loaded[name] = f.read()
        return self._loaded[name]

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return self[name]
        except KeyError as e:
            raise AttributeError(str(e)) from None

    def __repr__(self):
        return f"<grainflow.RunOutputs {self.folder!r}: {', '.join(self._items)}>"


def load_run(folder):
    """The outputs of a finished run's folder (``grainflow run -o FOLDER`` or
    ``Simulation.run(output=FOLDER)``), read as they are asked for."""
    folder = os.fspath(folder)
    if not os.path.isfile(os.path.join(folder, "summary.json")):
        raise FileNotFoundError(f"{folder}: no summary.json: not the folder of a finished run")
    return RunOutputs(folder)


__all__ = ["load_run", "read_table", "read_hdf5", "RunOutputs", "Table"]
