"""Collision stresses and collision angles of an event-driven run (Campbell 1982 sections 3.3, 3.4.2).

stresses.csv [+ walls.csv] -> stresses.png: the normal stress P_yy and the shear stress -P_yx
    (Campbell's tau_N and tau_s; P_yx < 0 in a flow speeding up with y) per strip against y/H
    (Couette: the stresses' y_over_H; chute: height above the bottom wall over the flow depth):
    collisional, kinetic and total parts (total with its standard error), Campbell's weight-integral
    estimate (weight_yy, weight_yx) as a dashed line where present, and each wall's normal_stress and
    -shear_stress from walls.csv as black markers at the wall.
collision_angles.csv -> collision_angles.png (Figs. 3.32-3.34): the measured density of the angle
    theta of the line of centres against theta, with Savage and Jeffrey's
    P(theta) = (1/pi) erfc(2^-1/2 S cos theta sin theta) at the cell's S (summary's
    savage_jeffrey_S, else the file's comment) and, as Campbell did, at S C/R: the length scale C =
    R (pi/nu)^1/2, the mean spacing of discs at solids fraction nu (spheres: R (4 pi / 3 nu)^1/3),
    instead of R.
"""

import math
import os
import re

import matplotlib.pyplot as plt
import numpy as np

from .common import (dimension, error_bars, existing, number, read_json, read_table, save_atomically,
                     strip_profiles, PlotError)

PARTS = [("collisional", "C0", "s", "collisional"), ("kinetic", "C1", "^", "kinetic"), ("total", "k", "o", "total")]


def plot(outdir, info):
    written = []
    path = existing(outdir, "stresses.csv")
    if path:
        stresses = read_table(path, ["y", "collisional_yy", "kinetic_yy", "total_yy", "collisional_yx",
                                     "kinetic_yx", "total_yx"])
        walls_path = existing(outdir, "walls.csv")
        walls = read_walls(walls_path) if walls_path else None
        written.append(plot_stresses(outdir, info, stresses, walls))
    path = existing(outdir, "collision_angles.csv")
    if path:
        angles = read_table(path, ["theta_deg", "density"])
        written.append(plot_angles(outdir, info, angles))
    return written


def read_walls(path):
    """walls.csv: its numeric columns (the face and axis names are text)."""
    return read_table(path, ["position", "normal_stress", "shear_stress"], text_columns=("wall", "axis"))


def height_scale(stresses, walls, info):
    """(function y -> plotted height, axis label)."""
    if "y_over_H" in stresses and walls is not None and len(walls) >= 2:
        lo, hi = float(np.min(walls["position"])), float(np.max(walls["position"]))
        if hi > lo:  # the walls' planes at the end, as the stresses' y (the strip centres at the end)
            return (lambda y: (y - lo) / (hi - lo)), "y / gap"
    depth = number(info.summary, "flow_depth")
    bottom = float(np.min(walls["position"])) if walls is not None and len(walls) else 0.0
    if depth:
        return (lambda y: (y - bottom) / depth), "y / H"
    return (lambda y: y), "y (m)"


def plot_stresses(outdir, info, stresses, walls):
    to_height, label = height_scale(stresses, walls, info)
    y = to_height(stresses["y"])
    figure, axes = plt.subplots(1, 2, sharey=True, figsize=(10.0, 5.5))
    for a, component, sign, name in ((axes[0], "yy", 1.0, "normal stress P_yy"),
                                     (axes[1], "yx", -1.0, "shear stress \u2212P_yx")):
        for part, colour, marker, text in PARTS:
            values = stresses.get(f"{part}_{component}")
            errors = error_bars(stresses.get(f"{part}_{component}_error")) if part == "total" else None
            a.errorbar(sign * values, y, xerr=errors, color=colour, marker=marker, markersize=3, capsize=2,
                       linewidth=1.4 if part == "total" else 0.9, label=text)
        weight = stresses.get(f"weight_{component}")
        if weight is not None and np.any(np.isfinite(weight)):
            a.plot(sign * weight, y, color="C3", linestyle="--", label="weight integral")
        if walls is not None and len(walls):
            value = walls["normal_stress"] if component == "yy" else walls["shear_stress"]
            errors = error_bars(walls.get("normal_stress_error" if component == "yy" else "shear_stress_error"))
            a.errorbar(sign * value, to_height(walls["position"]), xerr=errors, color="k", marker="D",
                       markersize=7, linestyle="none", markerfacecolor="none", capsize=3, label="walls")
        a.axvline(0.0, color="0.6", linewidth=0.6)
        a.set_xlabel(name + (" (N/m)" if dimension(info) == 2 else " (Pa)"))
        a.grid(True, alpha=0.3)
        a.legend(loc="best", fontsize=8)
    axes[0].set_ylabel(label)
    count = stresses.get("number")
    if count is not None and np.any(count > 0.0) and y.size >= 2:
        # Over a chute the strips reach the domain's top: end the axis above the last strip holding
        # 1% of the fullest one's particles (as strip_profiles.png does with nu).
        last = np.nonzero(count >= 0.01 * np.max(count))[0][-1]
        axes[0].set_ylim(min(0.0, float(np.min(y))) - 0.05, float(y[last] + abs(y[1] - y[0])))
    figure.suptitle(f"{info.name}\nstresses per strip (Campbell 1982 section 3.3): compressive positive; "
                    "bars: standard errors of the totals and the walls", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "stresses.png"))


