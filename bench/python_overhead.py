#!/usr/bin/python3
"""What driving a run from Python costs: the LAMMPS chute (cases/bench/chute_hooke.toml, 32,000
spheres) for STEPS steps from the command line, and from Python in advance() calls of 10 time
steps each, ROUNDS interleaved rounds, one thread. Prints each one's median particle-steps per
second (the summary's, over the loop) and the per-round ratio Python / command line.

Usage: /usr/bin/python3 bench/python_overhead.py [ROUNDS] [STEPS]   (after make release)
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "build", "release", "python"))
import grainflow  # noqa: E402

CASE = os.path.join(ROOT, "cases", "bench", "chute_hooke.toml")
PROGRAM = os.path.join(ROOT, "build", "release", "grainflow")


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    steps = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
    case = grainflow.Case.from_file(CASE)
    dt = case["run.time_step"]
    duration = steps * dt
    cli, python, ratios = [], [], []
    with tempfile.TemporaryDirectory() as out:
        for r in range(rounds):
            folder = os.path.join(out, f"cli_{r}")
            subprocess.run([PROGRAM, "run", CASE, "-o", folder, "--quiet", "--set", f"run.duration={duration!r}"],
                           check=True)
            with open(os.path.join(folder, "summary.json")) as f:
                cli.append(json.load(f)["particle_steps_per_second"])
            sim = grainflow.Simulation(case.with_values({"run.duration": duration}), output=os.path.join(out, f"py_{r}"))
            start = time.perf_counter()
            while sim.steps < steps:
                sim.advance(10 * dt)
            loop = time.perf_counter() - start
            summary = sim.summary()
            python.append(summary["particle_steps_per_second"])
            ratios.append(python[-1] / cli[-1])
            print(f"round {r + 1}: command line {cli[-1] / 1e6:.3f}, Python {python[-1] / 1e6:.3f} M particle-steps/s"
                  f" (Python's own clock over the advance() loop: {summary['particles'] * steps / loop / 1e6:.3f})",
                  flush=True)
    print(f"command line  median {statistics.median(cli) / 1e6:.3f} M particle-steps/s")
    print(f"Python        median {statistics.median(python) / 1e6:.3f} M particle-steps/s, advance() every 10 steps")
    print(f"Python / command line, per round: median {statistics.median(ratios):.3f} "
          f"(min {min(ratios):.3f}, max {max(ratios):.3f})")


if __name__ == "__main__":
    main()
