"""Silos and hoppers discharging ([[outlet]]): the discharge curve of one run and Beverloo's law
over a sweep of orifice sizes.

discharge.csv -> discharge.png: each outlet's cumulative discharged mass against time, with the
    steady rate summary.json gives drawn over its window.
a sweep folder whose runs have a holed plane and a discharge rate -> silo_beverloo.png and
    silo_beverloo.csv: the rate against the orifice D with the fit W = C rho_b sqrt(g) (D - k d)^(5/2)
    (3D; ^(3/2) for discs), as the straight line W^(2/5) = a (D - k d) weighted by each rate's error
    (tools/silo_analysis.py prints the fit).
"""

import csv
import glob
import json
import math
import os
import tomllib

import matplotlib.pyplot as plt
import numpy as np

from .common import PlotError, existing, read_table, save_atomically

# Published for spheres: Beverloo, Leniger & van de Velde (1961); Nedderman (1992); Mankoc et al. (2007).
PUBLISHED_3D = "published for spheres (3D): C = 0.55-0.65, k = 1.3-1.6 (Beverloo 1961; Nedderman 1992; Mankoc et al. 2007)"
PUBLISHED_2D = "published for discs (2D): C ~ 1.0-1.1 with the area fraction's density, k ~ 1.0-1.5 (Mankoc et al. 2007)"


def plot(outdir, info):
    written = []
    path = existing(outdir, "discharge.csv")
    if path is not None:
        written.append(plot_discharge(outdir, path, info))
    if existing(outdir, "sweep.json") is not None:
        rows = sweep_rows(outdir)
        if len(rows) >= 3:
            written.append(plot_beverloo(outdir, rows))
    return written


def plot_discharge(outdir, path, info):
    table = read_table(path, ["time", "removed_mass"], text_columns=["outlet"])
    if len(table) == 0:
        raise PlotError(f"{path}: no data rows")
    with open(path, newline="") as f:  # the outlets' names: read_table leaves text out
        outlets = [r["outlet"] for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    figure, axes = plt.subplots(figsize=(6.0, 4.0))
    for name in sorted(set(outlets)):
        mine = np.array([o == name for o in outlets])
        axes.plot(table["time"][mine], table["removed_mass"][mine], label=name)
    summary = info.summary
    if "discharge_rate" in summary:
        t0, t1, rate = summary["discharge_window_start"], summary["discharge_window_end"], summary["discharge_rate"]
        total = np.zeros(len(set(table["time"])))
        times = np.array(sorted(set(table["time"])))
        for k, t in enumerate(times):
            total[k] = np.sum(table["removed_mass"][table["time"] == t])
        middle = np.interp(0.5 * (t0 + t1), times, total)
        axes.plot([t0, t1], [middle - 0.5 * rate * (t1 - t0), middle + 0.5 * rate * (t1 - t0)], "k--",
                  label=f"steady rate {rate:.4g} ± {summary.get('discharge_rate_error', 0.0):.2g}")
    if summary.get("clogged"):
        axes.axvline(summary.get("clogged_at", table["time"][-1]), color="C3", linewidth=0.8, label="clogged")
    axes.set_xlabel("time")
    axes.set_ylabel("discharged mass")
    axes.legend()
    axes.grid(True, alpha=0.3)
    figure.suptitle(info.title(), fontsize=11)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "discharge.png"))


def sweep_rows(sweep, bed_radius=7.0, bed_z=(5.0, 15.0)):
    """Per run of `sweep` with a holed plane and a discharge rate: D, d, W, dW, rho_b, g, dimension."""
    rows = []
    for run in sorted(glob.glob(os.path.join(sweep, "*"))):
        summary_path, case_path = existing(run, "summary.json"), existing(run, "resolved_case.toml")
        if summary_path is None or case_path is None:
            continue
        summary = json.load(open(summary_path))
        with open(case_path, "rb") as f:
            case = tomllib.load(f)
        holes = [g["hole_radius"] for g in case.get("geometry", []) if "hole_radius" in g]
        if not holes or "discharge_rate" not in summary:
            continue
        dimension = case.get("engine", {}).get("dimension", 3)
        species = case["species"][0]
        has_bed = any("bed_lo" in o for o in case.get("outlet", []))
        fraction = summary.get("bulk_solids_fraction") if has_bed else None
        if fraction is None:  # runs without an outlet bed box: the final state's
            fraction = final_state_fraction(run, bed_radius, bed_z, dimension)
        g = math.sqrt(sum(v * v for v in case.get("gravity", {}).get("vector", [0.0, -9.81, 0.0])))
        rows.append(dict(run=os.path.basename(run), D=2.0 * holes[0], d=species["diameter"],
                         W=summary["discharge_rate"], dW=max(summary["discharge_rate_error"], 1e-12),
                         rho_b=fraction * species["density"], g=g, dimension=dimension))
    return sorted(rows, key=lambda r: r["D"])


