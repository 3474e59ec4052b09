"""Helpers shared by the integration scripts in this folder (test_*.py): the list of failed checks,
check(), running the grainflow executable, writing a case and reading the CSV files of an output
folder. Each script imports this module by putting its own folder on sys.path, so
`/usr/bin/python3 tests/integration/test_X.py PATH_TO_grainflow` works from the repo root.
"""
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys

FAILURES = []


def check(condition, message):
    """Records and prints a failed check; returns the condition so callers can stop on a failure."""
    if not condition:
        FAILURES.append(message)
        print("FAIL: " + message, file=sys.stderr)
    return condition


def executable_from_argv(usage):
    """The absolute path of grainflow, the one argument; None (after printing `usage`) otherwise."""
    if len(sys.argv) != 2:
        print(usage, file=sys.stderr)
        return None
    return os.path.abspath(sys.argv[1])


def run(exe, *args, cwd=None):
    """Runs grainflow with `args`; returns (exit status, stdout, stderr)."""
    result = subprocess.run([exe, *args], capture_output=True, text=True, cwd=cwd)
    return result.returncode, result.stdout, result.stderr


def mpi_environment():
    """The environment for mpirun here: as root Open MPI needs its two OMPI_ALLOW_RUN_AS_ROOT
    variables, and containers refuse cross-memory attach (shared memory is still used)."""
    env = dict(os.environ)
    env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                "OMPI_MCA_btl_vader_single_copy_mechanism": "none"})
    return env


def mpirun_found():
    """True when mpirun is on PATH; a failed check otherwise."""
    return check(shutil.which("mpirun") is not None, "mpirun not found (tools/install_deps.sh installs openmpi-bin)")


def write_text(path, text):
    """Writes `text` (a case file) to `path` and returns the path."""
    with open(path, "w") as f:
        f.write(text)
    return path


def read_csv(path):
    """The rows of an output CSV file as dicts, its '#' comment lines skipped."""
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def sweep_commands(path):
    """The `grainflow sweep ...` commands written in a case's header comment."""
    commands = []
    with open(path) as handle:
        for line in handle:
            if not line.startswith("#"):
                break
            found = re.search(r"grainflow sweep .*", line)
            if found:
                commands.append(found.group(0).strip())
    return commands


def finish(name):
    """The exit status of a script: 1 after any failed check, else 0 with a line saying all passed."""
    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed", file=sys.stderr)
        return 1
    print(f"{name}: all checks passed")
    return 0


ELASTIC_GAS = """[engine]
kind = "edmd"
dimension = {dim}

[domain]
lo = [0.0, 0.0, 0.0]
hi = [{L!r}, {L!r}, {Lz!r}]
boundary = {{ x = "periodic", y = "periodic", z = "periodic" }}

[gravity]
vector = [0.0, 0.0, 0.0]

[[species]]
name = "p"
diameter = 1.0
density = {density!r}   # unit mass
count = {N}

[particles]
init = "lattice"
lattice_spacing = {spacing!r}
initial_temperature = 1.0
seed = {seed}

[collision]
restitution = 1.0

[run]
duration = {duration}

[output]
{output}
"""


def elastic_gas_case(dim, side, phi, duration, output, seed=21):
    """The case text of side^dim elastic smooth particles (discs in 2D, spheres in 3D) of diameter 1
    and unit mass on a square / simple-cubic lattice at packing fraction phi, T = 1, periodic on
    every axis, no gravity; `output` is the [output] table's body. Returns (text, box edge)."""
    volume = math.pi / 4 if dim == 2 else math.pi / 6
    spacing = (volume / phi) ** (1.0 / dim)
    length = side * spacing
    text = ELASTIC_GAS.format(dim=dim, L=length, Lz=length if dim == 3 else 1.0, density=1.0 / volume, N=side ** dim,
                              spacing=spacing * (1 - 1e-9), seed=seed, duration=duration, output=output)
    return text, length


PERIODIC_GAS = """[engine]
kind = "{engine}"
dimension = {dimension}
[domain]
lo = [0.0, 0.0, 0.0]
hi = [{box!r}, {box!r}, {depth!r}]
boundary = {{ x = "periodic", y = "periodic", z = "periodic" }}
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "particle"
diameter = 1.0
density = {density!r}
count = {count}
[particles]
init = "lattice"
initial_temperature = 1.0
seed = 4
{law}
{extra}
[run]
duration = {duration!r}
{steps}
[output]
interval = {interval!r}
average_start = {start!r}
profile_interval = {profile_interval!r}
{zones}
{stresses}
"""


def periodic_gas_case(engine, dimension, count, box, depth, density, law, duration, start, interval,
                      profile_interval, zone_thickness=None, extra="", steps=""):
    """A gas of unit-diameter particles on a lattice at temperature 1 in a periodic box without
    gravity, `law` being its [contact] or [collision] table and `extra` any further tables; strips
    `zone_thickness` thick along y when given, and the engine's stresses switched on."""
    stresses = "stresses = true" if engine == "dem" else "collision_stresses = true"
    zones = f"zone_thickness = {zone_thickness!r}" if zone_thickness is not None else ""
    return PERIODIC_GAS.format(engine=engine, dimension=dimension, count=count, box=box, depth=depth,
                               density=density, law=law, extra=extra, duration=duration, steps=steps,
                               interval=interval, start=start, profile_interval=profile_interval,
                               zones=zones, stresses=stresses)


def run_case_text(exe, folder, name, text):
    """Writes `text` to folder/name.toml and runs it into folder/name; that output folder, or None
    after a failed check when the run failed."""
    case = write_text(os.path.join(folder, f"{name}.toml"), text)
    out = os.path.join(folder, name)
    status, _, err = run(exe, "run", case, "-o", out, "--quiet")
    if not check(status == 0, f"{name}: exited {status}: {err.strip()}"):
        return None
    return out


GOLDENS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "regression", "seed_goldens.json")


def golden_entry(case):
    """The golden scalars of a bundled seed case (tests/regression/seed_goldens.json): the run's
    arguments ("args") and the values with their tolerances ("values"; how they were set is the
    file's "why"), or None after a failed check."""
    with open(GOLDENS) as f:
        entry = json.load(f)["cases"].get(case)
    check(entry is not None, f"{case}: no golden values in {GOLDENS} (make_seed_goldens.py writes them)")
    return entry


def check_goldens(case, entry, summary):
    """Compares a run's summary, made with entry["args"], with the golden values; returns how many."""
    for key, golden in entry["values"].items():
        value, expected, tolerance = summary.get(key), golden["value"], golden["relative_tolerance"]
        if not check(value is not None, f"{case}: summary.json has no {key}"):
            continue
        check(abs(value - expected) <= tolerance * abs(expected),
              f"{case}: {key} = {value!r}, golden {expected!r} (relative tolerance {tolerance:.1e}, run with "
              f"{' '.join(entry['args'])}); a change of the physics? see tests/regression/make_seed_goldens.py")
    return len(entry["values"])


def golden_run(exe, case, out, short_args, summary):
    """Checks the case's golden values: against `summary` when the goldens were made with the test's
    own `short_args`, else after a run of the goldens' shorter arguments into `out`_golden."""
    entry = golden_entry(case)
    if entry is None:
        return 0
    if entry["args"] != list(short_args):
        status, _, err = run(exe, "run", case, "-o", out + "_golden", "--quiet", *entry["args"])
        if not check(status == 0, f"golden run of {case}: exit {status}: {err.strip()}"):
            return 0
        with open(os.path.join(out + "_golden", "summary.json")) as f:
            summary = json.load(f)
    return check_goldens(case, entry, summary)
