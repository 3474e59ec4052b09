"""Followed particles (tracers): rise of a large sphere and its response to the floor (Lan 1994
section 5.3).

tracers.csv -> tracer_height.png: the vertical position of each tracer against time, with the rise
    speed of a linear regression in the legend (Figs. A5.12, A5.13, A5.15).
tracers.csv -> tracer_spectrum.png: each tracer's vertical velocity history and its Welch power
    spectral density with the dominant frequency marked (Fig. A5.14).
tracers.csv -> tracer_coordination.png: coordination number (and wall contacts) and vertical
    velocity over the last floor cycles, against time and against the floor phase (Fig. A5.17).

tracers.csv has the columns time,id,x,y,z,vx,vy,vz,coordination,wall_contacts,floor_position,
floor_velocity, the ids interleaved. The vertical axis is the run's gravity axis (y by default).
"""

import os

import matplotlib.pyplot as plt
import numpy as np

from .common import (dominant_frequency, existing, floor_phase, read_table, save_atomically,
                     welch)

COLUMNS = ["time", "id", "x", "y", "z", "vx", "vy", "vz", "coordination", "wall_contacts", "floor_position",
           "floor_velocity"]
MAX_SPECTRA = 4      # tracers with their own spectrum panels
PHASE_CYCLES = 4     # floor cycles of the coordination figure


def plot(outdir, info):
    path = existing(outdir, "tracers.csv")
    if path is None:
        return []
    table = read_table(path, COLUMNS)
    if len(table) == 0:
        return []
    tracers = split(table)
    return [plot_height(outdir, info, tracers, table),
            plot_spectrum(outdir, info, tracers),
            plot_coordination(outdir, info, tracers)]


def split(table):
    """{id: {column: values sorted by time}} in order of first appearance."""
    ids = table["id"].astype(np.int64)
    order = list(dict.fromkeys(ids.tolist()))
    tracers = {}
    for i in order:
        rows = np.nonzero(ids == i)[0]
        rows = rows[np.argsort(table["time"][rows], kind="stable")]
        tracers[i] = {name: table[name][rows] for name in COLUMNS}
    return tracers


def rise_speed(time, height):
    """Slope of the least-squares line height(t) (m/s), None with fewer than two times."""
    if time.size < 2 or np.ptp(time) <= 0.0:
        return None
    return float(np.polyfit(time, height, 1)[0])


def plot_height(outdir, info, tracers, table):
    scale, unit = info.length_scale()
    v = info.vertical
    figure, axes = plt.subplots(figsize=(9.0, 5.5))
    for k, (i, t) in enumerate(tracers.items()):
        speed = rise_speed(t["time"], t[v])
        label = f"id {i}" + ("" if speed is None else f": rise {speed:.3g} m/s")
        axes.plot(t["time"], scale * t[v], color=f"C{k % 10}", linewidth=1.0, label=label)
        if speed is not None:
            intercept = float(np.mean(t[v] - speed * t["time"]))
            axes.plot(t["time"], scale * (intercept + speed * t["time"]), color=f"C{k % 10}", linestyle="--",
                      linewidth=0.8)
    floor = table["floor_position"]
    if np.any(floor != 0.0):
        first = next(iter(tracers.values()))
        axes.plot(first["time"], scale * first["floor_position"], color="0.55", linewidth=0.6, label="floor")
    axes.set_xlabel("time (s)")
    axes.set_ylabel(f"{v} {unit}" if unit == "/ d" else f"{v} (m)")
    axes.legend(loc="best", fontsize=8, title="dashed: linear regression", title_fontsize=8)
    axes.grid(True, alpha=0.3)
    figure.suptitle(info.title() + "\ntracer trajectories (Lan Figs. A5.12, A5.13, A5.15)", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "tracer_height.png"))


def uniform(time, values):
    """(interval, values on a uniform grid): the samples as they are when evenly spaced, else
    linearly interpolated onto the median spacing."""
    steps = np.diff(time)
    interval = float(np.median(steps)) if steps.size else 0.0
    if interval <= 0.0:
        return 0.0, values
    if np.all(np.abs(steps - interval) <= 0.01 * interval):
        return interval, values
    grid = np.arange(time[0], time[-1] + 0.5 * interval, interval)
    return interval, np.interp(grid, time, values)


