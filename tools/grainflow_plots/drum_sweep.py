"""A `grainflow sweep` of the rotating drum over its angular velocity: the form of motion and the
dynamic angle of repose of each run against the Froude number Fr = omega^2 R / g.

sweep.csv + <run>/resolved_case.toml + <run>/snapshots/ -> drum_regimes.csv, drum_regimes.png
    (the later half of each run's snapshots: the steady part).

R, omega and the axis come from the run's resolved_case.toml: the [[geometry]] entry of kind
"cylinder" (its `radius`, `center` and an angular velocity key: see drum_parameters). When the case
does not give omega, the varied key of sweep.csv that names an angular velocity (or omega) does; a
vector value gives its z component. g is the magnitude of gravity.vector (9.81 by default, as the
case loader), d twice the snapshots' median radius.

Mellmann's (2001) ranges of Fr for each form of motion are drawn for reference: slumping 1e-5 to
1e-3, rolling 1e-4 to 1e-2, cascading 1e-3 to 1e-1, cataracting 0.1 to 1, centrifuging >= 1, as
they are usually quoted from his Table 1 (approximate: the boundaries also depend on the filling
degree and the wall friction, and overlap).
"""

import csv
import math
import os
import re
import sys

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.transforms import blended_transform_factory

from .common import PlotError, existing, save_atomically, tomllib
from .drum import REGIMES, classify_regime
from .snapshots import read_vtu, snapshot_list
from .sweep import read_sweep_csv

MELLMANN_BANDS = {"slumping": (1e-5, 1e-3), "rolling": (1e-4, 1e-2), "cascading": (1e-3, 1e-1),
                  "cataracting": (1e-1, 1.0), "centrifuging": (1.0, math.inf)}
MARKERS = {"slumping": "v", "rolling": "o", "cascading": "s", "cataracting": "^", "centrifuging": "*"}
COLUMNS = ["Fr", "angular_velocity", "regime", "angle_deg", "angle_std_deg", "surface_curvature",
           "airborne_fraction", "corotating_fraction", "surface_bend_deg", "run"]
OMEGA_KEYS = ("angular_velocity", "omega", "angular_speed", "rotation_rate")
DEFAULT_GRAVITY = 9.81
MAX_SNAPSHOTS = 40  # of the later half, evenly spread: enough for the angle's spread, quick to read


def analyze_sweep(sweep_dir, radius=None, gravity=None, max_snapshots=MAX_SNAPSHOTS):
    """Classifies every successful run of the sweep in `sweep_dir` and writes drum_regimes.csv and
    drum_regimes.png there. `radius` and `gravity` override what the runs' case files give.
    Returns (rows as dicts of COLUMNS, [paths written]). PlotError names the file at fault."""
    path = existing(sweep_dir, "sweep.csv")
    if path is None:
        raise PlotError(f"{sweep_dir}: no sweep.csv (not a `grainflow sweep` folder)")
    header, records = read_sweep_csv(path)
    keys = header[:header.index("run")]
    rows = []
    for record in records:
        run_dir = os.path.join(sweep_dir, record["run"])
        if record["status"].strip() != "0":
            print(f"drum_analysis: {run_dir}: left out (status {record['status']})", file=sys.stderr)
            continue
        parameters = drum_parameters(run_dir, {key: record[key] for key in keys}, radius, gravity)
        snapshots = steady_snapshots(run_dir, max_snapshots)
        if not snapshots:
            print(f"drum_analysis: {run_dir}: left out (no snapshots)", file=sys.stderr)
            continue
        d = 2.0 * float(np.median(snapshots[-1]["radius"]))
        result = classify_regime(snapshots, parameters["omega"], parameters["R"], parameters["g"], d,
                                 parameters["center"])
        rows.append({"Fr": result["froude"], "angular_velocity": parameters["omega"], "regime": result["regime"],
                     "angle_deg": result["angle_deg"], "angle_std_deg": result["angle_std_deg"],
                     "surface_curvature": result["surface_curvature"],
                     "airborne_fraction": result["airborne_fraction"],
                     "corotating_fraction": result["corotating_fraction"],
                     "surface_bend_deg": result["surface_bend_deg"], "run": record["run"]})
    rows.sort(key=lambda row: row["Fr"])
    written = [write_table(sweep_dir, rows)]
    if rows:
        written.append(draw(sweep_dir, rows))
    return rows, written


