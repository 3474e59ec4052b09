"""How the floor's motion travels up the bed (Lan 1994 section 4.3).

analysis/zone_spectra.csv [+ zone_series.h5] -> zone_spectra.png: the power spectral densities of
    the floor's and each zone's velocity along gravity, one curve per zone, log scale, the floor
    frequency marked (Fig. A4.13); with zone_series.h5 (and h5py), the time histories of the last
    floor cycles above them.
analysis/floor_correlation.csv [+ zone_series.h5] -> floor_correlation.png: each zone's delay behind
    the floor against its height with the fitted wave speed; with zone_series.h5 (and h5py), the
    floor's autocorrelation and the floor-zone cross-correlations with the delays marked (Fig. A4.14).
"""

import os

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import cm, colors

from .common import PlotError, existing, h5py, read_table, save_atomically, zone_profiles

HISTORY_CYCLES = 4  # floor cycles of the time histories
WATERFALL = 8       # zones drawn in the stack of correlation curves
WATERFALL_STEP = 1.5


def plot(outdir, info):
    written = []
    series = read_zone_series(outdir, info)
    spectra_path = existing(outdir, "analysis", "zone_spectra.csv")
    if spectra_path:
        spectra = read_table(spectra_path, ["frequency", "floor"])
        if len(spectra):
            written.append(plot_spectra(outdir, info, spectra, series))
    correlation_path = existing(outdir, "analysis", "floor_correlation.csv")
    if correlation_path:
        table = read_table(correlation_path, ["zone", "height", "delay", "speed"])
        if len(table):
            written.append(plot_correlation(outdir, info, table, series))
    return written


def read_zone_series(outdir, info):
    """{time, floor (velocity along gravity), zones [S, Z]} from zone_series.h5, or None."""
    path = existing(outdir, "zone_series.h5")
    if path is None or h5py is None:
        return None
    try:
        with h5py.File(path, "r") as f:
            axis = int(f.attrs.get("gravity_axis", info.gravity_axis))
            series = {"time": f["time"][:], "floor": f["floor_velocity"][:],
                      "zones": f["zone_velocity"][:, :, axis], "interval": float(f.attrs["interval"])}
    except (OSError, KeyError, ValueError, IndexError) as error:
        raise PlotError(f"{path}: cannot read the zone velocities ({error})") from error
    return series if series["time"].size >= 16 else None


def zone_colours(count):
    norm = colors.Normalize(vmin=0, vmax=max(count - 1, 1))
    return cm.ScalarMappable(norm=norm, cmap="viridis")


def zone_columns(table):
    names = [name for name in table.header if name.startswith("zone_")]
    return sorted(names, key=lambda name: int(name[5:]) if name[5:].isdigit() else 0)


def floor_frequency(info, spectra):
    """The drive frequency when known, else the floor spectrum's peak (None without floor motion)."""
    if info.drive_frequency:
        return info.drive_frequency, "drive"
    floor = spectra["floor"]
    if floor.size < 2 or not np.any(floor[1:] > 0.0):
        return None, ""
    return float(spectra["frequency"][1 + int(np.argmax(floor[1:]))]), "floor peak"


def last_cycles(series, frequency):
    """Rows of the last HISTORY_CYCLES floor cycles (the last quarter of the record without f)."""
    time = series["time"]
    span = HISTORY_CYCLES / frequency if frequency else 0.25 * (time[-1] - time[0])
    return time >= time[-1] - span


