#!/usr/bin/python3
"""Writes tests/regression/seed_goldens.json: a few scalars of the short version of every bundled
seed case (cases/lan1994/, cases/campbell1982/), which test_lan1994_cases.py and
test_campbell1982_cases.py compare every run with, so a change in physics fails a test.

The short versions are those the tests run, 3 ms of a soft-sphere case and 20 time units of an
event-driven one (averages from half-way), on one thread; an event-driven chute whose hard-disc
trajectories have decorrelated between two roundings by then (chaos amplifies round-off about
e-fold per collision per particle) gets its golden values from a shorter run (5, 2 or 1 time units),
the longest over which two roundings still agree to 1e-6. Each value's tolerance is the relative
difference between two builds that round differently (the release build, with FMA contraction
under -march=native, and one without -march), times 20, and never below 1e-7: the spread between two
roundings is the scale on which another compiler or CPU may legitimately land, and 20 times it
leaves room for a machine that rounds differently again, while a change of the physics (a
constant, a rule, a default) moves these values by far more.

Usage (from the repository root; the second build without -march=native):
  cmake -S . -B build/nonnative -G Ninja -DCMAKE_BUILD_TYPE=Release -DGRAINFLOW_NATIVE=OFF
  cmake --build build/nonnative --target grainflow
  /usr/bin/python3 tests/regression/make_seed_goldens.py build/release/grainflow build/nonnative/grainflow
Regenerate only when a change of the physics is intended, and say so in the commit.
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

DEM_SHORT = ["--set", "run.duration=0.003"]
EDMD_DURATIONS = (20.0, 5.0, 2.0, 1.0)  # the first is the tests' own short run
AGREEMENT = 1e-6
DEM_KEYS = ("kinetic_energy", "rotational_energy", "granular_temperature", "max_overlap_over_diameter", "cell_temperature",
            "bed_height", "neighbor_rebuilds", "steps")
EDMD_KEYS = ("collisions", "wall_collisions", "events", "kinetic_energy", "rotational_energy", "granular_temperature",
             "pressure", "dissipated_energy", "packing_fraction")
FACTOR, FLOOR = 20.0, 1e-7
OUTPUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "seed_goldens.json")


def is_edmd(case):
    with open(case) as f:
        return 'kind = "edmd"' in f.read()


def edmd_args(duration):
    return ["--set", f"run.duration={duration!r}", "--set", f"output.average_start={0.5 * duration!r}"]


def summary_of(exe, case, args, tmp):
    out = os.path.join(tmp, os.path.basename(os.path.dirname(exe)) + "_" + os.path.basename(case) + "_" + args[1])
    result = subprocess.run([exe, "run", case, "-o", out, "--quiet", *args], capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit(f"{exe} {case}: exit {result.returncode}: {result.stderr}")
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    first, second = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    goldens = {"why": __doc__.split("\n\n")[1].replace("\n", " "), "factor": FACTOR, "floor": FLOOR, "cases": {}}
    with tempfile.TemporaryDirectory(prefix="grainflow_goldens_") as tmp:
        for case in sorted(glob.glob("cases/lan1994/*.toml") + glob.glob("cases/campbell1982/*.toml")):
            keys = EDMD_KEYS if is_edmd(case) else DEM_KEYS
            for args in [edmd_args(d) for d in EDMD_DURATIONS] if is_edmd(case) else [DEM_SHORT]:
                a, b = summary_of(first, case, args, tmp), summary_of(second, case, args, tmp)
                spread = {k: abs(a[k] - b[k]) / max(abs(a[k]), 1e-300) for k in keys if k in a}
                if max(spread.values()) <= AGREEMENT:
                    break
            values = {k: {"value": a[k], "relative_tolerance": max(FACTOR * spread[k], FLOOR),
                          "spread_between_builds": spread[k]} for k in spread}
            entry = {"args": args, "values": values}
            goldens["cases"][case] = entry
            print(case, " ".join(args), {k: f"{v['value']:.6g} ±{v['relative_tolerance']:.1e}" for k, v in values.items()})
    with open(OUTPUT, "w") as f:
        json.dump(goldens, f, indent=1, sort_keys=True)
        f.write("\n")
    print(f"wrote {OUTPUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
