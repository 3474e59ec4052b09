#!/usr/bin/python3
"""`grainflow calibrate` (Lan 1994 section 4.1.3) on a case whose answer is known from theory.

Four glass spheres (d = 3 mm) move at v = 1 m/s onto a fixed floor, without gravity and far enough
apart never to touch each other. On the Walton-Braun loading branch F = K1 alpha, a sphere of mass
m hitting an immovable wall compresses the spring until its kinetic energy is stored:
alpha_max = v sqrt(m / K1). The overlap stays within 1 % of d when K1 >= K_needed = m (v / 0.01 d)^2.
The search multiplies K1 by the factor (1.25) from its start, so the K1 it reports must bracket
K_needed: K_needed <= K1 < 1.25 K_needed, and the trial below it must have failed. The starts are
chosen so that the grid points lie 12 % above and 10 % below K_needed, well clear of the time
integration's error in the peak overlap (about 0.2 % at 15 steps per contact).

Also: a start above the answer (the search steps down and reports the smallest passing K1), the
output files, and bad input (no starting stiffness, --factor <= 1, --limit, a non-DEM case):
exit status 2, a message naming the option or key, and no output folder.

Usage: /usr/bin/python3 tests/integration/test_calibrate.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

D = 0.003          # m
RHO = 2490.0       # kg/m^3
V = 1.0            # m/s, impact speed
LIMIT = 0.01       # max overlap / d
FACTOR = 1.25
MASS = RHO * math.pi / 6.0 * D ** 3
K_NEEDED = MASS * (V / (LIMIT * D)) ** 2  # N/m, about 3.9e4

# No contact.k1: calibrate sets it.
CASE = """# four spheres hitting the floor at 1 m/s
[engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.015, 0.02, 0.015]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[gravity]
vector = [0.0, 0.0, 0.0]

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0

[particles]
init = "file"
file = "drop.csv"

[contact]
restitution = 0.9

[run]
duration = 0.003