def plot_spectrum(outdir, info, tracers):
    v = info.vertical
    shown = list(tracers.items())[:MAX_SPECTRA]
    figure, axes = plt.subplots(len(shown), 2, figsize=(11.0, 1.2 + 2.6 * len(shown)), squeeze=False)
    for k, (i, t) in enumerate(shown):
        history, spectrum = axes[k]
        velocity = t["v" + v]
        history.plot(t["time"], velocity, color=f"C{k % 10}", linewidth=0.7)
        history.set_ylabel(f"v_{v} of id {i} (m/s)")
        interval, samples = uniform(t["time"], velocity)
        frequency, psd = welch(samples, interval) if interval > 0.0 else (np.zeros(0), np.zeros(0))
        peak = dominant_frequency(frequency, psd)
        positive = (frequency > 0.0) & (psd > 0.0)
        if np.any(positive):
            spectrum.semilogy(frequency[positive], psd[positive], color=f"C{k % 10}", linewidth=0.9)
            spectrum.set_ylim(bottom=1e-9 * float(psd.max()))  # nine decades below the peak
            spectrum.axvline(peak, color="C3", linestyle="--", linewidth=0.9,
                             label=f"dominant {peak:.3g} Hz (bins {frequency[1]:.2g} Hz apart)")
            if info.drive_frequency:
                spectrum.axvline(info.drive_frequency, color="0.4", linestyle=":", linewidth=0.9,
                                 label=f"floor {info.drive_frequency:.3g} Hz")
                spectrum.set_xlim(0.0, min(float(frequency.max()), 8.0 * info.drive_frequency))
            spectrum.legend(loc="upper right", fontsize=8)
        else:
            spectrum.text(0.5, 0.5, "too few samples for a spectrum", ha="center", va="center",
                          transform=spectrum.transAxes)
        spectrum.set_ylabel("PSD ((m/s)\u00b2/Hz)")
        for a in (history, spectrum):
            a.grid(True, which="both", alpha=0.25)
    axes[-1, 0].set_xlabel("time (s)")
    axes[-1, 1].set_xlabel("frequency (Hz)")
    more = len(tracers) - len(shown)
    figure.suptitle(info.title() + "\nvertical velocity history and Welch spectrum (Lan Fig. A5.14)"
                    + (f"; {more} more tracers not shown" if more > 0 else ""), fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "tracer_spectrum.png"))


def last_cycles(phase):
    """Rows of the last PHASE_CYCLES complete floor cycles (a cycle starts at phase 0) and each
    row's cycle number; (all rows, zeros) when fewer cycles were recorded."""
    cycle = np.floor(np.unwrap(phase) / (2.0 * np.pi)).astype(int)
    complete = np.unique(cycle)[1:-1]  # the first and last cycles are cut by the record's ends
    if complete.size == 0:
        return np.ones(phase.size, dtype=bool), np.zeros(phase.size, dtype=int)
    keep = np.isin(cycle, complete[-PHASE_CYCLES:])
    return keep, cycle


def plot_coordination(outdir, info, tracers):
    v = info.vertical
    first = next(iter(tracers.values()))
    phase = floor_phase(first["floor_position"], first["floor_velocity"])
    columns = 2 if phase is not None else 1
    figure, axes = plt.subplots(2, columns, figsize=(6.0 * columns, 7.0), squeeze=False, sharey="row")
    for k, (i, t) in enumerate(tracers.items()):
        colour = f"C{k % 10}"
        own_phase = floor_phase(t["floor_position"], t["floor_velocity"]) if phase is not None else None
        if own_phase is not None:
            keep, cycle = last_cycles(own_phase)
        else:
            keep, cycle = np.ones(t["time"].size, dtype=bool), np.zeros(t["time"].size, dtype=int)
        time = t["time"][keep]
        axes[0, 0].step(time, t["coordination"][keep], where="post", color=colour, linewidth=0.9, label=f"id {i}")
        if np.any(t["wall_contacts"][keep] != 0):
            axes[0, 0].step(time, t["wall_contacts"][keep], where="post", color=colour, linestyle=":", linewidth=0.8,
                            label=f"id {i}: wall contacts")
        axes[1, 0].plot(time, t["v" + v][keep], color=colour, linewidth=0.9)
        if own_phase is None:
            continue
        for c in np.unique(cycle[keep]):
            rows = keep & (cycle == c)
            order = np.argsort(own_phase[rows])
            axes[0, 1].plot(own_phase[rows][order], t["coordination"][rows][order], color=colour, alpha=0.7,
                            linewidth=0.8, marker=".", markersize=3)
            axes[1, 1].plot(own_phase[rows][order], t["v" + v][rows][order], color=colour, alpha=0.7,
                            linewidth=0.8, marker=".", markersize=3)
    if np.any(first["floor_velocity"] != 0.0):  # the floor for reference
        keep = last_cycles(phase)[0] if phase is not None else np.ones(first["time"].size, dtype=bool)
        axes[1, 0].plot(first["time"][keep], first["floor_velocity"][keep], color="0.55", linewidth=0.7,
                        label="floor")
        axes[1, 0].legend(loc="upper right", fontsize=8)
    axes[0, 0].set_ylabel("coordination number")
    axes[1, 0].set_ylabel(f"v_{v} (m/s)")
    axes[1, 0].set_xlabel("time (s)")
    axes[0, 0].legend(loc="upper right", fontsize=7)
    if columns == 2:
        ticks = np.arange(0, 9) * np.pi / 4
        for a in axes[:, 1]:
            a.set_xticks(ticks, ["0", "\u03c0/4", "\u03c0/2", "3\u03c0/4", "\u03c0", "5\u03c0/4", "3\u03c0/2",
                                 "7\u03c0/4", "2\u03c0"])
            a.set_xlim(0.0, 2.0 * np.pi)
        axes[1, 1].set_xlabel("floor phase \u03c6 (y_b = a sin \u03c6)")
        axes[0, 1].set_title(f"last {PHASE_CYCLES} complete floor cycles, overlaid", fontsize=9)
    for a in axes.flat:
        a.grid(True, alpha=0.3)
    figure.suptitle(info.title() + "\ncoordination number and velocity of the tracers (Lan Fig. A5.17)",
                    fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "tracer_coordination.png"))
