#!/usr/bin/python3
"""Beverloo's law from a sweep of silo discharges: for each run of SWEEP_DIR, its orifice diameter D
(twice the hole_radius of its holed plane), its steady discharge rate W with error (summary.json)
and its bed's bulk density rho_b (the bulk solids fraction summary.json gives for the outlet's
bed box, else that of the particles whose centres lie in a cylinder about the silo's axis in the
final state, away from the orifice and the free surface; times the particles' density); then the fit W = C rho_b sqrt(g) (D - k d)^(5/2) (3D; (D - k d)^(3/2) for discs), as the
straight line W^(2/5) = a (D - k d) weighted by each rate's error. Writes silo_beverloo.csv and
silo_beverloo.png in SWEEP_DIR and prints C and k with their errors beside the published ranges.

Usage: /usr/bin/python3 tools/silo_analysis.py SWEEP_DIR [--bed-radius R] [--bed-z LO HI]
  (defaults: R = 7, 5 < z < 15 in the case's units, about the z axis, gravity along -z)
"""
import argparse
import csv
import glob
import json
import math
import os
import sys
import tomllib

import numpy as np


def orifice_and_case(run):
    with open(os.path.join(run, "resolved_case.toml"), "rb") as f:
        case = tomllib.load(f)
    holes = [g["hole_radius"] for g in case.get("geometry", []) if "hole_radius" in g]
    if not holes:
        raise SystemExit(f"silo_analysis: {run}: no [[geometry]] plane with hole_radius")
    return 2.0 * holes[0], case


def bulk_fraction(run, radius, z_lo, z_hi, dimension):
    solid = 0.0
    with open(os.path.join(run, "final_state.csv")) as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        for r in rows:
            x, y, z, d = float(r["x"]), float(r["y"]), float(r["z"]), float(r["diameter"])
            if z_lo < z < z_hi and math.hypot(x, y) < radius:
                solid += math.pi * d ** 3 / 6.0 if dimension == 3 else math.pi * d * d / 4.0
    volume = math.pi * radius ** 2 * (z_hi - z_lo) if dimension == 3 else 2.0 * radius * (z_hi - z_lo)
    return solid / volume


def fit(D, W, dW, exponent):
    """W^(1/exponent) = a D + b, weighted; returns a, b and their covariance."""
    y = W ** (1.0 / exponent)
    dy = dW * y / (exponent * W)
    w = 1.0 / dy ** 2
    A = np.vstack([D, np.ones_like(D)]).T
    cov = np.linalg.inv(A.T @ (A * w[:, None]))
    a, b = cov @ (A.T @ (w * y))
    chi2 = float(np.sum(w * (y - (a * D + b)) ** 2))
    dof = max(1, len(D) - 2)
    return a, b, cov * max(1.0, chi2 / dof)  # errors scaled up when the scatter exceeds the error bars


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sweep")
    parser.add_argument("--bed-radius", type=float, default=7.0)
    parser.add_argument("--bed-z", type=float, nargs=2, default=[5.0, 15.0])
    args = parser.parse_args()
    runs = sorted(p for p in glob.glob(os.path.join(args.sweep, "*")) if os.path.isfile(os.path.join(p, "summary.json")))
    rows = []
    for run in runs:
        summary = json.load(open(os.path.join(run, "summary.json")))
        if "discharge_rate" not in summary:
            print(f"silo_analysis: {run}: no discharge_rate (too few samples or no outflow)", file=sys.stderr)
            continue
        D, case = orifice_and_case(run)
        dimension = case.get("engine", {}).get("dimension", 3)
        g = math.sqrt(sum(v * v for v in case.get("gravity", {}).get("vector", [0.0, -9.81, 0.0])))
        species = case["species"][0]
        # The bulk solids fraction the run measured in its outlet's bed box over the discharge
        # window, else one from the final state.
        has_bed = any("bed_lo" in o for o in case.get("outlet", []))
        fraction = summary.get("bulk_solids_fraction") if has_bed else None
        if fraction is None:
            fraction = bulk_fraction(run, args.bed_radius, *args.bed_z, dimension)
        rho_b = fraction * species["density"]
        rows.append(dict(run=os.path.basename(run), D=D, d=species["diameter"], W=summary["discharge_rate"],
                         dW=max(summary["discharge_rate_error"], 1e-12), rho_b=rho_b, g=g, dimension=dimension))
    if len(rows) < 3:
        raise SystemExit(f"silo_analysis: {len(rows)} runs with a discharge rate in {args.sweep}: the fit needs 3 or more")
    rows.sort(key=lambda r: r["D"])
    D, W, dW = (np.array([r[k] for r in rows]) for k in ("D", "W", "dW"))
    exponent = 2.5 if rows[0]["dimension"] == 3 else 1.5
    a, b, cov = fit(D, W, dW, exponent)
    d, g = rows[0]["d"], rows[0]["g"]
    rho_b = float(np.mean([r["rho_b"] for r in rows]))
    k = -b / (a * d)
    dk = math.sqrt(cov[1, 1] / a ** 2 + b ** 2 * cov[0, 0] / a ** 4 - 2.0 * b * cov[0, 1] / a ** 3) / d
    C = a ** exponent / (rho_b * math.sqrt(g))
    dC = exponent * a ** (exponent - 1.0) * math.sqrt(cov[0, 0]) / (rho_b * math.sqrt(g))
    with open(os.path.join(args.sweep, "silo_beverloo.csv"), "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["D", "D_over_d", "discharge_rate", "discharge_rate_error", "bulk_density", "fit_rate", "run"])
        for r in rows:
            out.writerow([r["D"], r["D"] / d, r["W"], r["dW"], r["rho_b"],
                          C * rho_b * math.sqrt(g) * max(0.0, r["D"] - k * d) ** exponent, r["run"]])
    law = "(D - k d)^(5/2)" if exponent == 2.5 else "(D - k d)^(3/2)"
    print(f"{'D/d':>6} {'W':>12} {'+-':>10} {'rho_b':>8}")
    for r in rows:
        print(f"{r['D'] / d:6.2f} {r['W']:12.5g} {r['dW']:10.3g} {r['rho_b']:8.4f}")
    print(f"W = C rho_b sqrt(g) {law}: C = {C:.3f} +- {dC:.3f}, k = {k:.2f} +- {dk:.2f}, "
          f"rho_b = {rho_b:.4f} (bulk density of the bed, solids fraction x particle density)")
    print("published for spheres (3D): C = 0.55-0.65, k = 1.3-1.6 (Beverloo 1961; Nedderman 1992; Mankoc et al. 2007)"
          if exponent == 2.5 else "published for discs (2D): C ~ 1.0-1.1 with the area fraction's density, k ~ 1.0-1.5")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5, 4))
        ax.errorbar(D / d, W, yerr=dW, fmt="o", label="grainflow")
        x = np.linspace(max(k * d, D.min() * 0.8), D.max() * 1.1, 100)
        ax.plot(x / d, C * rho_b * math.sqrt(g) * (x - k * d) ** exponent, "-",
                label=f"C = {C:.2f}, k = {k:.2f}")
        ax.set_xlabel("orifice D / d")
        ax.set_ylabel("discharge rate W")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(args.sweep, "silo_beverloo.png"), dpi=120)
    except ImportError:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
