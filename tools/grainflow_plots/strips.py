"""Campbell's (1982) strip profiles of an event-driven run: chute flows (Figs. 3.1, 3.10-3.15) and
Couette cells (Fig. 3.16), and the temperature components (Figs. 3.18-3.19).

profiles.csv (edmd) -> strip_profiles.png: against y/H (chute: height above the bottom over the
    flow depth) or y/gap (Couette), four panels: the mean velocity u/u_max (chute, u_max =
    summary's max_velocity) or u/U_T (Couette); the solids fraction nu with the packing limits of
    sheared discs (0.9069 triangular, 0.8210 contour-following, 0.7854 square; spheres: pi/6 simple
    cubic and 0.7405 close packed) dotted; the translational temperature <v'^2>/D and the rotational
    temperature beta<omega'^2> (Couette: times (H/U_T)^2, Campbell's scaling). Strips flagged
    plug_flow are shaded grey in every panel; error bars from the *_error columns.
profiles.csv (edmd) -> temperature_components.png: <u'^2>, <v'^2> (3D also <w'^2>) and
    beta<omega'^2> per strip (Couette: the *_scaled columns, times (H/U_T)^2).
"""

import math
import os
import re

import matplotlib.pyplot as plt
import numpy as np

from .common import dimension, error_bars, number, read_table, save_atomically, strip_profiles

REQUIRED = ["strip", "y", "solids_fraction", "u", "granular_temperature", "rotational_temperature",
            "u_variance", "v_variance", "plug_flow"]
DISC_LIMITS = [(0.9068996821, "triangular"), (0.8210210539, "contour-following"), (math.pi / 4, "square")]
SPHERE_LIMITS = [(math.pi / (3 * math.sqrt(2)), "close packed"), (math.pi / 6, "simple cubic")]
# Strips with less material than this share of the densest are left off a chute's height axis
# (the few particles thrown above the flow).
SPARSE_SHARE = 0.01


def plot(outdir, info):
    path = strip_profiles(outdir)
    if path is None:
        return []
    profiles = read_table(path, REQUIRED)
    geometry = Geometry(profiles, info)
    return [plot_profiles(outdir, info, profiles, geometry), plot_components(outdir, info, profiles, geometry)]


class Geometry:
    """How the strips are scaled: the height coordinate, the velocity scale and the temperature
    scaling of a chute or a Couette cell (or plain y when the profile says neither)."""

    def __init__(self, profiles, info):
        self.couette = "y_over_gap" in profiles
        self.chute = "y_over_H" in profiles
        if self.couette:
            self.height, self.height_label = profiles["y_over_gap"], "y / gap"
        elif self.chute:
            self.height, self.height_label = profiles["y_over_H"], "y / H"
        else:
            self.height, self.height_label = profiles["y"], "y (m)"
        spacing = np.diff(self.height)
        self.half_strip = 0.5 * float(np.median(spacing)) if spacing.size else 0.5
        self.speed, self.speed_label = self._speed_scale(profiles, info)
        self.scaled = self.couette and "granular_temperature_scaled" in profiles
        solids = profiles["solids_fraction"]
        dense = np.nonzero(solids >= SPARSE_SHARE * np.nanmax(solids, initial=0.0))[0] if solids.size else []
        self.top = float(self.height[dense[-1]] + self.half_strip) if len(dense) else 1.0

    def _speed_scale(self, profiles, info):
        if self.couette:
            u_t = number(info.summary, "shear_speed") or comment_number(profiles, r"U_T = ([0-9.eE+-]+)")
            if u_t:
                return u_t, "u / U_T"
        if self.chute:
            u_max = number(info.summary, "max_velocity")
            if u_max is None:
                below = (profiles["y_over_H"] <= 1.0) & np.isfinite(profiles["u"])
                u_max = float(np.max(profiles["u"][below])) if np.any(below) else None
            if u_max:
                return u_max, "u / u_max"
        return 1.0, "u (m/s)"

    def mark_plug_flow(self, axes, profiles):
        for k in np.nonzero(profiles["plug_flow"] > 0.5)[0]:
            axes.axhspan(self.height[k] - self.half_strip, self.height[k] + self.half_strip, color="0.85", zorder=0)

    def finish(self, axes):
        axes.set_ylim(0.0, max(1.0, self.top) if (self.chute or self.couette) else self.top)
        axes.grid(True, alpha=0.3)


def comment_number(table, pattern):
    """The first number matching `pattern` in the table's comment lines, or None."""
    for line in table.comments:
        match = re.search(pattern, line)
        if match:
            try:
                return float(match.group(1))
            except ValueError:
                return None
    return None


def column_with_error(profiles, name, scale=1.0):
    values = profiles.get(name)
    if values is None:
        return None, None
    errors = error_bars(profiles.get(name + "_error"))
    return values * scale, None if errors is None else errors * abs(scale)


