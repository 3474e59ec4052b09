"""Shared pieces of the figure modules: the readers of grainflow's CSV/JSON outputs, PlotError (a
bad input, reported with the file's name), atomic PNG saving, a Welch spectrum, the phase of the
floor's motion, and RunInfo: what a title needs to know about a run (case name, Gamma, V_b, m_t,
gravity axis, drive frequency, reference diameter d), from summary.json, the HDF5 attributes, the
profile and, as a fallback, the case file.
"""

import csv
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
import numpy as np  # noqa: E402

try:
    import tomllib  # Python >= 3.11 (Debian 12)
except ImportError:  # pragma: no cover - older Pythons: no case-file fallback for the title
    tomllib = None

try:
    import h5py  # python3-h5py (tools/install_deps.sh); optional: only extra curves need it
except ImportError:  # pragma: no cover
    h5py = None

AXES = "xyz"
DPI = 130


class PlotError(Exception):
    """An input problem the user has to fix; reported on stderr with exit status 1."""


# --- Readers ------------------------------------------------------------------------------------


class Table:
    """A grainflow CSV file: numeric columns by name, the '#' comment lines and the header order."""

    def __init__(self, path, header, columns, comments):
        self.path, self.header, self.columns, self.comments = path, header, columns, comments

    def __contains__(self, name):
        return name in self.columns

    def __getitem__(self, name):
        return self.columns[name]

    def get(self, name):
        return self.columns.get(name)

    def __len__(self):
        return len(next(iter(self.columns.values()))) if self.columns else 0


def read_table(path, required=(), text_columns=()):
    """Reads a grainflow CSV ('#' comment lines, one header row, numbers) into a Table. Raises
    PlotError naming the file for a missing column, a short row or a field that is not a number
    ('nan' and 'inf' are numbers). Columns named in `text_columns` (e.g. walls.csv's face names)
    are left out unread."""
    try:
        with open(path, newline="") as handle:
            lines = [line for line in handle if line.strip()]
    except OSError as error:
        raise PlotError(f"cannot read {path}: {error.strerror}") from error
    comments = [line[1:].strip() for line in lines if line.startswith("#")]
    rows = list(csv.reader(line for line in lines if not line.startswith("#")))
    if not rows:
        raise PlotError(f"{path}: no header row")
    header = [name.strip() for name in rows[0]]
    missing = [name for name in required if name not in header]
    if missing:
        raise PlotError(f"{path}: missing column(s) {', '.join(missing)}")
    values = [[] for _ in header]
    for number, row in enumerate(rows[1:], start=1):
        if len(row) != len(header):
            raise PlotError(f"{path}: data row {number} has {len(row)} fields, the header has {len(header)}")
        for column, (name, text) in enumerate(zip(header, row)):
            if name in text_columns:
                continue
            try:
                values[column].append(float(text))
            except ValueError as error:
                raise PlotError(f"{path}: data row {number}, column '{name}': '{text}' is not a number") from error
    columns = {name: np.asarray(v, dtype=float) for name, v in zip(header, values) if name not in text_columns}
    return Table(path, header, columns, comments)


def read_json(path):
    """A JSON object from `path`; PlotError naming the file when it is unreadable or not an object."""
    try:
        with open(path) as handle:
            value = json.load(handle)
    except OSError as error:
        raise PlotError(f"cannot read {path}: {error.strerror}") from error
    except json.JSONDecodeError as error:
        raise PlotError(f"{path}: not valid JSON ({error})") from error
    if not isinstance(value, dict):
        raise PlotError(f"{path}: expected a JSON object")
    return value


def number(mapping, key):
    """mapping[key] as a finite float, or None (absent, null, a string, NaN)."""
    value = mapping.get(key) if isinstance(mapping, dict) else None
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return float(value) if math.isfinite(value) else None


def error_bars(errors):
    """Error-bar half-lengths for matplotlib: None when there are none (absent or all NaN, e.g.
    block averages over too few samples), else the values with NaN as 0 (no bar)."""
    if errors is None or not np.any(np.isfinite(errors)):
        return None
    return np.where(np.isfinite(errors), np.abs(errors), 0.0)


def existing(*parts):
    """The joined path when it is a file, else None."""
    path = os.path.join(*parts)
    return path if os.path.isfile(path) else None


def zone_profiles(outdir):
    """profiles.csv of a DEM run (Lan's zone profiles), else None: an event-driven run's profiles.csv
    holds Campbell's strip profiles (first line "# strip profiles"), which these figures do not draw."""
    path = existing(outdir, "profiles.csv")
    if path is None:
        return None
    with open(path) as f:
        return None if f.readline().startswith("# strip profiles") else path


