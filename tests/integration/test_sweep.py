#!/usr/bin/python3
"""`grainflow sweep` (README "Command reference", docs/OUTPUTS.md "Sweeps"):

- Campbell's chute (shortened with --set) at collision.restitution = 0.5, 0.7 times
  walls.ylo.restitution = 0.8, 0.9, two at a time: exit 0, four run folders named after the
  values, each with a summary.json; sweep.csv with the key columns, run, status and the summaries'
  scalar fields, one row per run with status 0; sweep.json with the case, the keys and values and
  the command; one progress line per run. Each run is the run `grainflow run` makes with the same
  --set (identical collision counts and dissipated energy), and the four differ.
- --zip pairs the lists element by element, with an array value whose commas sit inside brackets.
- Invalid input exits 2 naming the file, the key and the value, and creates no output folder:
  restitution 1.5 in one combination, lists of unequal length with --zip, a malformed --vary.
- A run that fails at run time (a DEM bed halted by a tiny run.halt_overlap) makes the sweep exit
  1; its row has status 1, the others 0 and the sweep names it. Without -o the sweep goes to
  runs/<case stem>_sweep; --quiet leaves no progress lines.

Usage: /usr/bin/python3 tests/integration/test_sweep.py PATH_TO_grainflow  (from the repo root)
"""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

CHUTE = "cases/campbell1982/chute_30deg.toml"
SHORT = "run.duration=5"  # of the case's 500 time units: a few milliseconds a run
E_P = ["0.5", "0.7"]
E_W = ["0.8", "0.9"]

# 20 glass spheres on a floor, 0.02 s; with run.halt_overlap = 1e-9 the first contact halts it (exit 1).
DEM_BED = """[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.05, 0.02]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = 20

[particles]
init = "random"
expansion_time = 0.0
seed = 3

[contact]
k1 = 1.0e6
restitution = 0.9

[run]
duration = 0.02

[output]
interval = 0.005
"""


def name(*pairs):
    return "_".join(f"{key}={value}" for key, value in pairs)


