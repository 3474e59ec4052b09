#!/usr/bin/python3
"""The records a run leaves beside its results (docs/OUTPUTS.md): OUTDIR/resolved_case.toml, the
case with every default filled in and the --set overrides applied, and OUTDIR/run_log.json. A small
DEM run (particles from a file given by a relative path, so the resolved case must name it
absolutely) and a small event-driven run, each with --set overrides; `grainflow run` on the
resolved case, from another working folder, must give a byte-identical final_state.csv.

Usage: /usr/bin/python3 tests/integration/test_run_records.py PATH_TO_grainflow  (from the repo root)
"""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, elastic_gas_case, executable_from_argv, finish, run, write_text  # noqa: E402

DEM_CASE = """[engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.015, 0.05, 0.015]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = 30

[particles]
init = "random"
expansion_time = 0.005
initial_temperature = 0.05
seed = 9

[contact]
k1 = 1.0e6
restitution = 0.9

[walls.ylo]
friction = 0.2

[run]
duration = 0.01

[output]
interval = 0.005
"""

# The same bed started from the first run's final state, read through a relative particles.file.
DEM_FROM_FILE = DEM_CASE.replace("count = 30", "").replace('init = "random"', 'init = "file"\nfile = "state/start.csv"')

RUN_LOG_KEYS = ("version", "git_commit", "hostname", "cpu_model", "cpu_cores", "threads", "command_line",
                "start_time", "end_time", "exit_status")


def check_records(exe, label, case, out, overrides, threads):
    """Runs `case` with the overrides, checks run_log.json, reruns resolved_case.toml elsewhere and
    compares final_state.csv byte for byte."""
    args = ["run", case, "-o", out, "--quiet", "--threads", str(threads)]
    for assignment in overrides:
        args += ["--set", assignment]
    status, _, err = run(exe, *args)
    if not check(status == 0, f"{label}: run exited {status}: {err.strip()}"):
        return
    resolved = os.path.join(out, "resolved_case.toml")
    if not check(os.path.isfile(resolved), f"{label}: no resolved_case.toml"):
        return
    with open(resolved) as f:
        text = f.read()
    for assignment in overrides:
        key, value = assignment.split("=", 1)
        check(f"{key.split('.')[-1]} = {value}" in text, f"{label}: resolved_case.toml lacks the override {assignment}")
    with open(os.path.join(out, "run_log.json")) as f:
        log = json.load(f)
    for key in RUN_LOG_KEYS:
        check(key in log, f"{label}: run_log.json has no '{key}'")
    check(log.get("threads") == threads, f"{label}: run_log threads = {log.get('threads')}")
    check(log.get("command_line", [])[1:] == args, f"{label}: run_log command_line = {log.get('command_line')}")
    check(log.get("exit_status") == 0, f"{label}: run_log exit_status = {log.get('exit_status')}")
    check(log.get("start_time", "") <= log.get("end_time", ""), f"{label}: start {log.get('start_time')} after end {log.get('end_time')}")
    with open(os.path.join(out, "summary.json")) as f:
        check("errors" in json.load(f), f"{label}: summary.json lost its keys")

    # From another working folder: no path in the resolved case may depend on where it was run.
    again = out + "_again"
    status, _, err = run(exe, "run", os.path.abspath(resolved), "-o", again, "--quiet", "--threads", str(threads),
                         cwd=os.path.dirname(os.path.dirname(out)))
    if not check(status == 0, f"{label}: rerun of resolved_case.toml exited {status}: {err.strip()}"):
        return
    with open(os.path.join(out, "final_state.csv"), "rb") as a, open(os.path.join(again, "final_state.csv"), "rb") as b:
        check(a.read() == b.read(), f"{label}: final_state.csv of the resolved case differs from the original run's")
    with open(os.path.join(again, "resolved_case.toml")) as f:
        second = f.read()
    # The resolved case resolves to itself, but for its header comment (which names the case file).
    body = lambda t: [line for line in t.splitlines() if not line.startswith("#")]  # noqa: E731
    check(body(second) == body(text), f"{label}: resolving resolved_case.toml again changes it")


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory(prefix="grainflow_records_") as tmp:
        work = os.path.join(tmp, "work")
        os.makedirs(os.path.join(work, "state"))
        case = write_text(os.path.join(work, "dem.toml"), DEM_CASE)
        check_records(exe, "dem", case, os.path.join(tmp, "runs", "dem"), ["contact.restitution=0.8", "particles.seed=3"], 2)

        # init = "file" through a relative path: the resolved case must still find the file.
        os.replace(os.path.join(tmp, "runs", "dem", "final_state.csv"), os.path.join(work, "state", "start.csv"))
        case = write_text(os.path.join(work, "dem_file.toml"), DEM_FROM_FILE)
        check_records(exe, "dem from file", os.path.relpath(case), os.path.join(tmp, "runs", "dem_file"), ["run.duration=0.005"], 1)

        text, _ = elastic_gas_case(2, 6, 0.3, 2.0, "interval = 0.5\n")
        case = write_text(os.path.join(work, "edmd.toml"), text)
        check_records(exe, "edmd", case, os.path.join(tmp, "runs", "edmd"),
                      ["collision.restitution=0.9", "particles.lattice_jitter=0.25"], 1)
    return finish("test_run_records")


if __name__ == "__main__":
    sys.exit(main())