def strip_profiles(outdir):
    """profiles.csv of an event-driven run (Campbell's strip profiles, first line "# strip
    profiles"), else None."""
    path = existing(outdir, "profiles.csv")
    if path is None:
        return None
    with open(path) as f:
        return path if f.readline().startswith("# strip profiles") else None


def is_edmd(info):
    """True for an event-driven run folder (summary.json's engine, else strip profiles)."""
    engine = info.summary.get("engine")
    return engine == "edmd" if isinstance(engine, str) else strip_profiles(info.outdir) is not None


def dimension(info):
    """2 or 3 from summary.json (2, Campbell's discs, when it does not tell)."""
    value = info.summary.get("dimension")
    return value if value in (2, 3) else 2


# --- Output -------------------------------------------------------------------------------------


def save_atomically(figure, path):
    """Saves a figure under a temporary name next to `path`, then renames it into place; returns path."""
    directory, name = os.path.split(path)
    temporary = os.path.join(directory, f".{name}.tmp-{os.getpid()}")
    try:
        figure.savefig(temporary, format="png", dpi=DPI)
        os.replace(temporary, path)
    except OSError as error:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise PlotError(f"cannot write {path}: {error.strerror}") from error
    finally:
        plt.close(figure)
    return path


# --- Signals ------------------------------------------------------------------------------------


