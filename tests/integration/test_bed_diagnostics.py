#!/usr/bin/python3
"""Bed diagnostics of a DEM run end to end (Lan 1994 sections 4.2, 5.1, 5.2): a large sphere placed
at the centre of the floor with a bed poured around it, flat frictional side walls along z and a
[field] and a [tracers] table. Checks identities the outputs must satisfy exactly:
- bed height x bulk solids fraction x cross-section = volume of the spheres in the bed (section 4.2's
  definition of bulk nu), with no grains in flight once the bed has settled; the settled bed packs
  between 0.45 and 0.66 (frictional spheres between walls pack looser than random close packing,
  0.64; a wrong height, e.g. off by the floor or by a diameter, moves nu by > 15%);
- the velocity field counts every free particle once per sample (sum of visits = samples x N);
- the placed sphere starts where the case put it, is followed in tracers.csv, and rests on the
  floor touching it and its neighbours;
- collisions per particle and the profile error-bar columns are written;
- bad [field] / [tracers] / species.position input is refused with exit status 2, naming the key.

Usage: /usr/bin/python3 tests/integration/test_bed_diagnostics.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

D, BIG, N = 0.003, 0.009, 150
LX, LZ = 0.021, 0.018  # periodic x must hold 2 (largest diameter + skin)
CASE = f"""[engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [{LX}, 0.05, {LZ}]
boundary = {{ x = "periodic", y = ["wall", "open"], z = "wall" }}

[[species]]
name = "glass"
diameter = {D}
density = 2490.0
count = {N}

[[species]]
name = "large"
diameter = {BIG}
density = 2490.0
count = 1
position = [{LX / 2}, {BIG / 2}, {LZ / 2}]

[particles]
init = "random"
region_hi = [{LX}, 0.04, {LZ}]
expansion_time = 0.02
seed = 3

[contact]
k1 = 1.0e6
restitution = 0.6
friction = 0.5

[run]
duration = 0.45

[output]
interval = 0.005
average_start = 0.3

[field]
axis = "z"
start = 0.3
interval = 0.001
phase_bins = 0

[tracers]
species = ["large"]
interval = 0.01
"""


def bad_input(exe, tmp, replace, add, key):
    text = CASE.replace(*replace) if replace else CASE
    case = write_text(os.path.join(tmp, "bad.toml"), text + add)
    status, _, err = run(exe, "check", case)
    check(status == 2 and key in err, f"bad input for {key}: exit {status}, {err.strip()}")


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory(prefix="grainflow_bed_") as tmp:
        case = write_text(os.path.join(tmp, "bed.toml"), CASE)
        out = os.path.join(tmp, "bed")
        status, _, err = run(exe, "run", case, "-o", out, "--quiet")
        if not check(status == 0, f"run exited {status}: {err.strip()}"):
            return finish("test_bed_diagnostics")
        rows = read_csv(os.path.join(out, "timeseries.csv"))
        last = rows[-1]
        volume = N * math.pi / 6 * D**3 + math.pi / 6 * BIG**3
        check(int(last["ballistic_particles"]) == 0, f"{last['ballistic_particles']} grains in flight in a settled bed")
        h, nu = float(last["bed_height"]), float(last["bulk_solids_fraction"])
        check(abs(h * nu * LX * LZ / volume - 1) < 1e-9, f"H nu A = {h * nu * LX * LZ} vs sphere volume {volume}")
        check(0.45 < nu < 0.66, f"settled bulk solids fraction {nu} (height {h} m)")
        check(int(last["collisions"]) > 0 and float(last["cell_temperature"]) >= 0, "collision count / cell temperature")

        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        for key in ("bed_height", "bulk_solids_fraction", "cell_temperature", "collisions_per_particle",
                    "convection_speed", "density_peak_Y", "mass_holdup", "shaking_acceleration"):
            check(key in summary, f"summary.json lacks {key}")

        field = read_csv(os.path.join(out, "convection.csv"))
        columns, rows_y = round(LZ / D), math.ceil(0.05 / D - 1e-9)
        check(len(field) == columns * rows_y, f"{len(field)} field cells, expected {columns} x {rows_y}")
        # Samples at t = 0.3, 0.301, ..., 0.45: 151, each counting all N + 1 free particles once.
        visits = sum(int(c["visits"]) for c in field)
        check(visits == 151 * (N + 1), f"field visits {visits}, expected 151 x {N + 1}")
        check(not os.path.exists(os.path.join(out, "convection_phases.csv")), "phase fields written with phase_bins = 0")

        tracers = read_csv(os.path.join(out, "tracers.csv"))
        ids = {r["id"] for r in tracers}
        check(len(ids) == 1, f"tracer ids {ids}: expected the one large sphere")
        first, end = tracers[0], tracers[-1]
        check(abs(float(first["x"]) - LX / 2) < 1e-9 and abs(float(first["z"]) - LZ / 2) < 1e-9,
              f"large sphere starts at ({first['x']}, {first['z']}), placed at ({LX / 2}, {LZ / 2})")
        check(int(end["wall_contacts"]) >= 1 and int(end["coordination"]) >= 1,
              f"settled large sphere touches {end['wall_contacts']} walls, {end['coordination']} spheres")
        check(abs(float(end["y"]) - BIG / 2) < 0.01 * BIG, f"large sphere rests at y = {end['y']}, not on the floor")

        profiles = read_csv(os.path.join(out, "profiles.csv"))
        check(all(k in profiles[0] for k in ("solids_fraction_error", "temperature_error", "W_error")),
              "profiles.csv lacks error columns")

        bad_input(exe, tmp, ('axis = "z"', 'axis = "y"'), "", "field.axis")
        bad_input(exe, tmp, ("count = 1\n", "count = 2\n"), "", "position")
        bad_input(exe, tmp, ('species = ["large"]', 'species = ["huge"]'), "", "tracers.species")
        bad_input(exe, tmp, ("phase_bins = 0", "phase_bins = 8"), "", "field.phase_bins")
    return finish("test_bed_diagnostics")


if __name__ == "__main__":
    sys.exit(main())
