#!/usr/bin/python3
"""`grainflow theory` end to end (docs/MODELS.md, "Kinetic theory of a vibrated bed"; Lan 1994
section 4.1): on the bundled demo case it writes a CSV with '#' lines and the header
Y,solids_fraction,W,temperature,pressure,heat_flux. Checked against the case file, read here with
tomllib: the mass hold-up m_t = N pi d^2/(6 A) (Lan eq. 4-1-3) is the trapezoid integral of the
solids fraction over Y; the floor carries the weight, p(0) = rho_s g d m_t; W = sqrt(T/(g d)). Given a
run's output folder (a summary.json naming the case), it writes OUTDIR/analysis/kinetic_theory.csv,
and without -o it writes kinetic_theory.csv in the current folder. Bad input (a missing path, a
folder without summary.json or without its "case" field, a case with no drive) exits with status
2 and a message naming the file, the key and the reason, and writes nothing.

Usage: /usr/bin/python3 tests/integration/test_theory.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile
import tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

DEMO = os.path.abspath(os.path.join("cases", "demo", "vibrated_bed.toml"))
HEADER = "Y,solids_fraction,W,temperature,pressure,heat_flux"


def case_quantities(path):
    """d, rho_s, g and m_t of a one-species case with its floor normal to y."""
    with open(path, "rb") as f:
        case = tomllib.load(f)
    species = case["species"][0]
    d, rho = species["diameter"], species["density"]
    lo, hi = case["domain"]["lo"], case["domain"]["hi"]
    area = (hi[0] - lo[0]) * (hi[2] - lo[2])
    g = math.sqrt(sum(c * c for c in case["gravity"]["vector"]))
    return d, rho, g, species["count"] * math.pi * d**3 / 6.0 / (area * d)


def check_profile(path, label, count_scale=1.0):
    """The CSV's layout and its balances against the demo case (its particle count times count_scale)."""
    if not check(os.path.exists(path), f"{label}: {path} was not written"):
        return
    with open(path) as f:
        lines = f.read().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    check(len(comments) >= 1 and "kinetic theory" in comments[0] and "m_t" in comments[0],
          f"{label}: first comment line does not describe the model: {comments[:1]}")
    check(any("units" in c for c in comments), f"{label}: no units comment")
    header = next(line for line in lines if not line.startswith("#"))
    check(header == HEADER, f"{label}: header {header!r}")
    rows = read_csv(path)
    if not check(len(rows) > 50, f"{label}: only {len(rows)} rows"):
        return
    col = {k: [float(r[k]) for r in rows] for k in HEADER.split(",")}
    d, rho, g, mt = case_quantities(DEMO)
    mt *= count_scale
    y, nu = col["Y"], col["solids_fraction"]
    check(y[0] == 0.0 and all(b > a for a, b in zip(y, y[1:])), f"{label}: Y does not rise from 0")
    # Trapezoid rule: the solver spaces points at most 0.02 max(1, theta) apart, so the rule errs by
    # less than (0.02)^2/12 ~ 3e-5 of m_t where nu varies on the scale of a diameter or of theta;
    # the profile stops where 1e-10 of the mass is left above. Allow 1e-4 relative.
    mass = sum(0.5 * (y[i] - y[i - 1]) * (nu[i] + nu[i - 1]) for i in range(1, len(y)))
    check(abs(mass - mt) < 1e-4 * mt, f"{label}: integral of nu dY = {mass}, case m_t = {mt}")
    # Hydrostatics (printed to 10 digits).
    p0 = rho * g * d * mt
    check(abs(col["pressure"][0] - p0) < 1e-8 * p0, f"{label}: p(0) = {col['pressure'][0]} Pa, weight {p0} Pa")
    worst = max(abs(w * w * g * d - t) / t for w, t in zip(col["W"], col["temperature"]))
    check(worst < 1e-8, f"{label}: W^2 g d differs from T by {worst} relative")
    check(all(0.0 < v < 0.64 for v in nu), f"{label}: solids fraction outside (0, 0.64)")
    check(col["heat_flux"][0] > 0.0, f"{label}: the floor does not heat the bed: q(0) = {col['heat_flux'][0]}")


