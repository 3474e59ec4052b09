#!/usr/bin/python3
"""The output files as their users' tools open them. A small DEM run and a small event-driven run,
each with snapshots and a [trajectory]:

- snapshots/particles.pvd and its VTU files read with VTK's own readers (Debian's python3-vtk9;
  VTK 9.1 has no PVD reader, so the .pvd is parsed as the XML collection it is and each file read
  with vtkXMLUnstructuredGridReader): one point and one vertex cell per particle, the point-data
  arrays with their component counts and types, the listed times on the snapshot grid, and the last
  snapshot's positions equal to final_state.csv's to the VTU's 10 significant digits;
- trajectory.h5 opened with h5py: the datasets and attributes docs/OUTPUTS.md promises, shapes
  consistent with each other;
- every CSV file of the folders has a '# units:' comment line before its header.

Usage: /usr/bin/python3 tests/integration/test_vtu_reader.py PATH_TO_grainflow  (from the repo root)
"""
import json
import os
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, elastic_gas_case, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

DEM_N = 40
DEM_SNAPSHOT_INTERVAL = 0.01
DEM_DURATION = 0.03
DEM_CASE = f"""[engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.015, 0.05, 0.015]
boundary = {{ x = "periodic", y = ["wall", "open"], z = "periodic" }}

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = {DEM_N}

[particles]
init = "random"
expansion_time = 0.005
initial_temperature = 0.05
seed = 9

[contact]
k1 = 1.0e6
restitution = 0.9

[run]
duration = {DEM_DURATION}

[output]
interval = 0.005
snapshot_interval = {DEM_SNAPSHOT_INTERVAL}

[trajectory]
start = 0.01
samples = 20
"""

EDMD_SIDE, EDMD_DIM = 4, 3
EDMD_N = EDMD_SIDE ** EDMD_DIM
EDMD_SNAPSHOT_INTERVAL = 0.1
EDMD_DURATION = 0.3  # 3 * 0.1 rounds above 0.3: the last snapshot must still be taken

# The point-data arrays of a snapshot: name -> (components, VTK data type name).
POINT_ARRAYS = {"diameter": (1, "double"), "radius": (1, "double"), "velocity": (3, "double"),
                "angular_velocity": (3, "double"), "species": (1, "int"), "id": (1, "long long")}
DEM_DATASETS = {"id": 1, "time": 1, "velocity": 3, "position": 3}
DEM_ATTRIBUTES = ("window", "start", "time_step", "samples", "samples_requested", "max_lag", "diameter",
                  "restitution", "gravity_axis", "case", "version", "units")
EDMD_DATASETS = {"id": 1, "radius": 1, "time": 1, "position": 3, "velocity": 3, "angular_velocity": 3,
                 "wall_lo": 1, "wall_hi": 1, "strip_lo": 1, "strip_hi": 1, "box_width": 1}
EDMD_ATTRIBUTES = ("engine", "dimension", "flow_axis", "gradient_axis", "inertia_factor", "particles_total",
                   "strip_count", "period_y", "box_depth", "start", "interval", "samples", "samples_requested",
                   "case", "version", "units")


def read_vtu(path):
    """The unstructured grid in `path`, read by VTK; None (after a failed check) if VTK cannot."""
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if not check(grid is not None and grid.GetNumberOfPoints() > 0, f"VTK read no points from {path}"):
        return None
    return grid


def check_snapshot(label, grid, n):
    """Points, vertex cells and point-data arrays of one snapshot."""
    check(grid.GetNumberOfPoints() == n, f"{label}: {grid.GetNumberOfPoints()} points, expected {n} particles")
    check(grid.GetNumberOfCells() == n, f"{label}: {grid.GetNumberOfCells()} cells, expected {n} vertices")
    types = {grid.GetCellType(i) for i in range(grid.GetNumberOfCells())}
    check(types == {1}, f"{label}: cell types {types}, expected only VTK_VERTEX (1)")
    point_data = grid.GetPointData()
    for name, (components, type_name) in POINT_ARRAYS.items():
        array = point_data.GetArray(name)
        if not check(array is not None, f"{label}: VTK finds no point array '{name}'"):
            continue
        check(array.GetNumberOfComponents() == components,
              f"{label}: '{name}' has {array.GetNumberOfComponents()} components, expected {components}")
        check(array.GetNumberOfTuples() == n, f"{label}: '{name}' has {array.GetNumberOfTuples()} tuples, expected {n}")
        check(array.GetDataTypeAsString() == type_name,
              f"{label}: '{name}' is {array.GetDataTypeAsString()}, expected {type_name}")
    check(point_data.GetScalars() is not None and point_data.GetScalars().GetName() == "diameter",
          f"{label}: the active scalars are not 'diameter'")
    check(point_data.GetVectors() is not None and point_data.GetVectors().GetName() == "velocity",
          f"{label}: the active vectors are not 'velocity'")


