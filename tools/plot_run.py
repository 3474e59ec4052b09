#!/usr/bin/python3
"""PNG figures of a finished grainflow run: depth profiles and time series.

Usage: /usr/bin/python3 tools/plot_run.py OUTDIR     (what `grainflow plot OUTDIR` runs)

Reads OUTDIR/profiles.csv, OUTDIR/timeseries.csv and OUTDIR/summary.json and writes
  OUTDIR/profiles.png    W(Y) = sqrt(T / (g d)) and solids fraction nu(Y) against Y = y/d,
                         in the style of Lan (1994), Figs. A4.1-A4.7;
  OUTDIR/timeseries.png  kinetic energy, granular temperature, floor and mass-centre height,
                         maximum overlap / d against time.
Each PNG is written under a temporary name in OUTDIR and renamed into place.
Needs only Debian's python3-matplotlib and python3-numpy. Exit status 1 on missing or bad input.
"""

import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
import numpy as np  # noqa: E402

try:
    import tomllib  # Python >= 3.11 (Debian 12)
except ImportError:  # pragma: no cover - older Pythons: no Gamma / V_b in the title
    tomllib = None

# W of a zone is drawn as a line only where the zone holds on average at least this many
# particles: a particle alone in a zone has no fluctuation about the instantaneous zone mean, so
# Lan's temperature is biased low (to zero) in sparse zones. Those zones get hollow markers.
SPARSE_ZONE_PARTICLES = 1.0
# Without the particle count in summary.json: sparse = solids fraction below this share of its peak.
SPARSE_ZONE_FRACTION = 0.01
# Lan's halt criterion for the overlap monitor (sections 2.5, 4.1.3): 1% of a diameter.
LAN_OVERLAP_LIMIT = 0.01


class PlotError(Exception):
    """An input problem the user has to fix; reported on stderr with exit status 1."""


def read_csv(path, required):
    """Reads a grainflow CSV ('#' comment lines, one header row) into {column: numpy array}."""
    try:
        with open(path, newline="") as handle:
            rows = [row for row in csv.reader(line for line in handle if line.strip() and not line.startswith("#"))]
    except OSError as error:
        raise PlotError(f"cannot read {path}: {error.strerror}") from error
    if not rows:
        raise PlotError(f"{path}: no header row")
    header = [name.strip() for name in rows[0]]
    missing = [name for name in required if name not in header]
    if missing:
        raise PlotError(f"{path}: missing column(s) {', '.join(missing)}")
    columns = {name: [] for name in header}
    for number, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise PlotError(f"{path}: data row {number - 1} has {len(row)} fields, the header has {len(header)}")
        for name, text in zip(header, row):
            try:
                columns[name].append(float(text))
            except ValueError as error:
                raise PlotError(f"{path}: data row {number - 1}, column '{name}': '{text}' is not a number") from error
    return {name: np.asarray(values, dtype=float) for name, values in columns.items()}


def read_summary(path):
    try:
        with open(path) as handle:
            summary = json.load(handle)
    except OSError as error:
        raise PlotError(f"cannot read {path}: {error.strerror}") from error
    except json.JSONDecodeError as error:
        raise PlotError(f"{path}: not valid JSON ({error})") from error
    if not isinstance(summary, dict):
        raise PlotError(f"{path}: expected a JSON object")
    return summary


def save_atomically(figure, path):
    """Saves a figure under a temporary name next to `path`, then renames it into place."""
    directory, name = os.path.split(path)
    temporary = os.path.join(directory, f".{name}.tmp-{os.getpid()}")
    try:
        figure.savefig(temporary, format="png", dpi=130)
        os.replace(temporary, path)
    except OSError as error:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise PlotError(f"cannot write {path}: {error.strerror}") from error
    finally:
        plt.close(figure)


def case_name(summary, outdir):
    case = summary.get("case")
    if isinstance(case, str) and case:
        return os.path.splitext(os.path.basename(case))[0]
    return os.path.basename(os.path.normpath(outdir))


# --- Drive parameters for the title ------------------------------------------------------------


