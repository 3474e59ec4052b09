#!/usr/bin/python3
"""The output folder of a short run with snapshots (INTERFACE.md "The output folder"): a PVD index
listing VTU files at increasing times, each VTU well-formed with one point per particle and the
arrays ParaView needs at the right sizes, final_state.csv with its exact header and one row per
particle, summary.json valid JSON, and no temporary files left behind.

Usage: /usr/bin/python3 tests/integration/test_outputs.py PATH_TO_grainflow  (from the repo root)
"""
import csv
import json
import math
import os
import sys
import tempfile
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

SNAPSHOT_INTERVAL = 0.01  # s
DURATION = 0.05           # s
SPECIES = {"glass": (0.003, 2490.0, 30), "steel": (0.002, 7800.0, 20)}  # name: (diameter m, density, count)
N = sum(count for _, _, count in SPECIES.values())

CASE = """[engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.06, 0.02]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[gravity]
vector = [0.0, -9.81, 0.0]
""" + "".join(f"""
[[species]]
name = "{name}"
diameter = {d}
density = {rho}
count = {count}
""" for name, (d, rho, count) in SPECIES.items()) + f"""
[particles]
init = "random"
expansion_time = 0.01
initial_temperature = 0.01
seed = 4

[contact]
k1 = 1.0e6
restitution = 0.9
friction = 0.3

[run]
duration = {DURATION}

[output]
interval = 0.005
snapshot_interval = {SNAPSHOT_INTERVAL}
"""

def values_of(array):
    return (array.text or "").split()