def welch(signal, interval):
    """One-sided power spectral density (units^2/Hz) by Welch's method: Hann window, 50% overlap,
    segments of the largest power of two up to a quarter of the record (the whole record when that
    is shorter than 16 samples), each segment's mean removed. Returns (frequency Hz, psd)."""
    x = np.asarray(signal, dtype=float)
    n = x.size
    if n < 4:
        return np.zeros(0), np.zeros(0)
    segment = 8
    while segment * 2 <= n // 4:
        segment *= 2
    if n < 16:
        segment = n
    window = 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(segment) / segment)  # periodic Hann
    step = max(1, segment // 2)
    spectra = []
    for first in range(0, n - segment + 1, step):
        piece = x[first:first + segment]
        spectra.append(np.abs(np.fft.rfft(window * (piece - piece.mean()))) ** 2)
    psd = np.mean(spectra, axis=0) * interval / np.sum(window ** 2)
    if segment > 1:  # one-sided: every bin but 0 (and Nyquist for even segments) doubled
        psd[1:segment // 2 + (segment % 2)] *= 2.0
    return np.fft.rfftfreq(segment, interval), psd


def dominant_frequency(frequency, psd):
    """The frequency of the spectrum's largest peak above f = 0, refined between bins by the vertex
    of the parabola through the logarithms of the peak and its neighbours (None when empty)."""
    if frequency.size < 2:
        return None
    k = 1 + int(np.argmax(psd[1:]))
    if k + 1 < psd.size and np.all(psd[k - 1:k + 2] > 0.0):
        a, b, c = np.log(psd[k - 1:k + 2])
        curvature = a - 2.0 * b + c
        if curvature < 0.0:
            return float(frequency[k] + 0.5 * (a - c) / curvature * (frequency[1] - frequency[0]))
    return float(frequency[k])


def floor_phase(position, velocity, reference=None):
    """Phase of a sinusoidal floor motion from its state, in [0, 2 pi): with the floor at
    y_b = A sin(phi) about the centre of its range and v = A w cos(phi) (the drive of MODELS.md,
    Lan's phases: pi/2 at the top, pi moving down through the middle). The range and the peak speed
    are those of `reference` = (positions, velocities) when given, else of the arguments. None when
    the floor rests."""
    position, velocity = np.asarray(position, dtype=float), np.asarray(velocity, dtype=float)
    range_position, range_velocity = (position, velocity) if reference is None else map(np.asarray, reference)
    if position.size == 0 or range_position.size == 0:
        return None
    half_range = 0.5 * (range_position.max() - range_position.min())
    peak_speed = np.abs(range_velocity).max()
    if half_range <= 0.0 or peak_speed <= 0.0:
        return None
    centre = 0.5 * (range_position.max() + range_position.min())
    return np.mod(np.arctan2((position - centre) / half_range, velocity / peak_speed), 2.0 * np.pi)


def pi_label(phase):
    """A phase as a multiple of pi, e.g. '0.75\u03c0'."""
    return f"{phase / math.pi:.3g}\u03c0"


# --- What the titles need to know about a run ---------------------------------------------------


class RunInfo:
    """Case name, drive numbers, gravity axis and d of a run folder, from whatever it holds.

    Sources, first found wins: summary.json (shaking_acceleration, boundary_fluctuation_velocity,
    mass_holdup, gravity_axis, drive_frequency, diameter), the root attributes of zone_series.h5 and
    trajectory.h5 (gravity_axis, diameter, drive_frequency), the profile (d = position / Y), and the
    case file named in summary.json when it can still be found and its drive matches the floor motion
    recorded in timeseries.csv (a --set override may have changed the drive since).
    """

    def __init__(self, outdir, summary=None):
        self.outdir = outdir
        self.summary = summary if summary is not None else {}
        self.name = case_name(self.summary, outdir)
        self.particles = self.summary.get("particles") if isinstance(self.summary.get("particles"), int) else None
        self.gamma = number(self.summary, "shaking_acceleration")
        self.v_b = number(self.summary, "boundary_fluctuation_velocity")
        self.m_t = number(self.summary, "mass_holdup")
        self.drive_frequency = number(self.summary, "drive_frequency")
        self.diameter = number(self.summary, "diameter")
        axis = self.summary.get("gravity_axis")
        self.gravity_axis = axis if isinstance(axis, int) and 0 <= axis < 3 else None
        self.drive_start = self.drive_ramp = None
        self._from_hdf5()
        if self.diameter is None:
            self.diameter = profile_diameter(outdir)
        self._from_case_file()
        if self.gravity_axis is None:
            self.gravity_axis = 1

    @property
    def vertical(self):
        return AXES[self.gravity_axis]

    def _from_hdf5(self):
        if h5py is None:
            return
        for name in ("zone_series.h5", "trajectory.h5"):
            path = existing(self.outdir, name)
            if path is None:
                continue
            try:
                with h5py.File(path, "r") as f:
                    attributes = {key: f.attrs[key] for key in ("gravity_axis", "diameter", "drive_frequency")
                                  if key in f.attrs}
            except (OSError, ValueError):
                continue  # context only: `grainflow analyze` reports a broken file
            if self.gravity_axis is None and "gravity_axis" in attributes:
                self.gravity_axis = int(attributes["gravity_axis"])
            if self.diameter is None and float(attributes.get("diameter", 0.0)) > 0.0:
                self.diameter = float(attributes["diameter"])
            if self.drive_frequency is None and float(attributes.get("drive_frequency", 0.0)) > 0.0:
                self.drive_frequency = float(attributes["drive_frequency"])

    def _from_case_file(self):
        numbers = case_numbers(find_case_file(self.summary, self.outdir))
        if numbers is None:
            return
        if self.gravity_axis is None:
            self.gravity_axis = numbers["axis"]
        if self.diameter is None:
            self.diameter = numbers["diameter"]
        if self.m_t is None and numbers["moving"] == self.particles:
            self.m_t = numbers["m_t"]
        if not numbers["driven"] or not drive_matches_run(numbers, self.outdir):
            return
        self.drive_start, self.drive_ramp = numbers["start"], numbers["ramp"]
        if self.gamma is None:
            self.gamma = numbers["gamma"]
        if self.v_b is None:
            self.v_b = numbers["v_b"]
        if self.drive_frequency is None and numbers["frequency"] > 0.0:
            self.drive_frequency = numbers["frequency"]

    def drive_text(self):
        """'Gamma = 3   V_b = 0.5   m_t = 5' with what is known (empty without a drive)."""
        parts = []
        if self.gamma:
            parts.append(f"\u0393 = {self.gamma:.3g}")
        if self.v_b:
            parts.append(f"V_b = {self.v_b:.3g}")
        if self.m_t:
            parts.append(f"m_t = {self.m_t:.3g}")
        return "   ".join(parts)

    def title(self, what=""):
        """'<case>   <what>   Gamma = ...' for a figure's suptitle."""
        return "   ".join(part for part in (self.name, what, self.drive_text()) if part)

    def length_scale(self):
        """(factor, unit label) turning metres into diameters, or metres when d is unknown."""
        if self.diameter and self.diameter > 0.0:
            return 1.0 / self.diameter, "/ d"
        return 1.0, "(m)"


def case_name(summary, outdir):
    case = summary.get("case")
    if isinstance(case, str) and case:
        return os.path.splitext(os.path.basename(case))[0]
    return os.path.basename(os.path.normpath(outdir))


def profile_diameter(outdir):
    """d of Y = y/d, recovered from profiles.csv's own columns (None when it does not tell)."""
    path = zone_profiles(outdir)
    if path is None:
        return None
    try:
        profiles = read_table(path, ["position", "Y"])
    except PlotError:
        return None  # the profile figures report it
    return reference_diameter(profiles)


def reference_diameter(profiles):
    """d = position / Y over the profile's zones (None when no zone tells)."""
    y, position = profiles["Y"], profiles["position"]
    ratio = np.divide(position, y, out=np.zeros_like(y), where=y != 0)
    ratio = ratio[np.isfinite(ratio) & (ratio > 0)]
    return float(np.median(ratio)) if ratio.size else None


def find_case_file(summary, outdir):
    """The case file a run came from, if it can still be found (its path is relative to the
    directory the run was started in: try the current directory, the repository, OUTDIR/.. and
    OUTDIR/../.. for a sweep's member)."""
    case = summary.get("case")
    if not isinstance(case, str) or not case:
        return None
    repository = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parent = os.path.dirname(os.path.abspath(outdir))
    candidates = [case] if os.path.isabs(case) else [
        case, os.path.join(repository, case), os.path.join(parent, case),
        os.path.join(os.path.dirname(parent), case)]
    for candidate in candidates:
        if os.path.isfile(candidate):
            return candidate
    return None


def case_numbers(case_path):
    """From the case file, as `grainflow check` computes them (MODELS.md "Derived quantities"):
    gravity axis, reference diameter, m_t, and for a drive Gamma = a w^2 / g along gravity,
    V_b = sqrt(<v_floor^2>/3) / sqrt(g d), the drive frequency along gravity and the vertical floor
    speed amplitude a w (to check the case file against the run). None when unreadable."""
    if tomllib is None or case_path is None:
        return None
    try:
        with open(case_path, "rb") as handle:
            case = tomllib.load(handle)
    except (OSError, tomllib.TOMLDecodeError):
        return None
    try:
        gravity = [float(x) for x in case.get("gravity", {}).get("vector", [0.0, -9.81, 0.0])]
        g = math.sqrt(sum(x * x for x in gravity))
        axis = max(range(3), key=lambda k: abs(gravity[k])) if g > 0.0 else 1
        moving = [s for s in case.get("species", []) if not s.get("frozen", False)]
        if not moving:
            return None
        # Reference species: the lightest moving one (derived_quantities.cpp).
        reference = min(moving, key=lambda s: float(s["density"]) * float(s["diameter"]) ** 3)
        diameter = float(reference["diameter"])
        lo, hi = case["domain"]["lo"], case["domain"]["hi"]
        area = 1.0
        for k in range(3):
            if k != axis:
                area *= float(hi[k]) - float(lo[k])
        volume = sum(int(s.get("count", 0)) * math.pi * float(s["diameter"]) ** 3 / 6.0 for s in moving)
        drive = case.get("drive")
        drive = drive if isinstance(drive, dict) else {}
        amplitude = [float(x) for x in drive.get("amplitude", [0.0, 0.0, 0.0])]
        frequency = [float(x) for x in drive.get("frequency", [0.0, 0.0, 0.0])]
        if drive.get("preset") == "rotary":
            amplitude = [amplitude[0]] * 3
            frequency = [frequency[0]] * 3
    except (KeyError, TypeError, ValueError, IndexError):
        return None
    omega = [2.0 * math.pi * f for f in frequency]
    mean_square = sum(0.5 * (a * w) ** 2 for a, w in zip(amplitude, omega))
    return {
        "axis": axis,
        "diameter": diameter,
        "moving": sum(int(s.get("count", 0)) for s in moving),
        "m_t": volume / (area * diameter) if area > 0.0 else None,
        "driven": bool(drive) and g > 0.0,
        "gamma": amplitude[axis] * omega[axis] ** 2 / g if g > 0.0 else 0.0,
        "v_b": math.sqrt(mean_square / 3.0) / math.sqrt(g * diameter) if g > 0.0 else 0.0,
        "frequency": frequency[axis],
        "vertical_speed_amplitude": amplitude[axis] * omega[axis],
        "start": float(drive.get("start", 0.0)),
        "ramp": float(drive.get("ramp", 1.0)),
    }


def drive_matches_run(numbers, outdir):
    """True when the floor speed recorded in timeseries.csv fits the case file's drive (False
    without a readable time series: then the case file cannot be checked)."""
    path = existing(outdir, "timeseries.csv")
    if path is None:
        return False
    try:
        series = read_table(path, ["time", "floor_velocity"])
    except PlotError:
        return False
    time, speed = series["time"], np.abs(series["floor_velocity"])
    expected = numbers["vertical_speed_amplitude"]
    if speed.size == 0 or speed.max() > expected * 1.001 + 1e-12:
        return False
    steady = speed[time >= numbers["start"] + numbers["ramp"]]
    if expected == 0.0:
        return True
    if steady.size >= 20:  # enough phases sampled: the peak must be close to the amplitude
        return steady.max() >= 0.7 * expected
    return True
