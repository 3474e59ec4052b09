#!/usr/bin/python3
"""Smoke test of every bundled Campbell 1982 case (cases/campbell1982/*.toml): each passes `grainflow check`,
runs 20 time units (--set run.duration, averages from 10) to exit status 0 with summary.json, timeseries.csv and
profiles.csv (and trajectory.h5 where the case has a [trajectory] table), and every sweep command written in a
case's header runs with the same short duration, one folder per value. A sweep's own --vary of run.duration or
output.average_start is dropped so that it stays short. The full-length runs are tools/run_campbell1982.sh.

Usage: /usr/bin/python3 tests/integration/test_campbell1982_cases.py PATH_TO_grainflow  (from the repo root)
"""
import glob
import os
import shlex
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, run, sweep_commands  # noqa: E402

# 20 time units: a few hundred collisions in the 2D cells, enough to exercise walls, servo and averaging
# (from t = 10), a few seconds in all.
SHORT = ["--set", "run.duration=20.0", "--set", "output.average_start=10.0"]
LENGTH_KEYS = ("run.duration=", "output.average_start=")


def short_sweep_args(command):
    """The sweep's arguments after `grainflow sweep`, without -o and without --vary of the run length."""
    args = shlex.split(command)[2:]
    kept = []
    i = 0
    while i < len(args):
        if args[i] == "-o":
            i += 2
            continue
        if args[i] == "--vary" and args[i + 1].startswith(LENGTH_KEYS):
            i += 2
            continue
        kept.append(args[i])
        i += 1
    return kept


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    cases = sorted(glob.glob("cases/campbell1982/*.toml"))
    check(len(cases) >= 16, f"only {len(cases)} Campbell 1982 cases found")
    with tempfile.TemporaryDirectory(prefix="grainflow_campbell_") as tmp:
        for case in cases:
            name = os.path.splitext(os.path.basename(case))[0]
            status, _, err = run(exe, "check", case)
            check(status == 0, f"check {case}: exit {status}: {err.strip()}")
            out = os.path.join(tmp, name)
            status, _, err = run(exe, "run", case, "-o", out, "--quiet", *SHORT)
            if not check(status == 0, f"run {case}: exit {status}: {err.strip()}"):
                continue
            expected = ["summary.json", "timeseries.csv", "profiles.csv"]
            with open(case) as handle:
                expected += ["trajectory.h5"] if "[trajectory]" in handle.read() else []
            for file in expected:
                check(os.path.exists(os.path.join(out, file)), f"{case}: no {file}")
            for number, command in enumerate(sweep_commands(case)):
                folder = os.path.join(tmp, f"{name}_sweep{number}")
                args = short_sweep_args(command)
                status, _, err = run(exe, "sweep", *args, "-o", folder, "--quiet", *SHORT)
                check(status == 0 and os.path.exists(os.path.join(folder, "sweep.csv")),
                      f"{case}: sweep `{command}` exit {status}: {err.strip()[-400:]}")
                run_dirs = glob.glob(os.path.join(folder, "*", ""))
                check(len(run_dirs) >= 2, f"{case}: sweep `{command}` made {len(run_dirs)} run folders")
                for run_dir in run_dirs:
                    check(os.path.exists(os.path.join(run_dir, "profiles.csv")), f"{run_dir}: no profiles.csv")
    return finish("test_campbell1982_cases")


if __name__ == "__main__":
    sys.exit(main())
