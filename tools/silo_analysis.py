#!/usr/bin/python3
"""Beverloo's law from a sweep of silo discharges: for each run of SWEEP_DIR, its orifice diameter D
(twice the hole_radius of its holed plane), its steady discharge rate W with error (summary.json)
and its bed's bulk density rho_b (the bulk solids fraction summary.json gives for the outlet's bed
box, else that of the particles whose centres lie in a cylinder about the silo's axis in the final
state, away from the orifice and the free surface; times the particles' density); then the fit
W = C rho_b sqrt(g) (D - k d)^(5/2) (3D; (D - k d)^(3/2) for discs), as the straight line
W^(2/5) = a (D - k d) weighted by each rate's error. Writes silo_beverloo.csv and silo_beverloo.png
in SWEEP_DIR (as `grainflow plot SWEEP_DIR` does) and prints C and k with their errors beside the
published ranges.

Usage: /usr/bin/python3 tools/silo_analysis.py SWEEP_DIR [--bed-radius R] [--bed-z LO HI]
  (the final state's cylinder, for runs without an outlet bed box: R = 7, 5 < z < 15 in the
  case's units, about the z axis)
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from grainflow_plots import silo  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sweep")
    parser.add_argument("--bed-radius", type=float, default=7.0)
    parser.add_argument("--bed-z", type=float, nargs=2, default=[5.0, 15.0])
    args = parser.parse_args()
    rows = silo.sweep_rows(args.sweep, args.bed_radius, tuple(args.bed_z))
    if len(rows) < 3:
        raise SystemExit(f"silo_analysis: {len(rows)} runs with a discharge rate in {args.sweep}: the fit needs 3 or more")
    C, dC, k, dk, rho_b, exponent = silo.beverloo_fit(rows)
    d = rows[0]["d"]
    print(f"{'D/d':>6} {'W':>12} {'+-':>10} {'rho_b':>8}")
    for r in rows:
        print(f"{r['D'] / d:6.2f} {r['W']:12.5g} {r['dW']:10.3g} {r['rho_b']:8.4f}")
    law = "(D - k d)^(5/2)" if exponent == 2.5 else "(D - k d)^(3/2)"
    print(f"W = C rho_b sqrt(g) {law}: C = {C:.3f} +- {dC:.3f}, k = {k:.2f} +- {dk:.2f}, "
          f"rho_b = {rho_b:.4f} (bulk density of the bed, solids fraction x particle density)")
    print(silo.PUBLISHED_3D if exponent == 2.5 else silo.PUBLISHED_2D)
    silo.plot_beverloo(args.sweep, rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