def read_summary(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def check_product(exe, tmp):
    out = os.path.join(tmp, "product")
    status, _, err = run(exe, "sweep", CHUTE, "--set", SHORT, "--vary", "collision.restitution=" + ",".join(E_P),
                         "--vary", "walls.ylo.restitution=" + ",".join(E_W), "--jobs", "2", "-o", out)
    if not check(status == 0, f"product sweep: exited {status}: {err.strip()}"):
        return
    progress = [line for line in err.splitlines() if line.startswith("grainflow sweep: [")]
    check(len(progress) == 4, f"product sweep: {len(progress)} progress lines, expected 4:\n{err}")

    expected = [(p, w) for p in E_P for w in E_W]
    folders = [name(("collision.restitution", p), ("walls.ylo.restitution", w)) for p, w in expected]
    summaries = {}
    for folder in folders:
        path = os.path.join(out, folder)
        if check(os.path.isfile(os.path.join(path, "summary.json")), f"product sweep: no {folder}/summary.json"):
            summaries[folder] = read_summary(path)
            check(summaries[folder]["errors"] == [], f"product sweep: {folder}: errors {summaries[folder]['errors']}")
    check(len({(s["collisions"], s["dissipated_energy"]) for s in summaries.values()}) == len(summaries),
          "product sweep: two runs have the same collision count and dissipated energy")
    leftovers = [f for f in os.listdir(out) if ".tmp-" in f]
    check(not leftovers, f"product sweep: temporary files left: {leftovers}")

    rows = read_csv(os.path.join(out, "sweep.csv"))
    if not check(len(rows) == 4, f"sweep.csv: {len(rows)} rows, expected 4"):
        return
    header = list(rows[0].keys())
    check(header[:4] == ["collision.restitution", "walls.ylo.restitution", "run", "status"],
          f"sweep.csv: header starts {header[:4]}")
    for key in ("engine", "collisions", "dissipated_energy", "granular_temperature", "case"):
        check(key in header, f"sweep.csv: no column '{key}'")
    check("errors" not in header, "sweep.csv: the list 'errors' should be left out")
    for row, (p, w), folder in zip(rows, expected, folders):
        check((row["collision.restitution"], row["walls.ylo.restitution"], row["run"], row["status"]) == (p, w, folder, "0"),
              f"sweep.csv: row {row['run']}: expected {p}, {w}, {folder}, 0")
        if folder in summaries and "collisions" in row:
            check(int(row["collisions"]) == summaries[folder]["collisions"],
                  f"sweep.csv: {folder}: collisions {row['collisions']}, summary {summaries[folder]['collisions']}")
            check(row["engine"] == "edmd", f"sweep.csv: {folder}: engine {row['engine']!r}")

    with open(os.path.join(out, "sweep.json")) as f:
        plan = json.load(f)
    check(plan["case"] == CHUTE, f"sweep.json: case {plan['case']!r}")
    check(plan["vary"] == [{"key": "collision.restitution", "values": E_P}, {"key": "walls.ylo.restitution", "values": E_W}],
          f"sweep.json: vary {plan['vary']}")
    check(plan["command"][1:3] == ["sweep", CHUTE] and "--jobs" in plan["command"], f"sweep.json: command {plan['command']}")
    check([r["status"] for r in plan["runs"]] == [0] * 4 and [r["run"] for r in plan["runs"]] == folders,
          f"sweep.json: runs {plan['runs']}")

    # Two runs again by hand, with the same settings: the sweep's children ran exactly these.
    for p, w in (expected[1], expected[2]):
        single = os.path.join(tmp, f"single_{p}_{w}")
        status, _, err = run(exe, "run", CHUTE, "-o", single, "--quiet", "--set", SHORT,
                             "--set", f"collision.restitution={p}", "--set", f"walls.ylo.restitution={w}")
        folder = name(("collision.restitution", p), ("walls.ylo.restitution", w))
        if check(status == 0, f"single run {p}, {w}: exited {status}: {err.strip()}") and folder in summaries:
            direct = read_summary(single)
            for key in ("collisions", "wall_collisions", "events", "dissipated_energy", "kinetic_energy"):
                check(direct[key] == summaries[folder][key],
                      f"{folder}: {key} = {summaries[folder][key]} in the sweep, {direct[key]} in a plain run")


def check_zip(exe, tmp):
    out = os.path.join(tmp, "zip")
    velocities = ["[3.0, 0.0, 0.0]", "[2.5,0,0]"]
    status, _, err = run(exe, "sweep", CHUTE, "--zip", "--quiet", "--set", SHORT, "--vary", "collision.restitution=0.5, 0.7",
                         "--vary", "particles.initial_velocity=" + ",".join(velocities), "-o", out)
    if not check(status == 0, f"zip sweep: exited {status}: {err.strip()}"):
        return
    check(err.strip() == "", f"zip sweep: --quiet, yet stderr says: {err.strip()}")
    folders = sorted(f for f in os.listdir(out) if os.path.isdir(os.path.join(out, f)))
    expected = sorted(["collision.restitution=0.5_particles.initial_velocity=3.0_0.0_0.0",
                       "collision.restitution=0.7_particles.initial_velocity=2.5_0_0"])
    check(folders == expected, f"zip sweep: folders {folders}, expected {expected}")
    rows = read_csv(os.path.join(out, "sweep.csv"))
    pairs = [(r["collision.restitution"], r["particles.initial_velocity"], r["status"]) for r in rows]
    check(pairs == [("0.5", velocities[0], "0"), ("0.7", velocities[1], "0")], f"zip sweep: sweep.csv rows {pairs}")


def check_invalid(exe, tmp):
    out = os.path.join(tmp, "invalid")
    status, _, err = run(exe, "sweep", CHUTE, "--set", SHORT, "--vary", "collision.restitution=0.5,1.5",
                         "--vary", "walls.ylo.restitution=0.8", "-o", out)
    check(status == 2, f"restitution 1.5: exited {status}, expected 2")
    check(CHUTE in err and "'collision.restitution'" in err and "collision.restitution=1.5" in err,
          f"restitution 1.5: the message should name the file, the key and the value: {err.strip()}")
    check("collision.restitution=0.5 " not in err, f"restitution 1.5: a valid combination was reported: {err.strip()}")
    check(not os.path.exists(out), "restitution 1.5: the output folder was created")

    status, _, err = run(exe, "sweep", CHUTE, "--zip", "--vary", "collision.restitution=0.5,0.6",
                         "--vary", "walls.ylo.restitution=0.8,0.9,1.0", "-o", out)
    check(status == 2 and "equal length" in err, f"zip of unequal lists: exited {status}: {err.strip()}")
    check(not os.path.exists(out), "zip of unequal lists: the output folder was created")

    status, _, err = run(exe, "sweep", CHUTE, "--vary", "particles.initial_velocity=[1,0,0],[2,0", "-o", out)
    check(status == 2 and "particles.initial_velocity" in err, f"malformed --vary: exited {status}: {err.strip()}")
    check(not os.path.exists(out), "malformed --vary: the output folder was created")


def check_failed_run(exe, tmp):
    case = write_text(os.path.join(tmp, "bed.toml"), DEM_BED)
    status, _, err = run(exe, "sweep", case, "--vary", "run.halt_overlap=0,1e-9", "--jobs", "2", "--quiet", cwd=tmp)
    check(status == 1, f"halted run: sweep exited {status}, expected 1: {err.strip()}")
    failed = "run.halt_overlap=1e-9"
    check(failed in err and "exit 1" in err, f"halted run: the sweep should name the failed run: {err.strip()}")
    check("[1/2]" not in err, f"halted run: --quiet, yet progress lines: {err.strip()}")
    out = os.path.join(tmp, "runs", "bed_sweep")  # the default output folder
    if not check(os.path.isfile(os.path.join(out, "sweep.csv")), f"halted run: no {out}/sweep.csv"):
        return
    rows = read_csv(os.path.join(out, "sweep.csv"))
    statuses = {row["run"]: row["status"] for row in rows}
    check(statuses == {"run.halt_overlap=0": "0", failed: "1"}, f"halted run: statuses {statuses}")
    for row in rows:
        check(row.get("engine") == "dem", f"halted run: {row['run']}: engine {row.get('engine')!r}")
    check(os.path.isfile(os.path.join(out, failed, "run.log")), "halted run: no run.log with the failure")


def main():
    exe = executable_from_argv("usage: test_sweep.py PATH_TO_grainflow")
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        check_product(exe, tmp)
        check_zip(exe, tmp)
        check_invalid(exe, tmp)
        check_failed_run(exe, tmp)
    return finish("test_sweep")


if __name__ == "__main__":
    sys.exit(main())
