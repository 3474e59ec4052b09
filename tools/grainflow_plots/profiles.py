"""Depth profiles of one run (Lan 1994, Figs. A4.1-A4.4, A4.7, A4.15, A4.18-A4.19) and the mass
below a depth (Fig. A4.9).

profiles.csv [+ analysis/kinetic_theory.csv] -> profiles.png: W(Y) and nu(Y) against Y = y/d, with
    the block-averaging error bars (W_error, solids_fraction_error) when the profile has them and the
    kinetic theory's W(Y), nu(Y) as lines when analysis/kinetic_theory.csv exists.
profiles.csv -> mass_below.png: the share of the integral of nu dY below each Y (from the floor up).
"""

import os

import matplotlib.pyplot as plt
import numpy as np

from .common import error_bars, existing, read_table, save_atomically, zone_profiles

# W of a zone is drawn as a line only where the zone holds on average at least this many
# particles: a particle alone in a zone has no fluctuation about the instantaneous zone mean, so
# Lan's temperature is biased low (to zero) in sparse zones. Those zones get hollow markers.
SPARSE_ZONE_PARTICLES = 1.0
# Without the particle count in summary.json: sparse = solids fraction below this share of its peak.
SPARSE_ZONE_FRACTION = 0.01

PROFILE_COLUMNS = ["position_lo", "position_hi", "position", "Y", "solids_fraction", "temperature",
                   "temperature_time_mean", "W"]
KINETIC_THEORY_COLUMNS = ["Y", "solids_fraction", "W"]
THEORY_STYLE = {"color": "k", "linestyle": "-", "linewidth": 1.2, "label": "kinetic theory"}


def plot(outdir, info):
    path = zone_profiles(outdir)
    if path is None:
        return []
    profiles = read_table(path, PROFILE_COLUMNS)
    theory_path = existing(outdir, "analysis", "kinetic_theory.csv")
    theory = read_table(theory_path, KINETIC_THEORY_COLUMNS) if theory_path else None
    written = [plot_profiles(outdir, info, profiles, theory)]
    curve = mass_below(profiles)
    if curve is not None:
        written.append(plot_mass_below(outdir, info, curve, theory))
    return written


def occupied_zones(profiles):
    """Index one past the last zone with material (empty zones above the bed are left out)."""
    occupied = np.nonzero(profiles["solids_fraction"] > 0.0)[0]
    return occupied[-1] + 1 if occupied.size else 0


def mass_below(profiles):
    """(Y at the zone tops, with the lowest zone's bottom first; share of the integral of nu dY
    below each), or None without material. Lan's Fig. A4.9 in fractions of the total."""
    count = occupied_zones(profiles)
    if count == 0:
        return None
    lo, hi = profiles["position_lo"][:count], profiles["position_hi"][:count]
    mass = profiles["solids_fraction"][:count] * (hi - lo)
    total = float(np.sum(mass))
    d = profile_scale(profiles)
    if total <= 0.0 or d is None:
        return None
    return np.concatenate([[lo[0]], hi]) / d, np.concatenate([[0.0], np.cumsum(mass)]) / total


def theory_mass_below(theory):
    """The same share for the kinetic theory's nu(Y) (trapezoid rule on its own Y grid)."""
    y, nu = theory["Y"], theory["solids_fraction"]
    if y.size < 2:
        return None
    order = np.argsort(y)
    y, nu = y[order], nu[order]
    cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (nu[1:] + nu[:-1]) * np.diff(y))])
    return (y, cumulative / cumulative[-1]) if cumulative[-1] > 0.0 else None


def profile_scale(profiles):
    """d = position / Y (None when the profile does not tell)."""
    y, position = profiles["Y"], profiles["position"]
    ratio = np.divide(position, y, out=np.zeros_like(y), where=y != 0)
    ratio = ratio[np.isfinite(ratio) & (ratio > 0)]
    return float(np.median(ratio)) if ratio.size else None


def profile_gravity(profiles):
    """g recovered from the profile itself (W^2 = T / (g d)), so no case file is needed."""
    t, w, y, position = profiles["temperature"], profiles["W"], profiles["Y"], profiles["position"]
    usable = (w > 0) & (t > 0) & (y > 0)
    if not np.any(usable):
        return 0.0
    d = position[usable] / y[usable]
    return float(np.median(t[usable] / (w[usable] ** 2 * d)))


def dense_zones(particles, solids, thickness):
    """Zones holding enough particles for W; and the legend text for the others. The mean number of
    particles in a zone is N times the zone's share of the integral of nu over the depth."""
    integral = float(np.sum(solids * thickness))
    if isinstance(particles, int) and particles > 0 and integral > 0.0:
        occupancy = particles * solids * thickness / integral
        return occupancy >= SPARSE_ZONE_PARTICLES, f"sparse zones (< {SPARSE_ZONE_PARTICLES:g} particle on average)"
    return (solids >= SPARSE_ZONE_FRACTION * solids.max(),
            f"sparse zones (\u03bd < {SPARSE_ZONE_FRACTION:g} \u00d7 peak)")