def kind_text(geometry, info):
    if geometry.couette:
        gap, u_t = number(info.summary, "mean_gap"), number(info.summary, "shear_speed")
        return "Couette cell" + (f", H = {gap:.3g}, U_T = {u_t:.3g}" if gap and u_t else "")
    if geometry.chute:
        angle, depth = number(info.summary, "chute_angle"), number(info.summary, "flow_depth")
        fr = number(info.summary, "froude_number")
        parts = [f"{angle:.3g}\u00b0 chute" if angle is not None else "chute"]
        if depth:
            parts.append(f"H = {depth:.3g}")
        if fr:
            parts.append(f"Fr = {fr:.3g}")
        return ", ".join(parts)
    return "strips"


def plot_profiles(outdir, info, profiles, geometry):
    figure, axes = plt.subplots(1, 4, sharey=True, figsize=(13.0, 5.5))
    y = geometry.height
    for a in axes:
        geometry.mark_plug_flow(a, profiles)

    u, u_error = column_with_error(profiles, "u", 1.0 / geometry.speed)
    axes[0].errorbar(u, y, xerr=u_error, color="C0", marker="o", markersize=3, capsize=2)
    axes[0].set_xlabel(geometry.speed_label)

    nu, nu_error = column_with_error(profiles, "solids_fraction")
    axes[1].errorbar(nu, y, xerr=nu_error, color="C3", marker="o", markersize=3, capsize=2, label="\u03bd")
    limits = SPHERE_LIMITS if dimension(info) == 3 else DISC_LIMITS
    for k, (value, name) in enumerate(limits):
        axes[1].axvline(value, color="k", linestyle=":", linewidth=0.8 + 0.3 * k, label=f"{value:.4g} {name}")
    axes[1].set_xlim(0.0, 1.0)
    axes[1].set_xlabel("solids fraction \u03bd")
    axes[1].legend(loc="upper right", fontsize=7, title="plug-flow limits", title_fontsize=7)

    suffix = "_scaled" if geometry.scaled else ""
    unit = " \u00d7 (H/U_T)\u00b2" if geometry.scaled else " (m\u00b2/s\u00b2)"
    t, t_error = column_with_error(profiles, "granular_temperature" + suffix)
    r, r_error = column_with_error(profiles, "rotational_temperature" + suffix)
    axes[2].errorbar(t, y, xerr=t_error, color="C2", marker="o", markersize=3, capsize=2)
    axes[2].set_xlabel("translational temperature \u27e8v\u2032\u00b2\u27e9/D" + unit)
    axes[3].errorbar(r, y, xerr=r_error, color="C4", marker="o", markersize=3, capsize=2)
    axes[3].set_xlabel("rotational temperature \u03b2\u27e8\u03c9\u2032\u00b2\u27e9" + unit)
    for a in axes:
        geometry.finish(a)
    axes[0].set_ylabel(geometry.height_label)
    for a in axes[2:]:
        a.set_xlim(left=0.0)
    note = "plug-flow strips shaded" if np.any(profiles["plug_flow"] > 0.5) else "no plug-flow strips"
    figure.suptitle(f"{info.name}   {kind_text(geometry, info)}\nstrip profiles (Campbell 1982 Figs. 3.1, "
                    f"3.10-3.16); bars: standard errors; {note}", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "strip_profiles.png"))


def plot_components(outdir, info, profiles, geometry):
    figure, axes = plt.subplots(figsize=(6.5, 5.5))
    geometry.mark_plug_flow(axes, profiles)
    suffix = "_scaled" if geometry.scaled else ""
    components = [("u_variance", "\u27e8u\u2032\u00b2\u27e9"), ("v_variance", "\u27e8v\u2032\u00b2\u27e9"),
                  ("w_variance", "\u27e8w\u2032\u00b2\u27e9"),
                  ("rotational_temperature", "\u03b2\u27e8\u03c9\u2032\u00b2\u27e9")]
    for k, (name, label) in enumerate(components):
        values, errors = column_with_error(profiles, name + suffix)
        if values is None:
            continue
        axes.errorbar(values, geometry.height, xerr=errors, color=f"C{k}", marker="os^d"[k], markersize=4,
                      capsize=2, label=label)
    geometry.finish(axes)
    axes.set_xlim(left=0.0)
    axes.set_ylabel(geometry.height_label)
    axes.set_xlabel("temperature component" + (" \u00d7 (H/U_T)\u00b2" if geometry.scaled else " (m\u00b2/s\u00b2)"))
    axes.legend(loc="best", fontsize=8)
    figure.suptitle(f"{info.name}   {kind_text(geometry, info)}\ntemperature components per strip "
                    "(Campbell 1982 Figs. 3.18-3.19)", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "temperature_components.png"))
