#!/usr/bin/python3
"""Smoke test of every bundled Lan 1994 case (cases/lan1994/*.toml): each passes `grainflow check`,
runs a few milliseconds of simulated time (--set run.duration) to exit status 0 with its outputs
(summary.json, timeseries.csv, profiles.csv, and the field / tracer / sampled files its tables ask
for), and every sweep command written in a case's header runs with the same short duration, one
folder per value. The full runs and their wall times are in docs/validation/lan1994.md.

Usage: /usr/bin/python3 tests/integration/test_lan1994_cases.py PATH_TO_grainflow  (from the repo root)
"""
import glob
import os
import shlex
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, run, sweep_commands  # noqa: E402

SHORT = "run.duration=0.003"  # >= 70 steps of the largest time step among the cases (4.2e-5 s)


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    cases = sorted(glob.glob("cases/lan1994/*.toml"))
    check(len(cases) >= 14, f"only {len(cases)} Lan 1994 cases found")
    with tempfile.TemporaryDirectory(prefix="grainflow_lan_") as tmp:
        for case in cases:
            name = os.path.splitext(os.path.basename(case))[0]
            status, _, err = run(exe, "check", case)
            check(status == 0, f"check {case}: exit {status}: {err.strip()}")
            out = os.path.join(tmp, name)
            status, _, err = run(exe, "run", case, "-o", out, "--quiet", "--set", SHORT)
            if not check(status == 0, f"run {case}: exit {status}: {err.strip()}"):
                continue
            expected = ["summary.json", "timeseries.csv", "profiles.csv"]
            with open(case) as handle:
                text = handle.read()
            expected += ["convection.csv"] if "[field]" in text else []
            expected += ["tracers.csv"] if "[tracers]" in text else []
            expected += ["trajectory.h5"] if "[trajectory]" in text else []
            expected += ["zone_series.h5"] if "[zone_series]" in text else []
            for file in expected:
                check(os.path.exists(os.path.join(out, file)), f"{case}: no {file}")
            for number, command in enumerate(sweep_commands(case)):
                args = shlex.split(command)[2:]  # after "grainflow sweep"
                if "-o" in args:
                    i = args.index("-o")
                    del args[i : i + 2]
                folder = os.path.join(tmp, f"{name}_sweep{number}")
                status, _, err = run(exe, "sweep", *args, "-o", folder, "--quiet", "--set", SHORT)
                check(status == 0 and os.path.exists(os.path.join(folder, "sweep.csv")),
                      f"{case}: sweep `{command}` exit {status}: {err.strip()[-400:]}")
    return finish("test_lan1994_cases")


if __name__ == "__main__":
    sys.exit(main())
