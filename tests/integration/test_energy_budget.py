#!/usr/bin/python3
"""The energy budget end to end (docs/OUTPUTS.md "The energy budget"): summary.json's keys and
timeseries.csv's columns for a soft-sphere bed shaken by its floor, an event-driven chute, a servo
Couette cell and a Lees-Edwards gas.

Checks, for each run: energy_input is the sum of its parts (to 1e-12 of the largest: they are
written with 10 significant digits), energy_budget_residual is (input - change - dissipated) /
max(|input|, |dissipated|) of the summary's own numbers, the last timeseries row carries the same
budget, and the residual is small: round-off (1e-9) for the event-driven engine, the integrator's
error for the soft-sphere one (measured 4e-7 in this bed; 1e-3 leaves room for another rounding's
trajectory, while a missing work term leaves a residual of order 1). The part that drives each run
is positive (the floor's work, gravity's along the chute, the walls', the Lees-Edwards
boundaries'), and collisions dissipate.

Usage: /usr/bin/python3 tests/integration/test_energy_budget.py PATH_TO_grainflow  (from the repo root)
"""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run  # noqa: E402

PARTS = ["energy_input_gravity", "energy_input_walls", "energy_input_boundaries", "energy_input_growth",
         "energy_input_separation"]
RUNS = [
    # label, case, --set overrides, driving part, residual bound
    ("shaken bed", "cases/demo/vibrated_bed.toml",
     ["run.duration=0.6", "drive.start=0.1", "drive.ramp=0.1", "output.average_start=0.3", "output.snapshot_interval=0"],
     "energy_input_walls", 1e-3),
    ("chute", "cases/campbell1982/chute_30deg.toml", ["run.duration=100"], "energy_input_gravity", 1e-9),
    ("couette", "cases/campbell1982/couette_noslip.toml", ["run.duration=2000"], "energy_input_walls", 1e-9),
    ("sheared gas", "cases/bench/sheared_spheres_n0.5.toml", ["run.duration=2", "species.0.count=4000",
                                                              "domain.hi=[20.0,20.0,20.0]",
                                                              "particles.lattice_spacing=1.4142135609588815"],
     "energy_input_boundaries", 1e-9),
]


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        for label, case, overrides, driver, bound in RUNS:
            out = os.path.join(tmp, label.replace(" ", "_"))
            args = ["run", case, "-o", out, "--quiet"]
            for o in overrides:
                args += ["--set", o]
            status, _, err = run(exe, *args)
            if not check(status == 0, f"{label}: exited {status}: {err.strip()}"):
                continue
            with open(os.path.join(out, "summary.json")) as f:
                s = json.load(f)
            keys = ["energy_input", "energy_change", "energy_dissipated", "energy_budget_residual"] + PARTS
            missing = [k for k in keys if k not in s]
            if not check(not missing, f"{label}: summary.json lacks {missing}"):
                continue
            total = sum(s[k] for k in PARTS)
            scale = max(abs(s[k]) for k in PARTS + ["energy_input"])
            check(abs(s["energy_input"] - total) <= 1e-9 * scale,
                  f"{label}: energy_input {s['energy_input']} is not the sum of its parts {total}")
            denominator = max(abs(s["energy_input"]), abs(s["energy_dissipated"]))
            residual = (s["energy_input"] - s["energy_change"] - s["energy_dissipated"]) / denominator
            check(abs(residual - s["energy_budget_residual"]) <= 1e-8 + 1e-6 * abs(residual),
                  f"{label}: energy_budget_residual {s['energy_budget_residual']} but the keys give {residual}")
            check(abs(s["energy_budget_residual"]) < bound,
                  f"{label}: residual {s['energy_budget_residual']:.3g} above {bound:g}")
            check(s[driver] > 0.0, f"{label}: {driver} = {s[driver]}, expected positive")
            check(s["energy_dissipated"] > 0.0, f"{label}: energy_dissipated = {s['energy_dissipated']}")
            rows = read_csv(os.path.join(out, "timeseries.csv"))
            last = rows[-1]
            for column in ("energy_input", "energy_change", "energy_dissipated"):
                check(abs(float(last[column]) - s[column]) <= 1e-9 * scale,
                      f"{label}: timeseries' last {column} {last[column]} against the summary's {s[column]}")
            print(f"{label}: input {s['energy_input']:.6g} J ({driver} {s[driver]:.6g}), dissipated "
                  f"{s['energy_dissipated']:.6g}, residual {s['energy_budget_residual']:.3g}")
    return finish("test_energy_budget")


if __name__ == "__main__":
    sys.exit(main())
