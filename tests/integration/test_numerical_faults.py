#!/usr/bin/python3
"""Numerical faults at run time (ROBUSTNESS.md): a run that goes wrong stops with exit
status 1 and a message naming the particle(s), the simulated time and the likely cause, and every
output written so far is valid (summary.json with the message in `errors`, timeseries.csv,
final_state.csv). One tiny case per fault, each well under a second:

- DEM, a particle through a wall: one sphere at 20 m/s into a floor with k1 = 100 N/m (it would
  penetrate v sqrt(m/k1) = 12 mm, four radii).
- DEM, run.halt_overlap: two spheres meeting head-on at 4 m/s with k1 = 1e4 N/m (overlap ~5% of d).
- EDMD, inelastic collapse: 64 discs at packing fraction 0.6 cooling with e = 0.1 and no TC model
  (collision.contact_duration = 0) collapse at t ~ 0.8.
- EDMD, Zeno bounces on a wall: a column of discs on a floor under gravity with no TC model and
  collision.rolling_speed = 0.

A non-finite DEM or EDMD state cannot be reached from a valid case file (inputs are checked to be
finite, and the time step to resolve a contact); those are covered by tests/unit/test_fault_checks.cpp,
which drives the runs with a state the loader would refuse.

Usage: /usr/bin/python3 tests/integration/test_numerical_faults.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, elastic_gas_case, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

DEM_ONE_WALL = """[engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.012, 0.02, 0.012]
boundary = {{ x = "periodic", y = {y}, z = "periodic" }}

[gravity]
vector = [0.0, 0.0, 0.0]

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0

[particles]
init = "file"
file = "particles.csv"

[contact]
k1 = {k1}
restitution = 0.9

[run]
duration = {duration}
{run_extra}

[output]
interval = {interval}
"""

EDMD_COLUMN = """[engine]
kind = "edmd"
dimension = 2

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.05, 0.01]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[gravity]
vector = [0.0, -9.81, 0.0]

[[species]]
name = "disc"
diameter = 0.002
density = 2.0

[particles]
init = "file"
file = "particles.csv"

[collision]
restitution = 0.3
contact_duration = 0.0
rolling_speed = 0.0

[run]
duration = 2.0