def savage_jeffrey(theta, s):
    """(1/pi) erfc(S cos(theta) sin(theta) / sqrt 2), theta in radians."""
    return np.array([math.erfc(s * math.cos(t) * math.sin(t) / math.sqrt(2.0)) for t in theta]) / math.pi


def angle_s(angles, info):
    s = number(info.summary, "savage_jeffrey_S")
    if s is None:
        for line in angles.comments:
            match = re.search(r"at S = ([0-9.eE+-]+)", line)
            if match:
                try:
                    s = float(match.group(1))
                except ValueError:
                    pass
    return s


def solids_fraction(info):
    """The flow's nu for Campbell's spacing C: distributions.json's cell value, else the chute's
    depth mean, else the mean over the strips with material; None when unknown."""
    path = existing(info.outdir, "analysis", "distributions.json")
    if path:
        try:
            value = number(read_json(path), "solids_fraction")
        except PlotError:
            value = None  # the distribution figures report it
        if value:
            return value
    value = number(info.summary, "mean_solids_fraction")
    if value:
        return value
    path = strip_profiles(info.outdir)
    if path:
        try:
            nu = read_table(path, ["solids_fraction"])["solids_fraction"]
        except PlotError:
            return None
        nu = nu[np.isfinite(nu) & (nu > 0.0)]
        return float(np.mean(nu)) if nu.size else None
    return None


def spacing_over_radius(nu, dim):
    """C / R: discs R (pi/nu)^1/2 (Campbell), spheres R (4 pi / (3 nu))^1/3 (one particle per C^D)."""
    return math.sqrt(math.pi / nu) if dim == 2 else (4.0 * math.pi / (3.0 * nu)) ** (1.0 / 3.0)


def plot_angles(outdir, info, angles):
    figure, axes = plt.subplots(figsize=(7.0, 5.0))
    theta = angles["theta_deg"]
    axes.plot(theta, angles["density"], linestyle="none", marker="o", markersize=4, color="C0", label="measured")
    curve = np.linspace(0.0, 180.0, 361)
    s = angle_s(angles, info)
    if s is not None:
        axes.plot(curve, savage_jeffrey(np.radians(curve), s), color="k",
                  label=f"Savage\u2013Jeffrey, S = {s:.3g} (length scale R)")
        nu = solids_fraction(info)
        if nu:
            ratio = spacing_over_radius(nu, dimension(info))
            axes.plot(curve, savage_jeffrey(np.radians(curve), s * ratio), color="C3", linestyle="--",
                      label=f"Savage\u2013Jeffrey, S C/R = {s * ratio:.3g} (C = spacing at \u03bd = {nu:.3g})")
    axes.axhline(1.0 / math.pi, color="0.6", linestyle=":", label="isotropic 1/\u03c0")
    axes.set_xlim(0.0, 180.0)
    axes.set_xticks(range(0, 181, 30))
    axes.set_ylim(bottom=0.0)
    axes.set_xlabel("\u03b8: line of centres from the flow direction (\u00b0)")
    axes.set_ylabel("probability density (1/rad)")
    axes.grid(True, alpha=0.3)
    axes.legend(loc="best", fontsize=8)
    figure.suptitle(f"{info.name}\ncollision angles (Campbell 1982 Figs. 3.32-3.34)", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "collision_angles.png"))