def find_case_file(summary, outdir):
    """The case file a run came from, if it can still be found (its path is relative to the
    directory the run was started in: try the current directory, the repository, OUTDIR/..)."""
    case = summary.get("case")
    if not isinstance(case, str) or not case:
        return None
    repository = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    candidates = [case] if os.path.isabs(case) else [
        case, os.path.join(repository, case), os.path.join(os.path.dirname(os.path.abspath(outdir)), case)]
    for candidate in candidates:
        if os.path.isfile(candidate):
            return candidate
    return None


def drive_numbers(case_path):
    """Gamma = a w^2 / g along gravity and V_b = sqrt(<v_floor^2>/3) / sqrt(g d) (Lan eqs. 4-1-2,
    4-1-3), computed from the case file as `grainflow check` does; plus the vertical floor speed
    amplitude a w, for the consistency check against the run's time series. None without a drive."""
    if tomllib is None or case_path is None:
        return None
    try:
        with open(case_path, "rb") as handle:
            case = tomllib.load(handle)
    except (OSError, tomllib.TOMLDecodeError):
        return None
    drive = case.get("drive")
    if not isinstance(drive, dict):
        return None
    try:
        gravity = [float(x) for x in case.get("gravity", {}).get("vector", [0.0, -9.81, 0.0])]
        g = math.sqrt(sum(x * x for x in gravity))
        axis = max(range(3), key=lambda k: abs(gravity[k])) if g > 0.0 else 1
        amplitude = [float(x) for x in drive.get("amplitude", [0.0, 0.0, 0.0])]
        frequency = [float(x) for x in drive.get("frequency", [0.0, 0.0, 0.0])]
        if drive.get("preset") == "rotary":
            amplitude = [amplitude[0]] * 3
            frequency = [frequency[0]] * 3
        # Reference species: the lightest moving one (derived_quantities.cpp).
        moving = [s for s in case.get("species", []) if not s.get("frozen", False)]
        if not moving or g <= 0.0:
            return None
        reference = min(moving, key=lambda s: float(s["density"]) * float(s["diameter"]) ** 3)
        diameter = float(reference["diameter"])
    except (KeyError, TypeError, ValueError, IndexError):
        return None
    omega = [2.0 * math.pi * f for f in frequency]
    mean_square = sum(0.5 * (a * w) ** 2 for a, w in zip(amplitude, omega))
    return {
        "gamma": amplitude[axis] * omega[axis] ** 2 / g,
        "v_b": math.sqrt(mean_square / 3.0) / math.sqrt(g * diameter),
        "vertical_speed_amplitude": amplitude[axis] * omega[axis],
        "start": float(drive.get("start", 0.0)),
        "ramp": float(drive.get("ramp", 1.0)),
    }


def drive_matches_run(numbers, timeseries):
    """True when the floor speed recorded in the time series fits the case file's drive (a --set
    override may have changed the drive since; then the title must not quote the file's values)."""
    time, speed = timeseries["time"], np.abs(timeseries["floor_velocity"])
    expected = numbers["vertical_speed_amplitude"]
    if speed.size == 0:
        return False
    if speed.max() > expected * 1.001 + 1e-12:
        return False
    steady = speed[time >= numbers["start"] + numbers["ramp"]]
    if expected == 0.0:
        return True
    if steady.size >= 20:  # enough phases sampled: the peak must be close to the amplitude
        return steady.max() >= 0.7 * expected
    return True


def title_numbers(summary, outdir, timeseries):
    numbers = drive_numbers(find_case_file(summary, outdir))
    if numbers is None or not drive_matches_run(numbers, timeseries):
        return None
    return numbers


# --- Figures ------------------------------------------------------------------------------------