def expect_refusal(exe, args, words, label, cwd=None):
    status, out, err = run(exe, "theory", *args, cwd=cwd)
    check(status == 2, f"{label}: exit status {status}, expected 2 (stderr: {err.strip()})")
    for word in words:
        check(word in err, f"{label}: {word!r} not in the message: {err.strip()}")


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory(prefix="grainflow_theory_") as tmp:
        out = os.path.join(tmp, "kt.csv")
        status, stdout, err = run(exe, "theory", DEMO, "-o", out)
        if check(status == 0, f"theory on the demo exited {status}: {err.strip()}"):
            check("W(0)" in stdout, f"no summary line: {stdout!r}")
            check_profile(out, "demo")

        # Default output in the current folder.
        status, _, err = run(exe, "theory", DEMO, cwd=tmp)
        if check(status == 0, f"theory without -o exited {status}: {err.strip()}"):
            check_profile(os.path.join(tmp, "kinetic_theory.csv"), "default output")

        # A run's output folder: summary.json names the case.
        rundir = os.path.join(tmp, "run")
        os.makedirs(rundir)
        write_text(os.path.join(rundir, "summary.json"), json.dumps({"engine": "dem", "case": DEMO, "steps": 1}))
        status, _, err = run(exe, "theory", rundir)
        if check(status == 0, f"theory on a run folder exited {status}: {err.strip()}"):
            check_profile(os.path.join(rundir, "analysis", "kinetic_theory.csv"), "run folder")

        # A sweep's run folder: summary.json also records the run's --set assignments, one per
        # line, and the theory applies them (here 1.5 times the demo's particles: 1.5 times its m_t).
        with open(DEMO, "rb") as f:
            count = tomllib.load(f)["species"][0]["count"]
        pointdir = os.path.join(tmp, "sweep_point")
        os.makedirs(pointdir)
        write_text(os.path.join(pointdir, "summary.json"),
                   json.dumps({"engine": "dem", "case": DEMO, "case_overrides": f"run.duration=1\nspecies.0.count={3 * count // 2}"}))
        status, _, err = run(exe, "theory", pointdir)
        if check(status == 0, f"theory on a sweep point exited {status}: {err.strip()}"):
            check_profile(os.path.join(pointdir, "analysis", "kinetic_theory.csv"), "sweep point", (3 * count // 2) / count)

        # Bad input: exit 2, the message names the file (and key) and the reason; nothing written.
        missing = os.path.join(tmp, "no_such_case.toml")
        expect_refusal(exe, [missing, "-o", os.path.join(tmp, "bad.csv")], [missing, "no such"], "missing path")
        empty = os.path.join(tmp, "empty_run")
        os.makedirs(empty)
        expect_refusal(exe, [empty], [empty, "summary.json"], "folder without summary.json")
        nocase = os.path.join(tmp, "nocase_run")
        os.makedirs(nocase)
        write_text(os.path.join(nocase, "summary.json"), json.dumps({"engine": "dem"}))
        expect_refusal(exe, [nocase], ["summary.json", "'case'"], "summary.json without case")
        with open(DEMO) as f:
            text = f.read()
        undriven = write_text(os.path.join(tmp, "undriven.toml"), text[: text.index("[drive]")] + text[text.index("[run]"):])
        expect_refusal(exe, [undriven, "-o", os.path.join(tmp, "bad.csv")], [undriven, "'drive'"], "case without drive")
        expect_refusal(exe, [DEMO, "--set", "restitution=0.5", "-o", os.path.join(tmp, "bad.csv")],
                       ["restitution"], "unknown --set key")
        check(not os.path.exists(os.path.join(tmp, "bad.csv")), "a refused input wrote its output file")
        check(not os.path.exists(os.path.join(empty, "analysis")), "a refused run folder got an analysis folder")
    return finish("test_theory")


if __name__ == "__main__":
    sys.exit(main())
