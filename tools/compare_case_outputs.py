#!/usr/bin/python3
"""Runs the short version of every bundled case with two grainflow builds and compares their output
folders byte for byte: the check that a refactoring left the physics and the files untouched.

Each case runs on one thread (OpenMP sums are then in one fixed order) with the short durations the
case tests use: 3 ms of a soft-sphere case, 20 time units of an event-driven one. The files that
record the machine or the clock (run_log.json; summary.json's wall-time and memory keys) are
compared with those keys left out, HDF5 files by their contents (h5dump: the files carry
modification times); every other file must be identical. `grainflow check` output is compared too.

Usage: /usr/bin/python3 tools/compare_case_outputs.py OLD_GRAINFLOW NEW_GRAINFLOW [CASE ...]
Exit status 0 when every case matches, 1 otherwise (the differing files are listed).
"""
import filecmp
import glob
import json
import os
import subprocess
import sys
import tempfile

DEM_SHORT = ["--set", "run.duration=0.003"]
EDMD_SHORT = ["--set", "run.duration=20.0", "--set", "output.average_start=10.0"]
# Keys that depend on the machine or the clock, not on the physics.
VOLATILE_KEYS = ("wall", "seconds", "commit", "host", "date", "time_started", "started", "finished", "threads_available",
                 "elapsed", "per_second", "rate_wall", "memory")


def short_args(case):
    with open(case) as handle:
        text = handle.read()
    return EDMD_SHORT if 'kind = "edmd"' in text else DEM_SHORT


def scrub(value):
    if isinstance(value, dict):
        return {k: scrub(v) for k, v in value.items() if not any(word in k for word in VOLATILE_KEYS)}
    if isinstance(value, list):
        return [scrub(v) for v in value]
    return value


def same_file(a, b):
    if filecmp.cmp(a, b, shallow=False):
        return True
    if a.endswith(".h5"):
        # HDF5 stamps objects with their modification times: compare every dataset and attribute.
        dump = [subprocess.run(["h5dump", f], capture_output=True, text=True).stdout.split("\n", 1)[-1] for f in (a, b)]
        return dump[0] == dump[1] and bool(dump[0])
    if a.endswith(".json"):
        with open(a) as fa, open(b) as fb:
            try:
                return scrub(json.load(fa)) == scrub(json.load(fb))
            except json.JSONDecodeError:
                return False
    return False


def run_case(exe, case, out):
    check = subprocess.run([exe, "check", case], capture_output=True, text=True)
    run = subprocess.run([exe, "run", case, "-o", out, "--quiet", "--threads", "1", *short_args(case)],
                         capture_output=True, text=True, env={**os.environ, "GRAINFLOW_SERIAL": "1"})
    return check.stdout + check.stderr, run.returncode, run.stderr


def compare(old, new, case, tmp):
    name = os.path.relpath(case).replace("/", "_").removesuffix(".toml")
    a, b = os.path.join(tmp, "old", name), os.path.join(tmp, "new", name)
    check_a, status_a, err_a = run_case(old, case, a)
    check_b, status_b, err_b = run_case(new, case, b)
    problems = []
    if check_a != check_b:
        problems.append("`grainflow check` output differs")
    if status_a != status_b:
        problems.append(f"exit status {status_a} against {status_b}: {err_b.strip()[-300:]}")
    files_a = sorted(os.path.relpath(p, a) for p in glob.glob(os.path.join(a, "**"), recursive=True) if os.path.isfile(p))
    files_b = sorted(os.path.relpath(p, b) for p in glob.glob(os.path.join(b, "**"), recursive=True) if os.path.isfile(p))
    if files_a != files_b:
        problems.append(f"file lists differ: {sorted(set(files_a) ^ set(files_b))}")
    for f in sorted(set(files_a) & set(files_b)):
        if f == "run_log.json":
            continue
        if not same_file(os.path.join(a, f), os.path.join(b, f)):
            problems.append(f"{f} differs")
    return problems, len(files_a)


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    old, new = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    cases = sys.argv[3:] or sorted(glob.glob("cases/*/*.toml"))
    cases = [c for c in cases if "cube_walls_100k" not in c]  # 10^5 spheres: a benchmark, not a short case
    failed = 0
    with tempfile.TemporaryDirectory(prefix="grainflow_compare_") as tmp:
        for case in cases:
            problems, count = compare(old, new, case, tmp)
            print(f"{'same' if not problems else 'DIFFERENT':9} {case} ({count} files)")
            for p in problems:
                print(f"          {p}")
            failed += bool(problems)
    print(f"{len(cases) - failed} of {len(cases)} cases byte-identical")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