def plot_profiles(outdir, summary, profiles, drive):
    y = profiles["Y"]
    solids = profiles["solids_fraction"]
    w = profiles["W"]
    d = reference_diameter(profiles)
    occupied = np.nonzero(solids > 0.0)[0]

    figure, (left, right) = plt.subplots(1, 2, sharey=True, figsize=(8.0, 6.0))
    title = case_name(summary, outdir)
    if occupied.size == 0:
        for axes in (left, right):
            axes.text(0.5, 0.5, "no profile samples\n(is output.average_start\nafter the end of the run?)",
                      ha="center", va="center", transform=axes.transAxes)
    else:
        last = occupied[-1]  # empty zones above the bed are left out
        y, solids, w = y[: last + 1], solids[: last + 1], w[: last + 1]
        w_time_mean = profiles["temperature_time_mean"][: last + 1]
        lo, hi = profiles["position_lo"][: last + 1], profiles["position_hi"][: last + 1]
        dense, sparse_label = dense_zones(summary, solids, hi - lo)

        # W from the temperature about the long-term zone mean velocity: it includes the zone's
        # periodic mean motion (the floor's drive), so it lies above Lan's W.
        g = profile_gravity(profiles)
        if g > 0.0 and d > 0.0:
            w_campbell = np.sqrt(np.maximum(w_time_mean, 0.0) / (g * d))
            left.plot(w_campbell[dense], y[dense], linestyle="--", color="0.6", marker="s", markersize=3,
                      label="about the time-mean velocity")
        left.plot(w[dense], y[dense], color="C0", marker="o", markersize=4,
                  label="about the instantaneous zone mean (Lan)")
        if np.any(~dense):
            left.plot(w[~dense], y[~dense], linestyle="none", marker="o", markersize=4, markerfacecolor="none",
                      color="0.7", label=sparse_label)
        left.legend(loc="upper center", bbox_to_anchor=(0.5, -0.11), fontsize=8, ncol=1, frameon=False,
                    title="W from the temperature", title_fontsize=8)

        right.plot(solids, y, color="C3", marker="o", markersize=4)
        right.set_xlim(0.0, max(0.65, 1.05 * solids.max()))
        if d > 0.0:
            held = float(np.sum(solids * (hi - lo)) / d)  # m_t = integral of nu dY (eq. 4-1-3)
            title += f"   \u222b\u03bd dY = {held:.3g}"
        left.set_ylim(0.0, float(hi[-1] / d) if d > 0.0 else float(y[-1]) + 0.5)
        left.set_xlim(left=0.0)
    if drive is not None:
        title += f"   \u0393 = {drive['gamma']:.3g}   V_b = {drive['v_b']:.3g}"
    samples = summary.get("profile_samples")
    if isinstance(samples, int):
        title += f"\n(long-term averages over {samples} samples)"
    figure.suptitle(title, fontsize=11)
    left.set_xlabel("W = \u221a(T / g d)")
    left.set_ylabel("Y = y / d")
    right.set_xlabel("solids fraction \u03bd")
    for axes in (left, right):
        axes.grid(True, alpha=0.3)
    figure.tight_layout()
    save_atomically(figure, os.path.join(outdir, "profiles.png"))


def reference_diameter(profiles):
    """d of Y = y/d, recovered from the profile's own columns (0 when they do not tell)."""
    y, position = profiles["Y"], profiles["position"]
    ratio = np.divide(position, y, out=np.zeros_like(y), where=y != 0)
    return float(np.median(ratio[ratio > 0])) if np.any(ratio > 0) else 0.0


def dense_zones(summary, solids, thickness):
    """Zones holding enough particles for W; and the legend text for the others. The mean number of
    particles in a zone is N times the zone's share of the integral of nu over the depth."""
    particles = summary.get("particles")
    integral = float(np.sum(solids * thickness))
    if isinstance(particles, int) and particles > 0 and integral > 0.0:
        occupancy = particles * solids * thickness / integral
        return occupancy >= SPARSE_ZONE_PARTICLES, f"sparse zones (< {SPARSE_ZONE_PARTICLES:g} particle on average)"
    return solids >= SPARSE_ZONE_FRACTION * solids.max(), f"sparse zones (\u03bd < {SPARSE_ZONE_FRACTION:g} \u00d7 peak)"


def profile_gravity(profiles):
    """g recovered from the profile itself (W^2 = T / (g d)), so no case file is needed."""
    t, w, y, position = profiles["temperature"], profiles["W"], profiles["Y"], profiles["position"]
    usable = (w > 0) & (t > 0) & (y > 0)
    if not np.any(usable):
        return 0.0
    d = position[usable] / y[usable]
    return float(np.median(t[usable] / (w[usable] ** 2 * d)))