def steady_snapshots(run_dir, max_snapshots=MAX_SNAPSHOTS):
    """The later half of a run's snapshots (at most `max_snapshots`, evenly spread), read."""
    series = snapshot_list(os.path.join(run_dir, "snapshots"))
    later = series[len(series) // 2:]
    if len(later) > max_snapshots:
        later = [later[k] for k in np.linspace(0, len(later) - 1, max_snapshots).round().astype(int)]
    return [read_vtu(file) for _, file in later]


def drum_parameters(run_dir, varied=None, radius=None, gravity=None):
    """{'R', 'omega', 'g', 'center'} of a drum run: the cylinder of its resolved_case.toml (a
    [[geometry]] entry with kind, type or shape "cylinder", or the only one with a radius), else the
    varied values of sweep.csv for omega and the `radius` argument for R."""
    case = read_case(run_dir)
    cylinder = find_cylinder(case)
    R = radius if radius is not None else scalar(cylinder.get("radius"))
    if R is None or not R > 0.0:
        raise PlotError(f"{run_dir}: no drum radius (no [[geometry]] cylinder with a radius in "
                        "resolved_case.toml; give --radius)")
    omega = find_omega(cylinder)
    if omega is None:
        for key, text in (varied or {}).items():
            if any(name in key.rsplit(".", 1)[-1] for name in OMEGA_KEYS):
                omega = axis_component(parse_value(text))
    if omega is None:
        raise PlotError(f"{run_dir}: no angular velocity (neither the [[geometry]] cylinder nor a varied key "
                        "named like angular_velocity gives it)")
    if gravity is None:
        vector = case.get("gravity", {}).get("vector", [0.0, -DEFAULT_GRAVITY, 0.0])
        gravity = math.sqrt(sum(float(v) ** 2 for v in vector))
    center = next((cylinder[k] for k in ("center", "centre", "origin", "point") if k in cylinder), (0.0, 0.0))
    center = [float(v) for v in center]
    center = (center[0], center[1])  # [x, y, z] or [x, y]: the axis is along z
    return {"R": float(R), "omega": float(omega), "g": float(gravity), "center": center}


def read_case(run_dir):
    path = existing(run_dir, "resolved_case.toml")
    if path is None or tomllib is None:
        return {}
    try:
        with open(path, "rb") as handle:
            return tomllib.load(handle)
    except (OSError, tomllib.TOMLDecodeError) as error:
        raise PlotError(f"{path}: not a readable case file ({error})") from error


def find_cylinder(case):
    entries = case.get("geometry", [])
    entries = [entries] if isinstance(entries, dict) else [e for e in entries if isinstance(e, dict)]
    for entry in entries:
        if any(str(entry.get(k, "")).lower() == "cylinder" for k in ("kind", "type", "shape")):
            return entry
    with_radius = [e for e in entries if "radius" in e]
    return with_radius[0] if len(with_radius) == 1 else {}


def find_omega(table):
    """An angular velocity key of the table or of a table inside it (e.g. a motion table)."""
    for key in OMEGA_KEYS:
        if key in table:
            return axis_component(table[key])
    if "rpm" in table:
        return axis_component(table["rpm"]) * 2.0 * math.pi / 60.0
    for value in table.values():
        if isinstance(value, dict):
            found = find_omega(value)
            if found is not None:
                return found
    return None


def scalar(value):
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def axis_component(value):
    """A number, or the z component of a vector (the drum's axis)."""
    if isinstance(value, (list, tuple)) and len(value) == 3:
        return scalar(value[2])
    return scalar(value)


def parse_value(text):
    """A sweep.csv cell as a number or a list of numbers (`1.5`, `[0, 0, 1.5]`); None otherwise."""
    numbers = re.findall(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", text)
    try:
        values = [float(n) for n in numbers]
    except ValueError:
        return None
    if text.strip().startswith("["):
        return values
    return values[0] if len(values) == 1 else None


def format_number(value):
    return "" if value is None else "nan" if isinstance(value, float) and math.isnan(value) else f"{value:.6g}"


def write_table(sweep_dir, rows):
    path = os.path.join(sweep_dir, "drum_regimes.csv")
    temporary = f"{path}.tmp-{os.getpid()}"
    try:
        with open(temporary, "w", newline="") as handle:
            handle.write(f"# drum regimes of the sweep {os.path.basename(os.path.normpath(sweep_dir))}: one row per "
                         "run, the later half of its snapshots (tools/drum_analysis.py, criteria in "
                         "tools/grainflow_plots/drum.py)\n")
            handle.write("# units: Fr = omega^2 R / g dimensionless; angular_velocity rad/s; angles and their std "
                         "degrees (nan, as the surface measures, when centrifuging); surface_curvature "
                         "dimensionless (curvature x fitted chord length); fractions of the particles\n")
            writer = csv.writer(handle)
            writer.writerow(COLUMNS)
            for row in rows:
                writer.writerow([row[c] if isinstance(row[c], str) else format_number(row[c]) for c in COLUMNS])
        os.replace(temporary, path)
    except OSError as error:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise PlotError(f"cannot write {path}: {error.strerror}") from error
    return path


def draw(sweep_dir, rows):
    figure, (bands, axes) = plt.subplots(2, 1, figsize=(8.0, 6.5), sharex=True,
                                         gridspec_kw={"height_ratios": [1, 3]})
    froude = np.array([row["Fr"] for row in rows])
    positive = froude[froude > 0.0]
    left = min(1e-5, positive.min() / 2.0) if positive.size else 1e-5
    right = max(3.0, positive.max() * 2.0) if positive.size else 3.0
    for k, regime in enumerate(REGIMES):
        lo, hi = MELLMANN_BANDS[regime]
        bands.broken_barh([(lo, min(hi, right) - lo)], (k - 0.4, 0.8), facecolors=f"C{k}", alpha=0.35)
    bands.set_yticks(range(len(REGIMES)), REGIMES, fontsize=7)
    bands.invert_yaxis()
    bands.set_title("Mellmann (2001) ranges of Fr (approximate; they depend on filling and friction)", fontsize=8)
    bottom = blended_transform_factory(axes.transData, axes.transAxes)
    for k, regime in enumerate(REGIMES):
        chosen = [row for row in rows if row["regime"] == regime]
        if not chosen:
            continue
        x = np.array([row["Fr"] for row in chosen])
        y = np.array([row["angle_deg"] for row in chosen])
        error = np.array([row["angle_std_deg"] for row in chosen])
        surface = np.isfinite(y)
        if np.any(surface):
            axes.errorbar(x[surface], y[surface], yerr=np.nan_to_num(error[surface]), fmt=MARKERS[regime],
                          color=f"C{k}", capsize=3, label=regime)
        if np.any(~surface):  # no free surface (centrifuging): marked along the bottom
            axes.plot(x[~surface], np.full(np.count_nonzero(~surface), 0.03), MARKERS[regime], color=f"C{k}",
                      markersize=9, transform=bottom, label=None if np.any(surface) else f"{regime} (no surface)")
    axes.set_xscale("log")
    axes.set_xlim(left, right)
    axes.set_xlabel("Froude number Fr = \u03c9\u00b2R/g")
    axes.set_ylabel("dynamic angle of repose (degrees)")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize=8)
    figure.suptitle(f"rotating drum sweep {os.path.basename(os.path.normpath(sweep_dir))}: surface angle "
                    "(mean \u00b1 std over the later snapshots) and form of motion", fontsize=9)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(sweep_dir, "drum_regimes.png"))
