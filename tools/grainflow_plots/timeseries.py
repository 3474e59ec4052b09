"""Time series of one run: the approach to the steady state behind Lan 1994's long-term averages
(section 4.1; the quantities of Figs. A4.5, A4.6, A4.11, A4.12 as they evolve in one run).

timeseries.csv -> timeseries.png, one panel per group of columns present:
    kinetic (and rotational) energy; granular temperature (Lan's cell average, `cell_temperature`:
    the same for DEM runs) and the zones' temperature about their instantaneous means
    (`zone_temperature`); mass-centre height, floor position and bed height (`bed_height`), in
    diameters when d is known; bulk solids fraction (`bulk_solids_fraction`); cumulative collisions
    (`collisions`) with the rate per particle; pressure (event-driven runs); maximum overlap / d with
    Lan's 1% limit. Only `time` is required, so event-driven runs plot too.
"""

import os

import matplotlib.pyplot as plt
import numpy as np

from .common import PlotError, existing, read_table, save_atomically

# Lan's halt criterion for the overlap monitor (sections 2.5, 4.1.3): 1% of a diameter.
LAN_OVERLAP_LIMIT = 0.01


def plot(outdir, info):
    path = existing(outdir, "timeseries.csv")
    if path is None:
        return []
    series = read_table(path, ["time"])
    if len(series) == 0:
        raise PlotError(f"{path}: no data rows")
    panels = [panel for panel in PANELS if any(name in series for name in panel[0])]
    if not panels:
        return []
    figure, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(8.0, 1.2 + 2.1 * len(panels)),
                                squeeze=False)
    axes = axes[:, 0]
    for (_, draw), a in zip(panels, axes):
        draw(a, series, info)
        a.grid(True, alpha=0.3)
        if info.drive_start is not None:
            a.axvline(info.drive_start, color="0.75", linewidth=0.8)
            if info.drive_ramp and info.drive_ramp > 0.0:
                a.axvspan(info.drive_start, info.drive_start + info.drive_ramp, color="0.92", zorder=0)
    axes[-1].set_xlabel("time (s)")
    title = info.title()
    errors = info.summary.get("errors")
    if isinstance(errors, list) and errors:
        title += "   (run failed: see summary.json errors)"
    figure.suptitle(title, fontsize=11)
    figure.tight_layout()
    return [save_atomically(figure, os.path.join(outdir, "timeseries.png"))]


def energy(axes, series, info):
    time = series["time"]
    if "kinetic_energy" in series:
        axes.plot(time, series["kinetic_energy"], color="C0")
        axes.set_ylabel("translational\nkinetic energy (J)", color="C0")
    rotational = series.get("rotational_energy")
    if rotational is not None and np.any(rotational != 0.0):  # usually far smaller: its own axis
        twin = axes.twinx()
        twin.plot(time, rotational, color="C1", linewidth=0.8)
        twin.set_ylabel("rotational (J)", color="C1")


def temperature(axes, series, info):
    time = series["time"]
    if "granular_temperature" in series:
        axes.plot(time, series["granular_temperature"], color="C2", label="cell average, about the mass-centre velocity (Lan A4.11)")
    if "zone_temperature" in series:
        axes.plot(time, series["zone_temperature"], color="C5", linewidth=0.9, label="about each zone's mean (eq. 3-1-9)")
    axes.set_ylabel("granular temperature\n(m\u00b2/s\u00b2)")
    axes.legend(loc="upper right", fontsize=8)


def heights(axes, series, info):
    time = series["time"]
    scale, unit = info.length_scale()
    label = "y / d" if unit == "/ d" else "m"
    if "mass_center_height" in series:
        axes.plot(time, scale * series["mass_center_height"], color="C4", label="mass centre")
    if "bed_height" in series:
        axes.plot(time, scale * series["bed_height"], color="C9", label="bed height")
    floor = series.get("floor_position")
    if floor is not None and np.any(floor != 0.0):
        axes.plot(time, scale * floor, color="0.4", linewidth=0.8, label="floor")
    axes.set_ylabel(f"height ({label})")
    axes.ticklabel_format(axis="y", useOffset=False)
    axes.legend(loc="upper right", fontsize=8)


def bulk_solids_fraction(axes, series, info):
    axes.plot(series["time"], series["bulk_solids_fraction"], color="C3")
    axes.set_ylabel("bulk solids\nfraction \u03bd")


def collisions(axes, series, info):
    time, count = series["time"], series["collisions"]
    axes.plot(time, count, color="C6")
    axes.set_ylabel("collisions\n(cumulative)", color="C6")
    if info.particles and time.size >= 2:
        rate = np.diff(count) / np.diff(time) / info.particles
        twin = axes.twinx()
        twin.step(time[1:], rate, where="pre", color="0.45", linewidth=0.7)
        twin.set_ylabel("per particle\nper second", color="0.45")
        # Scaled to the later half of the run: a bed at rest starts and ends contacts far more often.
        late = rate[rate.size // 2:]
        late = late[np.isfinite(late)]
        if late.size and late.max() > 0.0:
            twin.set_ylim(0.0, 1.5 * float(late.max()))


def pressure(axes, series, info):
    axes.plot(series["time"], series["pressure"], color="C8")
    axes.set_ylabel("pressure (Pa)")


def overlap(axes, series, info):
    axes.plot(series["time"], series["max_overlap_over_diameter"], color="C3")
    axes.axhline(LAN_OVERLAP_LIMIT, color="0.5", linestyle=":", label="1% of d (Lan's limit)")
    axes.set_ylabel("max overlap / d")
    axes.set_ylim(bottom=0.0)
    axes.legend(loc="upper right", fontsize=8)


# (columns any of which makes the panel, drawing function), top to bottom.
PANELS = [
    (["kinetic_energy", "rotational_energy"], energy),
    (["granular_temperature", "zone_temperature"], temperature),
    (["mass_center_height", "bed_height", "floor_position"], heights),
    (["bulk_solids_fraction"], bulk_solids_fraction),
    (["collisions"], collisions),
    (["pressure"], pressure),
    (["max_overlap_over_diameter"], overlap),
]