[output]
interval = 0.01
"""

NUMBER = r"[-+]?[0-9.]+(?:e[-+]?[0-9]+)?"


def run_fault(exe, tmp, name, case, particles):
    """Runs `case` (with `particles` as particles.csv when given) in its own folder; checks exit
    status 1, the message in summary.json's errors and on stderr, and that the outputs parse.
    Returns the message ('' on failure)."""
    folder = os.path.join(tmp, name)
    os.makedirs(folder)
    write_text(os.path.join(folder, "case.toml"), case)
    if particles:
        write_text(os.path.join(folder, "particles.csv"), particles)
    status, _, err = run(exe, "run", "case.toml", "-o", "out", "--quiet", cwd=folder)
    check(status == 1, f"{name}: exit status {status}, expected 1; stderr: {err.strip()[:300]}")
    out = os.path.join(folder, "out")
    try:
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        errors = summary.get("errors", [])
        check(len(errors) == 1, f"{name}: summary.json errors = {errors}")
        timeseries = read_csv(os.path.join(out, "timeseries.csv"))
        final = read_csv(os.path.join(out, "final_state.csv"))
        check(len(timeseries) >= 1 and all(math.isfinite(float(r["time"])) for r in timeseries),
              f"{name}: timeseries.csv has no valid rows")
        check(len(final) >= 1 and all(r["id"] != "" for r in final), f"{name}: final_state.csv is empty")
    except (OSError, ValueError, KeyError) as error:
        check(False, f"{name}: outputs missing or unreadable: {error}")
        return ""
    message = errors[0] if errors else ""
    check(message in err, f"{name}: the message is not repeated on stderr: {err.strip()[:300]}")
    return message


def expect(name, message, pattern, what):
    found = re.search(pattern, message)
    check(found is not None, f"{name}: message lacks {what} ({pattern!r}): {message}")
    return found


def main():
    exe = executable_from_argv("usage: test_numerical_faults.py PATH_TO_grainflow")
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        # DEM: one sphere at 20 m/s into a floor with k1 = 100 N/m.
        name = "dem_wall_escape"
        case = DEM_ONE_WALL.format(y='["wall", "open"]', k1=100.0, duration=0.004, run_extra="", interval=0.0001)
        message = run_fault(exe, tmp, name, case, "species,x,y,z,vx,vy,vz\nglass,0.006,0.004,0.006,0,-20,0\n"
                                                  "glass,0.002,0.01,0.002,0,0,0\n")
        expect(name, message, r"particle 0 at \(", "the particle")
        expect(name, message, r"ylo wall", "the face")
        expect(name, message, rf"at t = {NUMBER} s", "the time")
        expect(name, message, r"too soft a wall or too large a time step", "the cause")
        expect(name, message, rf"k1 = 100 N/m", "the stiffness")
        expect(name, message, rf"needs k1 >= {NUMBER} N/m", "the stiffness needed")

        # DEM: two spheres head-on at 2 m/s each, k1 = 1e4 N/m, halted at 1% of d.
        name = "dem_halt_overlap"
        case = DEM_ONE_WALL.format(y='"periodic"', k1=1.0e4, duration=0.002, run_extra="halt_overlap = 0.01",
                                   interval=0.00002)
        message = run_fault(exe, tmp, name, case, "species,x,y,z,vx,vy,vz\nglass,0.003,0.01,0.006,2,0,0\n"
                                                  "glass,0.008,0.01,0.006,-2,0,0\nglass,0.003,0.004,0.003,0,0,0\n")
        expect(name, message, r"exceeded run.halt_overlap = 0.01", "the bound")
        expect(name, message, r"between particles 0 and 1", "the pair")
        expect(name, message, rf"before t = {NUMBER} s", "the time")
        found = expect(name, message, rf"1 % criterion .* suggests k1 >= ({NUMBER}) N/m", "the suggested k1")
        if found:
            check(float(found.group(1)) > 1.0e4, f"{name}: suggested k1 {found.group(1)} is not above k1")

        # EDMD: 64 discs cooling with e = 0.1 and no TC model collapse.
        name = "edmd_inelastic_collapse"
        case, _ = elastic_gas_case(2, 8, 0.6, 50.0, "interval = 1.0")
        case = case.replace("restitution = 1.0", "restitution = 0.1\ncontact_duration = 0.0")
        message = run_fault(exe, tmp, name, case, None)
        expect(name, message, rf"simulated time stopped advancing at t = {NUMBER} s", "the time")
        expect(name, message, r"collision between particles [0-9]+ and [0-9]+", "the last pair")
        expect(name, message, r"particle\(s\) collided within those events \([0-9]+, [0-9]+", "the colliding particles")
        expect(name, message, r"inelastic collapse", "the cause")
        expect(name, message, r"collision.contact_duration \(now 0 s\)", "the TC model's key")
        expect(name, message, r'collision.restitution_law = "campbell"', "the velocity-dependent restitution")

        # EDMD: discs on a floor bouncing ever faster (Zeno) with no TC model and no rolling.
        name = "edmd_wall_zeno"
        column = "species,x,y,z,vx,vy,vz\n" + "".join(f"disc,0.01,{0.0015 + 0.003 * k},0.005,0,0,0\n" for k in range(4))
        message = run_fault(exe, tmp, name, EDMD_COLUMN, column)
        expect(name, message, rf"stopped advancing at t = {NUMBER} s", "the time")
        expect(name, message, r"particle [0-9]+ hitting the ylo wall", "the particle and wall")
        expect(name, message, r"collision.rolling_speed \(now 0 m/s\)", "the rolling key")
    return finish("test_numerical_faults")


if __name__ == "__main__":
    sys.exit(main())
