#!/usr/bin/python3
"""Every bundled Campbell 1982 case (cases/campbell1982/*.toml): each passes `grainflow check`, runs 20 time
units (--set run.duration, averages from 10) to exit status 0 with summary.json, timeseries.csv and profiles.csv
(and trajectory.h5 where the case has a [trajectory] table); its packing fraction is the particles' area (2D) or
volume (3D) over the cell's, computed here from the case; its dissipated energy (each collision's loss in its own
rest frame) is not negative, and zero with elastic smooth particles, to rounding; its golden scalars (tests/regression/seed_goldens.json) hold within their
tolerances; and every sweep command written in a case's header runs with the same short duration, one folder per
value. A sweep's own --vary of run.duration or
output.average_start is dropped so that it stays short. The full-length runs are tools/run_campbell1982.sh.

Usage: /usr/bin/python3 tests/integration/test_campbell1982_cases.py PATH_TO_grainflow  (from the repo root)
"""
import glob
import json
import math
import os
import shlex
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, golden_run, run, sweep_commands  # noqa: E402

import tomllib  # noqa: E402


def check_closed_forms(case, summary):
    """The packing fraction N pi r^2 / A (2D) or N (4/3) pi r^3 / V (3D) of the case's cell (a servo-driven
    Couette cell's walls move: its measure is the summary's wall_gap x cell_width); dissipation >= 0, and
    0 when every collision is elastic and smooth, to rounding."""
    with open(case, "rb") as f:
        c = tomllib.load(f)
    dim = c.get("engine", {}).get("dimension", 3)
    lengths = [hi - lo for lo, hi in zip(c["domain"]["lo"], c["domain"]["hi"])]
    measure = math.prod(lengths[:dim])
    if "servo" in c:
        measure = summary["wall_gap"] * summary["cell_width"] * (lengths[2] if dim == 3 else 1.0)
    if all("count" in s for s in c["species"]):
        r = lambda s: 0.5 * s["diameter"]  # noqa: E731
        solids = sum(s["count"] * (math.pi * r(s) ** 2 if dim == 2 else 4.0 / 3.0 * math.pi * r(s) ** 3) for s in c["species"])
        check(math.isclose(summary["packing_fraction"], solids / measure, rel_tol=1e-9),
              f"{case}: packing_fraction {summary['packing_fraction']} != {solids / measure}")
    # Each collision's loss carries rounding of ~1e-16 of the energies involved: 1e-9 of the energy scale.
    rounding = 1e-9 * (summary["kinetic_energy"] + abs(summary["dissipated_energy"]))
    check(summary["dissipated_energy"] >= -rounding, f"{case}: dissipated_energy {summary['dissipated_energy']} < 0")
    collision = c.get("collision", {})
    walls = c.get("walls", {})
    elastic = (collision.get("restitution", 1.0) == 1.0 and collision.get("restitution_law", "constant") == "constant"
               and collision.get("tangential_restitution", -1.0) == -1.0 and collision.get("roughness", "smooth") == "smooth"
               and collision.get("wall_restitution", collision.get("restitution", 1.0)) == 1.0
               and all(w.get("restitution", 1.0) == 1.0 and w.get("condition", "smooth") == "smooth" for w in walls.values()))
    if elastic:
        check(abs(summary["dissipated_energy"]) <= rounding,
              f"{case}: elastic smooth collisions dissipated {summary['dissipated_energy']}")

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
    goldens = 0
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
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
            check_closed_forms(case, summary)
            goldens += golden_run(exe, case, out, SHORT, summary)
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
    check(goldens >= 6 * len(cases), f"only {goldens} golden values compared")
    return finish("test_campbell1982_cases")


if __name__ == "__main__":
    sys.exit(main())