def check_vtu(path, time):
    """Parses one VTU and checks its points and arrays; returns (ids, diameters, species)."""
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as error:
        check(False, f"{path} is not well-formed XML: {error}")
        return None
    name = os.path.basename(path)
    check(root.tag == "VTKFile" and root.get("type") == "UnstructuredGrid", f"{name}: not a VTK UnstructuredGrid file")
    piece = root.find("./UnstructuredGrid/Piece")
    if not check(piece is not None, f"{name}: no Piece"):
        return None
    points = int(piece.get("NumberOfPoints", -1))
    check(points == N, f"{name} (t = {time}): NumberOfPoints = {points}, expected {N} particles")
    arrays = {a.get("Name"): a for a in piece.findall("./PointData/DataArray")}
    for array_name, components in (("diameter", 1), ("velocity", 3), ("angular_velocity", 3), ("species", 1), ("id", 1)):
        if not check(array_name in arrays, f"{name}: no PointData array '{array_name}'"):
            continue
        array = arrays[array_name]
        check(int(array.get("NumberOfComponents", "1")) == components,
              f"{name}: '{array_name}' has {array.get('NumberOfComponents', '1')} components, expected {components}")
        count = len(values_of(array))
        check(count == components * points, f"{name}: '{array_name}' holds {count} values, expected {components * points}")
    position = piece.find("./Points/DataArray")
    if check(position is not None, f"{name}: no Points"):
        check(len(values_of(position)) == 3 * points, f"{name}: Points holds {len(values_of(position))} values, expected {3 * points}")
        check(all(math.isfinite(float(v)) for v in values_of(position)), f"{name}: non-finite positions")
    cells = piece.find("./Cells")
    check(cells is not None, f"{name}: no Cells (ParaView needs vertex cells to show the points)")
    if not all(a in arrays for a in ("id", "diameter", "species")):
        return None
    ids = [int(v) for v in values_of(arrays["id"])]
    diameters = [float(v) for v in values_of(arrays["diameter"])]
    species = [int(v) for v in values_of(arrays["species"])]
    return ids, diameters, species


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory(prefix="grainflow_outputs_") as tmp:
        case_path = write_text(os.path.join(tmp, "outputs.toml"), CASE)
        out = os.path.join(tmp, "out")
        status, _, err = run(exe, "run", case_path, "-o", out, "--quiet")
        if not check(status == 0, f"run exited {status}: {err.strip()}"):
            return 1

        # --- summary.json
        with open(os.path.join(out, "summary.json")) as f:
            try:
                summary = json.load(f)
            except json.JSONDecodeError as error:
                check(False, f"summary.json is not valid JSON: {error}")
                summary = {}
        check(summary.get("particles") == N, f"summary particles = {summary.get('particles')}, expected {N}")
        check(summary.get("errors") == [], f"summary errors = {summary.get('errors')}")
        time_step = summary.get("time_step", 0.0)

        # --- snapshots/particles.pvd: the VTU files, at increasing times k * snapshot_interval.
        pvd_path = os.path.join(out, "snapshots", "particles.pvd")
        if not check(os.path.isfile(pvd_path), "snapshots/particles.pvd missing"):
            return 1
        root = ET.parse(pvd_path).getroot()
        check(root.tag == "VTKFile" and root.get("type") == "Collection", "particles.pvd is not a VTK Collection")
        datasets = root.findall("./Collection/DataSet")
        times = [float(d.get("timestep")) for d in datasets]
        files = [d.get("file") for d in datasets]
        expected_count = int(round(DURATION / SNAPSHOT_INTERVAL)) + 1  # t = 0 and every interval
        check(len(datasets) == expected_count, f"particles.pvd lists {len(datasets)} snapshots, expected {expected_count}")
        check(all(b > a for a, b in zip(times, times[1:])), f"snapshot times do not increase: {times}")
        for k, t in enumerate(times):
            # Snapshots fall on whole steps: within one step of k * interval (plus the printed digits).
            check(abs(t - k * SNAPSHOT_INTERVAL) <= time_step * 1.000001 + 1e-9,
                  f"snapshot {k} at t = {t}, expected {k * SNAPSHOT_INTERVAL} within one step {time_step}")
        check(len(set(files)) == len(files), "particles.pvd lists a file twice")
        vtu_on_disk = sorted(f for f in os.listdir(os.path.join(out, "snapshots")) if f.endswith(".vtu"))
        check(sorted(files) == vtu_on_disk, f"particles.pvd lists {sorted(files)}, the folder holds {vtu_on_disk}")

        largest = {i: d for i, (d, _, _) in enumerate(SPECIES.values())}
        for k, (t, name) in enumerate(zip(times, files)):
            path = os.path.join(out, "snapshots", name)
            if not check(os.path.isfile(path), f"{name} listed in particles.pvd does not exist"):
                continue
            parsed = check_vtu(path, t)
            if parsed is None:
                continue
            ids, diameters, species = parsed
            check(sorted(ids) == list(range(N)), f"{name}: ids are not 0..{N - 1}")
            check(all(s in largest for s in species), f"{name}: species indices {sorted(set(species))}")
            # Diameters grow to the species' diameter during radius expansion (section 2.2) and stay there.
            check(all(0.0 < d <= largest[s] * (1 + 1e-9) for d, s in zip(diameters, species)),
                  f"{name}: diameters outside (0, species diameter]")
            if t > 0.02:  # expansion_time = 0.01 s: all spheres are full-sized by then
                check(all(abs(d - largest[s]) <= 1e-9 * largest[s] for d, s in zip(diameters, species)),
                      f"{name} (t = {t}): diameters differ from the species' after the expansion")
            counts = [species.count(i) for i in range(len(SPECIES))]
            check(counts == [c for _, _, c in SPECIES.values()], f"{name}: species counts {counts}")

        # --- final_state.csv: exact header, one row per particle.
        with open(os.path.join(out, "final_state.csv")) as f:
            lines = [line.rstrip("\n") for line in f if not line.startswith("#")]
        check(lines[0] == "id,species,diameter,x,y,z,vx,vy,vz,wx,wy,wz", f"final_state.csv header is {lines[0]!r}")
        rows = list(csv.DictReader(lines))
        check(len(rows) == N, f"final_state.csv has {len(rows)} rows, expected {N}")
        check(sorted(int(r["id"]) for r in rows) == list(range(N)), "final_state.csv ids are not 0..N-1")
        for r in rows:
            name = r["species"]
            if not check(name in SPECIES, f"final_state.csv: unknown species {name!r}"):
                continue
            check(abs(float(r["diameter"]) - SPECIES[name][0]) <= 1e-12, f"final_state.csv: particle {r['id']} diameter {r['diameter']}")
            check(all(math.isfinite(float(r[c])) for c in ("x", "y", "z", "vx", "vy", "vz", "wx", "wy", "wz")),
                  f"final_state.csv: particle {r['id']} has non-finite values")
        check([sum(1 for r in rows if r["species"] == s) for s in SPECIES] == [c for _, _, c in SPECIES.values()],
              "final_state.csv species counts differ from the case")

        # --- the other files exist and parse; no temporary files anywhere.
        for name in ("timeseries.csv", "profiles.csv"):
            check(len(read_csv(os.path.join(out, name))) > 0, f"{name} has no rows")
        leftovers = [os.path.join(d, f) for d, _, fs in os.walk(out) for f in fs if ".tmp-" in f]
        check(not leftovers, f"temporary files left behind: {leftovers}")

    return finish("test_outputs")


if __name__ == "__main__":
    sys.exit(main())