[output]
interval = 0.0005
"""

# 1 mm above the floor (centres at d/2 + 1 mm), 7 mm apart, moving down at V.
PARTICLES = "species,x,y,z,vx,vy,vz\n" + "".join(
    f"glass,{x},0.0025,{z},0,{-V},0\n" for x in (0.004, 0.011) for z in (0.004, 0.011))


def check_bracket(outdir, label, expect_descended):
    """The answer in OUTDIR brackets K_NEEDED and the files agree with each other and with theory."""
    with open(os.path.join(outdir, "calibration.json")) as f:
        result = json.load(f)
    rows = read_csv(os.path.join(outdir, "calibration.csv"))
    k1 = result["k1"]
    check(result["converged"] and result["bracketed"], f"{label}: not converged and bracketed: {result}")
    check(result["descended"] == expect_descended, f"{label}: descended = {result['descended']}")
    check(K_NEEDED <= k1 < FACTOR * K_NEEDED,
          f"{label}: K1 = {k1} N/m does not bracket K_needed = {K_NEEDED:.6g} N/m (factor {FACTOR})")
    check(result["max_overlap_over_diameter"] <= LIMIT, f"{label}: reported overlap {result['max_overlap_over_diameter']}")
    # The measured peak overlap of the passing trial against alpha_max = v sqrt(m / K1).
    theory = V * math.sqrt(MASS / k1) / D
    check(abs(result["max_overlap_over_diameter"] - theory) < 0.01 * theory,
          f"{label}: max overlap / d {result['max_overlap_over_diameter']} vs theory {theory:.6g}")
    check(math.isclose(result["failing_k1"], k1 / FACTOR, rel_tol=1e-5),
          f"{label}: failing neighbour {result['failing_k1']} is not K1 / factor")
    check(result["failing_max_overlap_over_diameter"] > LIMIT, f"{label}: the failing neighbour did not fail")
    # Time step of eq. (2-5-4): dt = (pi e / 15) sqrt(m / 2 K1).
    dt = math.pi * 0.9 / 15 * math.sqrt(MASS / (2 * k1))
    check(math.isclose(result["time_step"], dt, rel_tol=1e-6), f"{label}: time step {result['time_step']} vs {dt}")
    check(result["hertz_k1"] is None, f"{label}: no youngs_modulus, yet hertz_k1 = {result['hertz_k1']}")
    check(len(rows) == result["trials"], f"{label}: {len(rows)} CSV rows for {result['trials']} trials")
    chosen = [r for r in rows if r["chosen"] == "1"]
    check(len(chosen) == 1 and float(chosen[0]["k1"]) == k1, f"{label}: chosen CSV row {chosen}")
    for r in rows:
        passed = float(r["max_overlap_over_diameter"]) <= LIMIT
        check((r["passed"] == "1") == passed and (r["halted"] == "1") != passed, f"{label}: inconsistent row {r}")
        check(os.path.isfile(os.path.join(outdir, r["folder"], "summary.json")), f"{label}: no {r['folder']}/summary.json")
        if r["halted"] == "1":  # halted early, at the first time-series row after the impact (t = 1 ms)
            check(float(r["simulated_time"]) < 0.0025, f"{label}: halted trial ran to {r['simulated_time']} s")
    return result


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory(prefix="grainflow_calibrate_") as tmp:
        case = write_text(os.path.join(tmp, "drop.toml"), CASE)
        write_text(os.path.join(tmp, "drop.csv"), PARTICLES)

        # Lan's direction: start below, grid points at 0.57, 0.72, 0.90 (fail) and 1.12 (pass) K_needed.
        up = os.path.join(tmp, "up")
        start = K_NEEDED * 1.12 / FACTOR ** 3
        status, out, err = run(exe, "calibrate", case, "--start-k1", repr(start), "-o", up)
        if check(status == 0, f"calibrate (upwards) exited {status}: {err}"):
            result = check_bracket(up, "upwards", expect_descended=False)
            check(result["trials"] == 4, f"upwards: {result['trials']} trials, expected 4")
            check(f"k1 = {result['k1']:.6g}" in out, f"upwards: no 'k1 = ...' line to paste:\n{out}")
            check("warning" not in err, f"upwards: unexpected warning: {err}")

        # A start above the answer: steps down to the smallest passing K1 (1.12 K_needed) with a warning.
        down = os.path.join(tmp, "down")
        start = K_NEEDED * 1.12 * FACTOR ** 2
        status, out, err = run(exe, "calibrate", case, "--start-k1", repr(start), "-o", down, "--factor", "1.25",
                               "--limit", "0.01")
        if check(status == 0, f"calibrate (downwards) exited {status}: {err}"):
            result = check_bracket(down, "downwards", expect_descended=True)
            check(result["trials"] == 4, f"downwards: {result['trials']} trials, expected 4")
            check("already keeps the overlap within the limit" in err, f"downwards: no warning about the start: {err}")

        # Too few trials to get there: exit 1, the files still say what was tried.
        few = os.path.join(tmp, "few")
        status, _, err = run(exe, "calibrate", case, "--start-k1", repr(K_NEEDED / 4), "--max-trials", "2", "-o", few)
        check(status == 1, f"calibrate with too few trials exited {status}")
        check("--max-trials" in err, f"too few trials: message does not name --max-trials: {err}")
        if check(os.path.isfile(os.path.join(few, "calibration.json")), "too few trials: no calibration.json"):
            with open(os.path.join(few, "calibration.json")) as f:
                result = json.load(f)
            check(not result["converged"] and result["k1"] is None and result["trials"] == 2,
                  f"too few trials: {result}")

        # Bad input: exit 2, a message naming the option or key, nothing written.
        chute = os.path.join("cases", "campbell1982", "chute_30deg.toml")
        bad = [
            ("no starting stiffness", [case], "species.youngs_modulus", "--start-k1"),
            ("factor 1", [case, "--start-k1", "1e4", "--factor", "1"], "--factor", "greater than 1"),
            ("factor below 1", [case, "--start-k1", "1e4", "--factor", "0.8"], "--factor", "greater than 1"),
            ("limit 0", [case, "--start-k1", "1e4", "--limit", "0"], "--limit", "(0, 1)"),
            ("negative start", [case, "--start-k1", "-5"], "--start-k1", "positive"),
            ("zero trials", [case, "--start-k1", "1e4", "--max-trials", "0"], "--max-trials", "at least 1"),
            ("event-driven case", [chute, "--start-k1", "1e4"], "engine.kind", "dem"),
            ("bad --set", [case, "--start-k1", "1e4", "--set", "contact.foo=1"], "contact.foo", "unknown key"),
        ]
        for label, args, key, words in bad:
            outdir = os.path.join(tmp, "bad_" + label.replace(" ", "_"))
            status, _, err = run(exe, "calibrate", *args, "-o", outdir)
            check(status == 2, f"{label}: exit status {status}, expected 2 ({err.strip()})")
            check(key in err and words in err, f"{label}: message does not name '{key}' and '{words}': {err.strip()}")
            check(not os.path.exists(outdir), f"{label}: the output folder was created")
    return finish("test_calibrate")


if __name__ == "__main__":
    sys.exit(main())