def plot_profiles(outdir, info, profiles, theory):
    figure, (left, right) = plt.subplots(1, 2, sharey=True, figsize=(8.0, 6.0))
    title = info.name
    count = occupied_zones(profiles)
    d = profile_scale(profiles)
    if count == 0:
        for axes in (left, right):
            axes.text(0.5, 0.5, "no profile samples\n(is output.average_start\nafter the end of the run?)",
                      ha="center", va="center", transform=axes.transAxes)
    else:
        def column(name):
            values = profiles.get(name)
            return values[:count] if values is not None else None

        y, solids, w = column("Y"), column("solids_fraction"), column("W")
        lo, hi = column("position_lo"), column("position_hi")
        w_error, solids_error = error_bars(column("W_error")), error_bars(column("solids_fraction_error"))
        dense, sparse_label = dense_zones(info.particles, solids, hi - lo)

        # W from the temperature about the long-term zone mean velocity: it includes the zone's
        # periodic mean motion (the floor's drive), so it lies above Lan's W.
        g = profile_gravity(profiles)
        if g > 0.0 and d:
            w_campbell = np.sqrt(np.maximum(column("temperature_time_mean"), 0.0) / (g * d))
            left.plot(w_campbell[dense], y[dense], linestyle="--", color="0.6", marker="s", markersize=3,
                      label="about the time-mean velocity")
        left.errorbar(w[dense], y[dense], xerr=None if w_error is None else w_error[dense], color="C0", marker="o",
                      markersize=4, capsize=2, label="about the instantaneous zone mean (Lan)")
        if np.any(~dense):
            left.plot(w[~dense], y[~dense], linestyle="none", marker="o", markersize=4, markerfacecolor="none",
                      color="0.7", label=sparse_label)
        right.errorbar(solids, y, xerr=solids_error, color="C3", marker="o", markersize=4, capsize=2,
                       label="simulation")
        if theory is not None:
            left.plot(theory["W"], theory["Y"], **THEORY_STYLE)
            right.plot(theory["solids_fraction"], theory["Y"], **THEORY_STYLE)
            right.legend(loc="upper right", fontsize=8)
        left.legend(loc="upper center", bbox_to_anchor=(0.5, -0.11), fontsize=8, ncol=1, frameon=False,
                    title="W from the temperature" + (" (bars: standard errors)" if w_error is not None else ""),
                    title_fontsize=8)
        right.set_xlim(0.0, max(0.65, 1.05 * float(np.nanmax(solids))))
        if d:
            held = float(np.sum(solids * (hi - lo)) / d)  # m_t = integral of nu dY (eq. 4-1-3)
            title += f"   \u222b\u03bd dY = {held:.3g}"
        left.set_ylim(0.0, float(hi[-1] / d) if d else float(y[-1]) + 0.5)
        left.set_xlim(left=0.0)
    drive = info.drive_text()
    if drive:
        title += "   " + drive
    samples = info.summary.get("profile_samples")
    if isinstance(samples, int):
        title += f"\n(long-term averages over {samples} samples)"
    figure.suptitle(title, fontsize=11)
    left.set_xlabel("W = \u221a(T / g d)")
    left.set_ylabel("Y = y / d")
    right.set_xlabel("solids fraction \u03bd")
    for axes in (left, right):
        axes.grid(True, alpha=0.3)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "profiles.png"))


def draw_mass_below(axes, curve, **style):
    """One mass-below curve, percent on x against Y on y (like the depth profiles)."""
    y, share = curve
    axes.plot(100.0 * share, y, **style)


def finish_mass_below_axes(axes, lowest=0.0):
    """Labels and limits; `lowest`: the lowest Y drawn (zones may start below the floor's rest)."""
    axes.axvline(50.0, color="0.6", linestyle=":", linewidth=0.8)
    axes.set_xlim(0.0, 100.0)
    axes.set_ylim(bottom=min(0.0, lowest))
    axes.set_xlabel("mass below Y (% of \u222b\u03bd dY)")
    axes.set_ylabel("Y = y / d")
    axes.grid(True, alpha=0.3)


def plot_mass_below(outdir, info, curve, theory):
    figure, axes = plt.subplots(figsize=(5.5, 6.0))
    draw_mass_below(axes, curve, color="C3", marker="o", markersize=3, label="simulation")
    theory_curve = theory_mass_below(theory) if theory is not None else None
    if theory_curve is not None:
        draw_mass_below(axes, theory_curve, color="k", linewidth=1.2, label="kinetic theory")
    y, share = curve
    half = float(np.interp(0.5, share, y))
    axes.axhline(half, color="0.6", linestyle=":", linewidth=0.8)
    axes.annotate(f"half the mass below Y = {half:.3g}", (50.0, half), xytext=(4, 4), textcoords="offset points",
                  fontsize=8)
    finish_mass_below_axes(axes, float(y[0]))
    axes.legend(loc="lower right", fontsize=8)
    figure.suptitle(info.title() + "\nmass below depth Y (Lan Fig. A4.9)", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "mass_below.png"))
