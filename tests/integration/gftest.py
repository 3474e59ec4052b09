"""Helpers shared by the integration scripts in this folder (test_*.py): the list of failed checks,
check(), running the grainflow executable, writing a case and reading the CSV files of an output
folder. Each script imports this module by putting its own folder on sys.path, so
`/usr/bin/python3 tests/integration/test_X.py PATH_TO_grainflow` works from the repo root.
"""
import csv
import os
import re
import subprocess
import sys

FAILURES = []


def check(condition, message):
    """Records and prints a failed check; returns the condition so callers can stop on a failure."""
    if not condition:
        FAILURES.append(message)
        print("FAIL: " + message, file=sys.stderr)
    return condition


def executable_from_argv(usage):
    """The absolute path of grainflow, the one argument; None (after printing `usage`) otherwise."""
    if len(sys.argv) != 2:
        print(usage, file=sys.stderr)
        return None
    return os.path.abspath(sys.argv[1])


def run(exe, *args, cwd=None, timeout=120):
    """Runs grainflow with `args`; returns (exit status, stdout, stderr)."""
    result = subprocess.run([exe, *args], capture_output=True, text=True, timeout=timeout, cwd=cwd)
    return result.returncode, result.stdout, result.stderr


def write_text(path, text):
    """Writes `text` (a case file) to `path` and returns the path."""
    with open(path, "w") as f:
        f.write(text)
    return path


def read_csv(path):
    """The rows of an output CSV file as dicts, its '#' comment lines skipped."""
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def sweep_commands(path):
    """The `grainflow sweep ...` commands written in a case's header comment."""
    commands = []
    with open(path) as handle:
        for line in handle:
            if not line.startswith("#"):
                break
            found = re.search(r"grainflow sweep .*", line)
            if found:
                commands.append(found.group(0).strip())
    return commands


def finish(name):
    """The exit status of a script: 1 after any failed check, else 0 with a line saying all passed."""
    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed", file=sys.stderr)
        return 1
    print(f"{name}: all checks passed")
    return 0