def check_snapshots(out, n, interval, duration, tolerance):
    """The .pvd's times and files, each VTU through VTK, and the last one against final_state.csv."""
    pvd = os.path.join(out, "snapshots", "particles.pvd")
    if not check(os.path.isfile(pvd), f"{pvd} missing"):
        return
    datasets = ET.parse(pvd).getroot().findall("./Collection/DataSet")
    times = [float(d.get("timestep")) for d in datasets]
    expected = int(round(duration / interval)) + 1  # t = 0 and every interval up to the end
    check(len(times) == expected, f"{pvd}: {len(times)} snapshots at {times}, expected {expected}")
    for k, t in enumerate(times):
        check(abs(t - k * interval) <= tolerance, f"{pvd}: snapshot {k} at t = {t}, expected {k * interval}")
    grid = None
    for d in datasets:
        path = os.path.join(out, "snapshots", d.get("file"))
        grid = read_vtu(path)
        if grid is not None:
            check_snapshot(d.get("file"), grid, n)
    if grid is None or not times or not check(abs(times[-1] - duration) <= tolerance,
                                              f"the last snapshot is at {times[-1] if times else None}, not at the end {duration}"):
        return
    # The last snapshot is the final state: positions agree to the VTU's 10 significant digits.
    final = {int(r["id"]): r for r in read_csv(os.path.join(out, "final_state.csv"))}
    ids = vtk_to_numpy(grid.GetPointData().GetArray("id"))
    points = vtk_to_numpy(grid.GetPoints().GetData())
    worst = 0.0
    for i, p in zip(ids, points):
        row = final.get(int(i))
        if not check(row is not None, f"snapshot id {i} is not in final_state.csv"):
            return
        for axis, name in enumerate("xyz"):
            exact = float(row[name])
            worst = max(worst, abs(p[axis] - exact) / max(abs(exact), 1e-300))
    check(worst <= 1e-9, f"the last snapshot's positions differ from final_state.csv by {worst:.3g} (relative)")


def check_trajectory(out, datasets, attributes):
    """trajectory.h5 opens with h5py and holds the documented objects, with consistent shapes."""
    path = os.path.join(out, "trajectory.h5")
    if not check(os.path.isfile(path), f"{path} missing"):
        return
    with h5py.File(path, "r") as f:
        for name, components in datasets.items():
            if not check(name in f, f"trajectory.h5: no dataset /{name}"):
                continue
            shape = f[name].shape
            if components == 3:
                check(len(shape) == 3 and shape[2] == 3 and shape[:2] == (len(f["time"]), len(f["id"])),
                      f"trajectory.h5: /{name} has shape {shape}, expected [samples, particles, 3]")
            else:
                check(len(shape) == 1, f"trajectory.h5: /{name} has shape {shape}, expected one axis")
        for name in attributes:
            check(name in f.attrs, f"trajectory.h5: no attribute '{name}' on /")
        if "time" in f:
            check(len(f["time"]) >= 2, f"trajectory.h5: only {len(f['time'])} samples")


def check_csv_units(out):
    """Every CSV in the folder (and below) has a '# units:' line among its leading comments."""
    found = 0
    for folder, _, files in os.walk(out):
        for name in files:
            if not name.endswith(".csv"):
                continue
            found += 1
            with open(os.path.join(folder, name)) as f:
                comments = []
                for line in f:
                    if not line.startswith("#"):
                        break
                    comments.append(line)
            check(any(c.startswith("# units:") for c in comments), f"{os.path.relpath(os.path.join(folder, name), out)}: no '# units:' line")
    check(found >= 3, f"{out}: only {found} CSV files")


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory(prefix="grainflow_vtu_") as tmp:
        dem = os.path.join(tmp, "dem")
        status, _, err = run(exe, "run", write_text(os.path.join(tmp, "dem.toml"), DEM_CASE), "-o", dem, "--quiet")
        if check(status == 0, f"DEM run exited {status}: {err.strip()}"):
            # DEM snapshots fall on whole steps: within one step of the grid.
            with open(os.path.join(dem, "summary.json")) as f:
                step = json.load(f).get("time_step", 0.0)
            check_snapshots(dem, DEM_N, DEM_SNAPSHOT_INTERVAL, DEM_DURATION, step * 1.000001 + 1e-9)
            check_trajectory(dem, DEM_DATASETS, DEM_ATTRIBUTES)
            check_csv_units(dem)

        text, _ = elastic_gas_case(EDMD_DIM, EDMD_SIDE, 0.2, EDMD_DURATION,
                                   f"interval = 0.05\nsnapshot_interval = {EDMD_SNAPSHOT_INTERVAL}\n\n[trajectory]\nsamples = 5\n")
        edmd = os.path.join(tmp, "edmd")
        status, _, err = run(exe, "run", write_text(os.path.join(tmp, "edmd.toml"), text), "-o", edmd, "--quiet")
        if check(status == 0, f"edmd run exited {status}: {err.strip()}"):
            check_snapshots(edmd, EDMD_N, EDMD_SNAPSHOT_INTERVAL, EDMD_DURATION, 1e-9)
            check_trajectory(edmd, EDMD_DATASETS, EDMD_ATTRIBUTES)
            check_csv_units(edmd)
    return finish("test_vtu_reader")


if __name__ == "__main__":
    sys.exit(main())
