#!/usr/bin/python3
"""Every bundled Lan 1994 case (cases/lan1994/*.toml): each passes `grainflow check`, runs a few
milliseconds of simulated time (--set run.duration) to exit status 0 with its outputs (summary.json,
timeseries.csv, profiles.csv, and the field / tracer / sampled files its tables ask for); its
summary carries Lan's closed forms computed here from the case file (the time step of eq. 2-5-4,
the step count, m_t of eq. 4-1-3 and Gamma = a omega^2 / g) and the golden scalars of
tests/regression/seed_goldens.json within their tolerances; and every sweep command written in a
case's header runs with the same short duration, one folder per value. The full runs and their wall
times are in docs/validation/lan1994.md.

Usage: /usr/bin/python3 tests/integration/test_lan1994_cases.py PATH_TO_grainflow  (from the repo root)
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
    """Lan's closed forms from the case file: eq. (2-5-4) dt = (pi e / n) sqrt(m / (2 K1)) for the
    lightest moving sphere, steps = round(duration / dt), m_t = N pi d^3 / 6 / (A d) (eq. 4-1-3), and
    Gamma = a omega^2 / g along gravity. Relative 1e-9: the same arithmetic, in another order."""
    with open(case, "rb") as f:
        c = tomllib.load(f)
    species = [s for s in c["species"] if not s.get("frozen", False)]
    mass = lambda s: s["density"] * math.pi / 6.0 * s["diameter"] ** 3  # noqa: E731
    reference = min(species, key=mass)
    contact, run_table = c.get("contact", {}), c.get("run", {})
    if contact.get("model", "walton_braun") == "walton_braun" and "time_step" not in run_table:
        e, n = contact.get("restitution", 0.9), run_table.get("collision_steps", 15)
        dt = math.pi * e / n * math.sqrt(mass(reference) / (2.0 * contact["k1"]))
        check(math.isclose(summary["time_step"], dt, rel_tol=1e-9), f"{case}: time_step {summary['time_step']} != eq. 2-5-4 {dt}")
        check(summary["steps"] == round(0.003 / dt), f"{case}: steps {summary['steps']} != round(duration / dt)")
    gravity = c.get("gravity", {}).get("vector", [0.0, -9.81, 0.0])
    axis = max(range(3), key=lambda a: abs(gravity[a]))
    lengths = [hi - lo for lo, hi in zip(c["domain"]["lo"], c["domain"]["hi"])]
    area = math.prod(lengths[a] for a in range(3) if a != axis)
    solids = sum(s.get("count", 0) * math.pi / 6.0 * s["diameter"] ** 3 for s in species)
    holdup = solids / (area * reference["diameter"])
    if all("count" in s for s in species):
        check(math.isclose(summary["mass_holdup"], holdup, rel_tol=1e-9), f"{case}: mass_holdup {summary['mass_holdup']} != {holdup}")
    drive = c.get("drive")
    if drive and "amplitude" in drive and "frequency" in drive:
        g = math.sqrt(sum(x * x for x in gravity))
        gamma = drive["amplitude"][axis] * (2.0 * math.pi * drive["frequency"][axis]) ** 2 / g
        check(math.isclose(summary["shaking_acceleration"], gamma, rel_tol=1e-9),
              f"{case}: shaking_acceleration {summary['shaking_acceleration']} != a omega^2 / g = {gamma}")

SHORT = "run.duration=0.003"  # >= 70 steps of the largest time step among the cases (4.2e-5 s)


def shortened(args):
    """A header sweep's arguments made short: without its --vary of run.duration, if any (a key may
    not be both varied and set; Table 4.6's sweep varies it for 400 cycles), and with --set SHORT.
    As test_campbell1982_cases.py does for its run lengths."""
    kept = []
    i = 0
    while i < len(args):
        if args[i] == "--vary" and i + 1 < len(args) and args[i + 1].startswith("run.duration="):
            i += 2
            continue
        kept.append(args[i])
        i += 1
    return kept + ["--set", SHORT]


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    cases = sorted(glob.glob("cases/lan1994/*.toml"))
    check(len(cases) >= 14, f"only {len(cases)} Lan 1994 cases found")
    goldens = 0
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
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
            check_closed_forms(case, summary)
            goldens += golden_run(exe, case, out, ["--set", SHORT], summary)
            for number, command in enumerate(sweep_commands(case)):
                args = shlex.split(command)[2:]  # after "grainflow sweep"
                if "-o" in args:
                    i = args.index("-o")
                    del args[i : i + 2]
                folder = os.path.join(tmp, f"{name}_sweep{number}")
                status, _, err = run(exe, "sweep", *shortened(args), "-o", folder, "--quiet")
                check(status == 0 and os.path.exists(os.path.join(folder, "sweep.csv")),
                      f"{case}: sweep `{command}` exit {status}: {err.strip()[-400:]}")
    check(goldens >= 4 * len(cases), f"only {goldens} golden values compared")
    return finish("test_lan1994_cases")


if __name__ == "__main__":
    sys.exit(main())