def plot_timeseries(outdir, summary, series, drive, diameter):
    time = series["time"]
    figure, axes = plt.subplots(4, 1, sharex=True, figsize=(8.0, 9.0))
    energy, temperature, height, overlap = axes

    energy.plot(time, series["kinetic_energy"], color="C0")
    energy.set_ylabel("translational\nkinetic energy (J)", color="C0")
    if np.any(series["rotational_energy"] != 0.0):  # usually far smaller: its own axis
        rotation = energy.twinx()
        rotation.plot(time, series["rotational_energy"], color="C1", linewidth=0.8)
        rotation.set_ylabel("rotational (J)", color="C1")

    temperature.plot(time, series["granular_temperature"], color="C2")
    temperature.set_ylabel("granular temperature\n(m\u00b2/s\u00b2)")

    # Heights in diameters, like Y = y/d of the profiles (in metres when d is unknown).
    scale, unit = (1.0 / diameter, "y / d") if diameter > 0.0 else (1.0, "m")
    height.plot(time, scale * series["mass_center_height"], color="C4", label="mass centre")
    if np.any(series["floor_position"] != 0.0):
        height.plot(time, scale * series["floor_position"], color="0.4", linewidth=0.8, label="floor")
    height.set_ylabel(f"height ({unit})")
    height.ticklabel_format(axis="y", useOffset=False)
    height.legend(loc="upper right", fontsize=8)

    overlap.plot(time, series["max_overlap_over_diameter"], color="C3")
    overlap.axhline(LAN_OVERLAP_LIMIT, color="0.5", linestyle=":", label="1% of d (Lan's limit)")
    overlap.set_ylabel("max overlap / d")
    overlap.set_xlabel("time (s)")
    overlap.set_ylim(bottom=0.0)
    overlap.legend(loc="upper right", fontsize=8)

    if drive is not None:
        for a in axes:
            a.axvline(drive["start"], color="0.75", linewidth=0.8)
            if drive["ramp"] > 0.0:
                a.axvspan(drive["start"], drive["start"] + drive["ramp"], color="0.92", zorder=0)
    for a in axes:
        a.grid(True, alpha=0.3)
    title = case_name(summary, outdir)
    errors = summary.get("errors")
    if isinstance(errors, list) and errors:
        title += "   (run failed: see summary.json errors)"
    figure.suptitle(title, fontsize=11)
    figure.tight_layout()
    save_atomically(figure, os.path.join(outdir, "timeseries.png"))


PROFILE_COLUMNS = ["position_lo", "position_hi", "position", "Y", "solids_fraction", "temperature",
                   "temperature_time_mean", "W"]
TIMESERIES_COLUMNS = ["time", "kinetic_energy", "rotational_energy", "granular_temperature",
                      "mass_center_height", "floor_position", "floor_velocity", "max_overlap_over_diameter"]


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print("usage: plot_run.py OUTDIR   (the output folder of `grainflow run`)", file=sys.stderr)
        return 1
    outdir = argv[1]
    if not os.path.isdir(outdir):
        raise PlotError(f"{outdir}: no such output folder")
    names = ["summary.json", "profiles.csv", "timeseries.csv"]
    missing = [name for name in names if not os.path.isfile(os.path.join(outdir, name))]
    if missing:
        raise PlotError(f"{outdir}: missing {', '.join(missing)} (is this the output folder of a finished run?)")
    summary = read_summary(os.path.join(outdir, "summary.json"))
    profiles = read_csv(os.path.join(outdir, "profiles.csv"), PROFILE_COLUMNS)
    series = read_csv(os.path.join(outdir, "timeseries.csv"), TIMESERIES_COLUMNS)
    if series["time"].size == 0:
        raise PlotError(f"{os.path.join(outdir, 'timeseries.csv')}: no data rows")
    drive = title_numbers(summary, outdir, series)
    plot_profiles(outdir, summary, profiles, drive)
    plot_timeseries(outdir, summary, series, drive, reference_diameter(profiles))
    print(f"plot_run: wrote {os.path.join(outdir, 'profiles.png')} and {os.path.join(outdir, 'timeseries.png')}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except PlotError as error:
        print(f"plot_run: {error}", file=sys.stderr)
        sys.exit(1)