def plot_spectra(outdir, info, spectra, series):
    names = zone_columns(spectra)
    mapper = zone_colours(len(names))
    f_floor, source = floor_frequency(info, spectra)
    rows = 2 if series is not None else 1
    figure, axes = plt.subplots(rows, 1, figsize=(8.5, 4.0 + 3.0 * (rows - 1)), squeeze=False,
                                layout="constrained")
    axes = axes[:, 0]
    if series is not None:
        history = axes[0]
        keep = last_cycles(series, f_floor)
        time = series["time"][keep]
        for z in range(series["zones"].shape[1]):
            if not np.any(series["zones"][keep, z]):
                continue  # an empty zone
            history.plot(time, series["zones"][keep, z], color=mapper.to_rgba(z), linewidth=0.8)
        history.plot(time, series["floor"][keep], color="k", linewidth=1.4, label="floor")
        history.set_xlabel("time (s)")
        history.set_ylabel(f"velocity along {info.vertical} (m/s)")
        history.legend(loc="upper right", fontsize=8)
        history.grid(True, alpha=0.3)
    spectrum = axes[-1]
    frequency = spectra["frequency"]
    positive = frequency > 0.0
    for z, name in enumerate(names):
        psd = spectra[name]
        shown = positive & (psd > 0.0)
        spectrum.semilogy(frequency[shown], psd[shown], color=mapper.to_rgba(z), linewidth=0.9)
    floor = spectra["floor"]
    shown = positive & (floor > 0.0)
    spectrum.semilogy(frequency[shown], floor[shown], color="k", linewidth=1.4, label="floor")
    if f_floor:
        for k in (1, 2, 3):
            spectrum.axvline(k * f_floor, color="C3", linestyle=":", linewidth=0.9,
                             label=f"{source} frequency {f_floor:.4g} Hz and harmonics" if k == 1 else None)
        spectrum.set_xlim(0.0, min(float(frequency.max()), 8.0 * f_floor))
    spectrum.set_xlabel("frequency (Hz)")
    spectrum.set_ylabel("PSD of the velocity along gravity\n((m/s)\u00b2/Hz)")
    spectrum.legend(loc="upper right", fontsize=8)
    spectrum.grid(True, which="both", alpha=0.25)
    if names:
        figure.colorbar(mapper, ax=list(axes), label="zone (0 = lowest)", pad=0.02)
    figure.suptitle(info.title() + "\nzone velocity spectra (Lan Fig. A4.13)", fontsize=10)
    return save_atomically(figure, os.path.join(outdir, "zone_spectra.png"))


def correlation(x, y, max_lag):
    """C_xy(k) = mean of (x_i - x̄)(y_{i+k} - ȳ) over the overlap, for k = -max_lag..max_lag, divided
    by the standard deviations (so 1 for y = x at k = 0); positive k: y follows x (analysis/)."""
    n = x.size
    xc, yc = x - x.mean(), y - y.mean()
    size = 1 << int(np.ceil(np.log2(2 * n)))
    circular = np.fft.irfft(np.conj(np.fft.rfft(xc, size)) * np.fft.rfft(yc, size), size)
    lags = np.arange(-max_lag, max_lag + 1)
    values = circular[lags % size] / (n - np.abs(lags))
    scale = xc.std() * yc.std()
    return lags, values / scale if scale > 0.0 else values


def occupied_zone_mask(outdir, zones):
    """Zones holding material (solids fraction >= 1% of the peak in profiles.csv); all without it."""
    path = zone_profiles(outdir)
    if path is None:
        return np.ones(zones.size, dtype=bool)
    try:
        solids = read_table(path, ["solids_fraction"])["solids_fraction"]
    except PlotError:
        return np.ones(zones.size, dtype=bool)  # the profile figures report it
    if solids.size == 0 or solids.max() <= 0.0:
        return np.ones(zones.size, dtype=bool)
    inside = zones < solids.size
    mask = np.zeros(zones.size, dtype=bool)
    mask[inside] = solids[zones[inside]] >= 0.01 * solids.max()
    return mask


def fit_zones(table, occupied):
    """The zones of the wave-speed fit: above the floor, with material and a positive delay, from
    the lowest such zone up to the one with the largest delay (above it the delay, taken within
    one drive period, wraps round to small values)."""
    height, delay = table["height"], table["delay"]
    usable = occupied & (height > 0.0) & np.isfinite(delay) & (delay > 0.0)
    if np.count_nonzero(usable) < 2:
        return usable
    candidates = np.flatnonzero(usable)
    top = height[candidates[np.argmax(delay[candidates])]]
    return usable & (height <= top)


