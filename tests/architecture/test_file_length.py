#!/usr/bin/python3
"""No source file under src/ is longer than 600 lines: a longer file holds more than one component
and is split along its seams (docs/ARCHITECTURE.md).

Usage: /usr/bin/python3 tests/architecture/test_file_length.py [REPOSITORY_ROOT]
Exit status 0 when every file is short enough, 1 with every offender and its line count listed.
"""
import os
import re
import sys

MAX_LINES = 600
SOURCE = re.compile(r"\.(hpp|cpp|h|c|in)$")


def line_count(path):
    with open(path, "rb") as f:
        return sum(1 for _ in f)


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    source_root = os.path.join(root, "src")
    problems, checked = [], 0
    for folder, _, names in sorted(os.walk(source_root)):
        for name in sorted(names):
            if not SOURCE.search(name):
                continue
            path = os.path.join(folder, name)
            checked += 1
            lines = line_count(path)
            if lines > MAX_LINES:
                problems.append(f"{os.path.relpath(path, root)}: {lines} lines (at most {MAX_LINES}; split it along its seams)")
    if checked < 100:
        problems.append(f"only {checked} source files were found under {source_root}; is this the repository?")
    for p in problems:
        print(p)
    print(f"test_file_length: {checked} source files checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
