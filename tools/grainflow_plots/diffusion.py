"""Velocity autocorrelation and mean-square displacement of one run (Lan 1994 section 4.4).

analysis/vacf.csv [+ analysis/diffusion.json] -> vacf.png: the components C_x, C_y, C_z of the
    velocity autocorrelation against the lag time (Figs. A4.16, A4.17, A4.20-A4.22, A4.25) and their
    running integrals D_a(tau), whose plateaus are the diffusion coefficients (eq. 4-4-2).
analysis/msd.csv [+ analysis/diffusion.json] -> msd.png: the total mean-square displacement with its
    fitted limiting slope 6 D (Fig. A4.26) and the components with slopes 2 D_a (Fig. A4.27).
"""

import os

import matplotlib.pyplot as plt
import numpy as np

from .common import AXES, existing, number, read_json, read_table, save_atomically

COLOURS = {"x": "C0", "y": "C3", "z": "C2"}


def plot(outdir, info):
    json_path = existing(outdir, "analysis", "diffusion.json")
    diffusion = read_json(json_path) if json_path else {}
    written = []
    vacf_path = existing(outdir, "analysis", "vacf.csv")
    if vacf_path:
        vacf = read_table(vacf_path, ["time", "vacf_x", "vacf_y", "vacf_z"])
        if len(vacf):
            written.append(plot_vacf(outdir, info, vacf, diffusion))
    msd_path = existing(outdir, "analysis", "msd.csv")
    if msd_path:
        msd = read_table(msd_path, ["time", "msd_x", "msd_y", "msd_z", "msd"])
        if len(msd):
            written.append(plot_msd(outdir, info, msd, diffusion))
    return written


def component_label(axis, info):
    return f"{axis}" + (" (shaking)" if axis == info.vertical else "")


def d_text(diffusion, kind, axis):
    """'D = 1.2e-4 ± 3e-6 m²/s' from diffusion.json's d_<kind>_<axis>(_error), or ''."""
    value = number(diffusion, f"d_{kind}_{axis}")
    if value is None:
        return ""
    error = number(diffusion, f"d_{kind}_{axis}_error")
    return f"D = {value:.3g}" + (f" \u00b1 {error:.2g}" if error else "") + " m\u00b2/s"


def cycles_axis(axes, info):
    """A top axis in floor cycles when the drive frequency is known (the y component's wiggles)."""
    f = info.drive_frequency
    if f:
        top = axes.secondary_xaxis("top", functions=(lambda t: t * f, lambda n: n / f))
        top.set_xlabel("floor cycles", fontsize=8)


def plot_vacf(outdir, info, vacf, diffusion):
    time = vacf["time"]
    has_running = all(f"running_d_{a}" in vacf for a in AXES)
    figure, axes = plt.subplots(2 if has_running else 1, 1, sharex=True, squeeze=False,
                                figsize=(8.0, 7.5 if has_running else 4.5))
    correlation = axes[0, 0]
    for a in AXES:
        correlation.plot(time, vacf[f"vacf_{a}"], color=COLOURS[a], label=f"C_{a}  {component_label(a, info)}")
    correlation.axhline(0.0, color="0.5", linewidth=0.7)
    correlation.set_ylabel("\u27e8v_a(t+\u03c4) v_a(t)\u27e9 (m\u00b2/s\u00b2)")
    correlation.legend(loc="upper right", fontsize=8)
    cycles_axis(correlation, info)
    if has_running:
        running = axes[1, 0]
        for a in AXES:
            running.plot(time, vacf[f"running_d_{a}"], color=COLOURS[a],
                         label=f"D_{a}(\u03c4)   {d_text(diffusion, 'vacf', a)}")
        running.axhline(0.0, color="0.5", linewidth=0.7)
        running.set_ylabel("running integral\n\u222b\u2080^\u03c4 C_a dt (m\u00b2/s)")
        running.legend(loc="best", fontsize=8, title="plateau = D_a (eq. 4-4-2)", title_fontsize=8)
    axes[-1, 0].set_xlabel("lag time \u03c4 (s)")
    for a in axes[:, 0]:
        a.grid(True, alpha=0.3)
    figure.suptitle(info.title() + "\nvelocity autocorrelation (Lan Figs. A4.16-A4.22)", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "vacf.png"))


def fit_window(msd, diffusion):
    """Rows of the MSD fit (diffusion.json's msd_fit_first_lag..last_lag; else the second half)."""
    lag = msd.get("lag")
    first, last = number(diffusion, "msd_fit_first_lag"), number(diffusion, "msd_fit_last_lag")
    if lag is not None and first is not None and last is not None:
        rows = (lag >= first) & (lag <= last)
        if np.count_nonzero(rows) >= 2:
            return rows
    rows = np.zeros(len(msd), dtype=bool)
    rows[len(msd) // 2:] = True
    return rows


def slope_line(axes, time, values, rows, slope, colour, label):
    """The line of a given slope through the fit window (least-squares intercept), dashed."""
    if slope is None or np.count_nonzero(rows) < 1:
        return
    intercept = float(np.mean(values[rows] - slope * time[rows]))
    axes.plot(time, intercept + slope * time, color=colour, linestyle="--", linewidth=1.0, label=label)
    axes.axvspan(time[rows][0], time[rows][-1], color="0.94", zorder=0)


def plot_msd(outdir, info, msd, diffusion):
    time = msd["time"]
    rows = fit_window(msd, diffusion)
    figure, (total, parts) = plt.subplots(1, 2, figsize=(11.0, 4.8))

    total.plot(time, msd["msd"], color="k", label="\u27e8|r|\u00b2\u27e9")
    d_total = number(diffusion, "d_msd_total")
    slope_line(total, time, msd["msd"], rows, None if d_total is None else 6.0 * d_total, "C1",
               f"slope 6D, {d_text(diffusion, 'msd', 'total')}")
    total.set_title("total (Lan Fig. A4.26)", fontsize=9)
    total.set_ylabel("mean-square displacement (m\u00b2)")

    for a in AXES:
        values = msd[f"msd_{a}"]
        parts.plot(time, values, color=COLOURS[a], label=f"\u27e8\u0394{a}\u00b2\u27e9  {component_label(a, info)}")
        d = number(diffusion, f"d_msd_{a}")
        slope_line(parts, time, values, rows, None if d is None else 2.0 * d, COLOURS[a],
                   f"slope 2D_{a}, {d_text(diffusion, 'msd', a)}")
    parts.set_title("components (Lan Fig. A4.27); shaded: fit window", fontsize=9)
    for a in (total, parts):
        a.set_xlabel("time (s)")
        a.legend(loc="upper left", fontsize=7)
        a.grid(True, alpha=0.3)
        a.set_xlim(left=0.0)
        a.set_ylim(bottom=0.0)
    figure.suptitle(info.title() + "\nmean-square displacement and limiting slopes", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "msd.png"))