def plot_correlation(outdir, info, table, series):
    rows = 2 if series is not None else 1
    figure, axes = plt.subplots(rows, 1, figsize=(8.5, 4.0 + 6.0 * (rows - 1)), squeeze=False,
                                layout="constrained")
    axes = axes[:, 0]
    zones = table["zone"].astype(int)
    mapper = zone_colours(int(zones.max()) + 1 if zones.size else 1)
    if series is not None:
        curves = axes[0]
        f = info.drive_frequency
        max_lag = min(series["time"].size // 4,
                      int(np.ceil(1.5 / (f * series["interval"]))) if f else series["time"].size // 4)
        lags, auto = correlation(series["floor"], series["floor"], max_lag)
        tau = lags * series["interval"]
        # A waterfall like Lan's stack of panels: the floor at the bottom, then up to WATERFALL zones
        # spread over the depth, each shifted up by WATERFALL_STEP.
        curves.plot(tau, auto, color="k", linewidth=1.6)
        shown = [k for k in range(zones.size) if zones[k] < series["zones"].shape[1]]
        shown = [shown[k] for k in np.unique(np.linspace(0, len(shown) - 1, min(WATERFALL, len(shown))).astype(int))]
        for rank, k in enumerate(shown, start=1):
            z, delay = zones[k], table["delay"][k]
            _, cross = correlation(series["floor"], series["zones"][:, z], max_lag)
            offset = rank * WATERFALL_STEP
            curves.plot(tau, offset + cross, color=mapper.to_rgba(z), linewidth=1.0)
            if np.isfinite(delay):
                curves.plot([delay], [offset + np.interp(delay, tau, cross)], "o", color=mapper.to_rgba(z),
                            markeredgecolor="k", markersize=5)
        curves.set_yticks([rank * WATERFALL_STEP for rank in range(len(shown) + 1)],
                          ["floor (auto)"] + [f"zone {zones[k]}" for k in shown], fontsize=7)
        curves.axvline(0.0, color="0.5", linewidth=0.7)
        curves.set_xlabel("lag τ (s): zone behind floor > 0")
        curves.set_title("normalised correlation with the floor velocity; dots: each zone's delay", fontsize=9)
        curves.grid(True, axis="x", alpha=0.3)

    delays = axes[-1]
    scale, unit = info.length_scale()
    height, delay = table["height"], table["delay"]
    fitted = fit_zones(table, occupied_zone_mask(info.outdir, zones))
    delays.scatter(delay[~fitted], scale * height[~fitted], c=[mapper.to_rgba(z) for z in zones[~fitted]],
                   marker="s", edgecolors="0.5", linewidths=0.4, alpha=0.5, zorder=3, label="not fitted")
    delays.scatter(delay[fitted], scale * height[fitted], c=[mapper.to_rgba(z) for z in zones[fitted]],
                   edgecolors="k", linewidths=0.4, zorder=3, label="fitted")
    text = ""
    if np.count_nonzero(fitted) >= 2:
        # height = c (delay - t0): least squares over the fitted zones
        slope, offset = np.polyfit(delay[fitted], height[fitted], 1)
        if slope > 0.0:
            line = np.linspace(0.0, float(delay[fitted].max()), 50)
            delays.plot(line, scale * (slope * line + offset), color="C3", linestyle="--",
                        label=f"fit: wave speed c = {slope:.3g} m/s")
            text = f"wave speed {slope:.3g} m/s"
        speeds = table["speed"][fitted & np.isfinite(table["speed"])]
        if speeds.size:
            delays.plot([], [], " ", label=f"median of height / delay: {np.median(speeds):.3g} m/s")
    delays.set_xlabel("delay behind the floor (s)")
    delays.set_ylabel("height above the mean floor " + ("(y / d)" if unit == "/ d" else "(m)"))
    delays.legend(loc="lower right", fontsize=8)
    delays.grid(True, alpha=0.3)
    delays.set_xlim(left=min(0.0, float(np.nanmin(delay)) if np.any(np.isfinite(delay)) else 0.0))
    figure.colorbar(mapper, ax=list(axes), label="zone (0 = lowest)", pad=0.02)
    figure.suptitle(info.title(text) + "\nfloor-zone correlations and delays (Lan Fig. A4.14)", fontsize=10)
    return save_atomically(figure, os.path.join(outdir, "floor_correlation.png"))
