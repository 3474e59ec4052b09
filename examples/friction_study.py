#!/usr/bin/python3
"""A small parameter study from Python: a short rough-based chute (Silbert et al. 2001, the case
cases/soft_sphere/silbert_chute.toml cut down to 600 grains over 8 x 8 d, tilted 26 degrees) run at three friction
coefficients; the flow's mean speed down the slope and its depth-averaged solids fraction,
read from the particle arrays at the end of each run.

Usage: /usr/bin/python3 examples/friction_study.py [--duration T] [--output FOLDER]
(with the package on the path: `make python`, or PYTHONPATH=build/release/python).
"""
import argparse
import os

import numpy as np

import grainflow

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CHUTE = os.path.join(ROOT, "cases", "soft_sphere", "silbert_chute.toml")

# Silbert's chute, smaller: 400 grains on a base of 73 (the same 1.14 per d^2) over 8 x 8 d.
SMALL_CHUTE = {
    "domain.hi": [8.0, 30.0, 8.0],
    "gravity.vector": [0.4383711467890774, -0.898794046299167, 0.0],  # tilted 26 degrees
    "species.0.count": 600,
    "species.1.count": 73,
    "species.1.region_hi": [8.0, 1.7, 8.0],
    "particles.region_hi": [8.0, 28.0, 8.0],
    "output.interval": 1.0,
    "output.average_start": 1.0e9,
}


def chute_case(duration, friction):
    values = dict(SMALL_CHUTE)
    values["run.duration"] = duration
    values["contact.friction"] = friction
    return grainflow.Case.from_file(CHUTE, set=values)


def flow_state(sim):
    """Mean speed of the free grains down the slope (x), and their number per unit area."""
    p = sim.particles
    free = p.motion == 0
    return float(p.velocity[free, 0].mean()), int(free.sum())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=20.0, help="simulated time of each run (d = g = 1)")
    parser.add_argument("--output", default=None, help="folder for the runs' outputs (default: temporary)")
    args = parser.parse_args()
    print(f"{'friction':>8}  {'mean speed':>10}  {'kinetic energy':>14}  {'residual':>9}")
    results = []
    for friction in (0.3, 0.5, 0.8):
        output = os.path.join(args.output, f"mu_{friction}") if args.output else None
        sim = grainflow.Simulation(chute_case(args.duration, friction), output=output)
        sim.run()
        speed, _ = flow_state(sim)
        summary = sim.summary()
        results.append((friction, speed))
        print(f"{friction:8.2f}  {speed:10.4f}  {summary['kinetic_energy']:14.6g}  "
              f"{summary['energy_budget_residual']:9.2e}")
    return results


if __name__ == "__main__":
    main()