def final_state_fraction(run, radius, z_range, dimension):
    solid = 0.0
    with open(os.path.join(run, "final_state.csv")) as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            x, y, z, d = float(r["x"]), float(r["y"]), float(r["z"]), float(r["diameter"])
            if z_range[0] < z < z_range[1] and math.hypot(x, y) < radius:
                solid += math.pi * d ** 3 / 6.0 if dimension == 3 else math.pi * d * d / 4.0
    span = z_range[1] - z_range[0]
    return solid / (math.pi * radius ** 2 * span if dimension == 3 else 2.0 * radius * span)


def beverloo_fit(rows):
    """C, dC, k, dk, rho_b, exponent of W = C rho_b sqrt(g) (D - k d)^exponent over `rows`."""
    D, W, dW = (np.array([r[key] for r in rows]) for key in ("D", "W", "dW"))
    exponent = 2.5 if rows[0]["dimension"] == 3 else 1.5
    y = W ** (1.0 / exponent)
    dy = dW * y / (exponent * W)
    w = 1.0 / dy ** 2
    A = np.vstack([D, np.ones_like(D)]).T
    cov = np.linalg.inv(A.T @ (A * w[:, None]))
    a, b = cov @ (A.T @ (w * y))
    chi2 = float(np.sum(w * (y - (a * D + b)) ** 2))
    cov = cov * max(1.0, chi2 / max(1, len(D) - 2))  # scaled up when the scatter exceeds the error bars
    d, g = rows[0]["d"], rows[0]["g"]
    rho_b = float(np.mean([r["rho_b"] for r in rows]))
    k = -b / (a * d)
    dk = math.sqrt(max(0.0, cov[1, 1] / a ** 2 + b ** 2 * cov[0, 0] / a ** 4 - 2.0 * b * cov[0, 1] / a ** 3)) / d
    C = a ** exponent / (rho_b * math.sqrt(g))
    dC = exponent * a ** (exponent - 1.0) * math.sqrt(cov[0, 0]) / (rho_b * math.sqrt(g))
    return C, dC, k, dk, rho_b, exponent


def plot_beverloo(sweep, rows):
    C, dC, k, dk, rho_b, exponent = beverloo_fit(rows)
    d, g = rows[0]["d"], rows[0]["g"]
    with open(os.path.join(sweep, "silo_beverloo.csv"), "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["D", "D_over_d", "discharge_rate", "discharge_rate_error", "bulk_density", "fit_rate", "run"])
        for r in rows:
            out.writerow([r["D"], r["D"] / d, r["W"], r["dW"], r["rho_b"],
                          C * rho_b * math.sqrt(g) * max(0.0, r["D"] - k * d) ** exponent, r["run"]])
    D = np.array([r["D"] for r in rows])
    figure, axes = plt.subplots(figsize=(5.5, 4.0))
    axes.errorbar(D / d, [r["W"] for r in rows], yerr=[r["dW"] for r in rows], fmt="o", label="grainflow")
    x = np.linspace(max(k * d, 0.8 * D.min()), 1.1 * D.max(), 100)
    axes.plot(x / d, C * rho_b * math.sqrt(g) * np.clip(x - k * d, 0.0, None) ** exponent, "-",
              label=f"C = {C:.3f} ± {dC:.3f}, k = {k:.2f} ± {dk:.2f}")
    axes.set_xlabel("orifice D / d")
    axes.set_ylabel("discharge rate W (mass per time)")
    axes.set_title("Beverloo: W = C ρ_b √g (D − k d)^" + ("5/2" if exponent == 2.5 else "3/2"), fontsize=10)
    axes.legend()
    axes.grid(True, alpha=0.3)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(sweep, "silo_beverloo.png"))
