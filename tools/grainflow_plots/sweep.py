"""A sweep folder (`grainflow sweep`): the runs' results against the varied value, Gamma when the
summaries give it (Lan 1994 section 4.2).

sweep.csv -> one figure per summary field present, with its error bars (`<field>_error`):
    sweep_bed_height.png (Fig. A4.5), sweep_bulk_solids_fraction.png (A4.6),
    sweep_density_peak.png (height of the solids-fraction peak, A4.8),
    sweep_cell_temperature.png (A4.11; the summary's granular_temperature when there is no
    cell_temperature), sweep_collisions.png (collisions per particle per second, A4.12),
    sweep_convection_speed.png (chapter 5).
<run>/profiles.csv -> sweep_profiles.png: the runs' W(Y) and nu(Y) overlaid (Figs. A4.4, A4.7,
    A4.18, A4.19) and sweep_mass_below.png (Fig. A4.9), each curve labelled by its value.
<run>/profiles.csv of event-driven runs -> sweep_strip_profiles.png: the runs' nu and translational
    temperature against y/H (chute) or y/gap (Couette; temperature x (H/U_T)^2) overlaid, e.g.
    Campbell's (1982) depth series of Fig. 3.10.
<run>/analysis/distributions.json (event-driven) -> sweep_distributions.png: Savage-Jeffrey's S
    against the solids fraction (Campbell's Figs. 3.40-3.41: S grows with density, an order
    parameter) and the fitted exponent ratios a_i / a_mi of X1..X5 against S (section 3.4.1: 1 for
    a Maxwellian), each with its error bar.
<run>/analysis/diffusion.json -> sweep_diffusion.png: the horizontal diffusion coefficients against
    the granular temperature of the same component (Fig. A4.24; the solids-weighted mean of the
    profile's temperature_x|y|z, else the cell temperature) and against Gamma (Fig. A4.23).

Only runs with status 0 are drawn; the x axis is summary `shaking_acceleration` when every such run
has it and it varies, else the first varied key when its values are numbers, else the run order.
"""

import csv
import math
import os

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import cm, colors

from .common import (AXES, PlotError, RunInfo, error_bars, existing, number, read_json, read_table,
                     save_atomically, strip_profiles, zone_profiles)
from .profiles import dense_zones, draw_mass_below, finish_mass_below_axes, mass_below, occupied_zones

# (summary field, y label, file, Lan figure)
FIELDS = [
    ("bed_height", "bed height (m)", "sweep_bed_height.png", "A4.5"),
    ("bulk_solids_fraction", "bulk solids fraction \u03bd", "sweep_bulk_solids_fraction.png", "A4.6"),
    ("density_peak_Y", "Y = y/d of the solids-fraction peak", "sweep_density_peak.png", "A4.8"),
    ("cell_temperature", "cell-average granular temperature (m\u00b2/s\u00b2)", "sweep_cell_temperature.png",
     "A4.11"),
    ("collision_rate_per_particle", "collisions per particle per second (1/s)", "sweep_collisions.png", "A4.12"),
    ("convection_speed", "convection speed (m/s)", "sweep_convection_speed.png", "chapter 5"),
]
FALLBACK = {"cell_temperature": "granular_temperature"}
PROFILE_COLUMNS = ["position_lo", "position_hi", "position", "Y", "solids_fraction", "W"]


def plot(outdir, info):
    path = existing(outdir, "sweep.csv")
    if path is None:
        return []
    sweep = Sweep(outdir, path)
    if not sweep.rows:
        return []
    written = []
    for field, label, name, figure_number in FIELDS:
        written += plot_field(sweep, field, label, name, figure_number)
    written += plot_profiles(sweep)
    written += plot_strip_profiles(sweep)
    written += plot_diffusion(sweep)
    written += plot_distributions(sweep)
    return written


class Sweep:
    """sweep.csv's successful runs, their x values and labels."""

    def __init__(self, outdir, path):
        self.outdir, self.path = outdir, path
        header, rows = read_sweep_csv(path)
        self.keys = header[:header.index("run")]
        self.failed = sum(1 for row in rows if row["status"].strip() != "0")
        self.rows = [row for row in rows if row["status"].strip() == "0"]
        self.name = sweep_name(outdir, path)
        self.x, self.x_label, self.numeric, self.labels = self.axis()
        order = np.argsort(self.x, kind="stable")
        self.rows = [self.rows[k] for k in order]
        self.x, self.labels = self.x[order], [self.labels[k] for k in order]

    def value(self, row, field):
        """A summary field of a run as a float (NaN when absent or not a number)."""
        for name in (field, "summary." + field):
            text = row.get(name)
            if text is not None and text.strip():
                try:
                    return float(text)
                except ValueError:
                    return math.nan
        return math.nan

    def column(self, field):
        return np.array([self.value(row, field) for row in self.rows])

    def axis(self):
        """(x values, axis label, numeric?, run labels)."""
        gamma = self.column("shaking_acceleration")
        if gamma.size and np.all(np.isfinite(gamma)) and np.ptp(gamma) > 0.0:
            return gamma, "shaking acceleration \u0393 = a\u03c9\u00b2/g", True, [f"\u0393 = {g:.3g}" for g in gamma]
        labels = ["  ".join(f"{key}={row[key]}" for key in self.keys) for row in self.rows]
        if self.keys:
            try:
                values = np.array([float(row[self.keys[0]]) for row in self.rows])
                return values, self.keys[0], True, labels
            except ValueError:
                pass
        return np.arange(len(self.rows), dtype=float), "run", False, labels

    def title(self, what):
        note = f"; {self.failed} failed run(s) left out" if self.failed else ""
        return f"sweep of {self.name}: {len(self.rows)} runs{note}\n{what}"

    def folder(self, row):
        return os.path.join(self.outdir, row["run"])

    def finish_x(self, axes):
        axes.set_xlabel(self.x_label)
        if not self.numeric:
            axes.set_xticks(self.x, self.labels, rotation=30, ha="right", fontsize=7)


def read_sweep_csv(path):
    """(header, rows as {column: text}) of sweep.csv; PlotError naming the file when malformed."""
    try:
        with open(path, newline="") as handle:
            lines = [line for line in handle if line.strip() and not line.startswith("#")]
    except OSError as error:
        raise PlotError(f"cannot read {path}: {error.strerror}") from error
    records = list(csv.reader(lines))
    if not records:
        raise PlotError(f"{path}: no header row")
    header = records[0]
    for needed in ("run", "status"):
        if needed not in header:
            raise PlotError(f"{path}: missing column {needed}")
    rows = []
    for number_, record in enumerate(records[1:], start=1):
        if len(record) != len(header):
            raise PlotError(f"{path}: data row {number_} has {len(record)} fields, the header has {len(header)}")
        rows.append(dict(zip(header, record)))
    return header, rows


def sweep_name(outdir, path):
    """The case's stem from sweep.json (else the folder's name)."""
    json_path = existing(outdir, "sweep.json")
    case = read_json(json_path).get("case") if json_path else None
    if isinstance(case, str) and case:
        return os.path.splitext(os.path.basename(case))[0]
    return os.path.basename(os.path.normpath(outdir))


def run_colours(sweep):
    norm = colors.Normalize(vmin=0, vmax=max(len(sweep.rows) - 1, 1))
    return [cm.viridis(norm(k)) for k in range(len(sweep.rows))]


def plot_field(sweep, field, label, name, figure_number):
    values = sweep.column(field)
    source = field
    if not np.any(np.isfinite(values)) and field in FALLBACK:
        source = FALLBACK[field]
        values = sweep.column(source)
        label = "granular temperature of the bed (m\u00b2/s\u00b2)"
    if not np.any(np.isfinite(values)):
        return []
    errors = sweep.column(source + "_error")
    figure, axes = plt.subplots(figsize=(7.0, 5.0))
    axes.errorbar(sweep.x, values, yerr=error_bars(errors), color="C0", marker="o", markersize=5, capsize=3)
    axes.set_ylabel(label)
    sweep.finish_x(axes)
    axes.grid(True, alpha=0.3)
    figure.suptitle(sweep.title(f"{source} (Lan Fig. {figure_number})"), fontsize=10)
    figure.tight_layout()
    return [save_atomically(figure, os.path.join(sweep.outdir, name))]


def member_profiles(sweep):
    """[(label, colour, profile table)] of the runs that have profiles.csv."""
    found = []
    for row, label, colour in zip(sweep.rows, sweep.labels, run_colours(sweep)):
        path = zone_profiles(sweep.folder(row))
        if path:
            found.append((label, colour, read_table(path, PROFILE_COLUMNS)))
    return found


def plot_strip_profiles(sweep):
    """nu and the translational temperature of every event-driven member, overlaid."""
    members = []
    for row, label, colour in zip(sweep.rows, sweep.labels, run_colours(sweep)):
        path = strip_profiles(sweep.folder(row))
        if path:
            members.append((label, colour, read_table(path, ["y", "solids_fraction", "granular_temperature"])))
    if not members:
        return []
    figure, (left, right) = plt.subplots(1, 2, sharey=True, figsize=(9.0, 6.0))
    height_label, scaled = "y (m)", all("granular_temperature_scaled" in p for _, _, p in members)
    for label, colour, profile in members:
        height = profile["y"]
        for name, text in (("y_over_H", "y / H"), ("y_over_gap", "y / gap")):
            if name in profile:
                height, height_label = profile[name], text
        temperature = profile["granular_temperature_scaled" if scaled else "granular_temperature"]
        left.plot(profile["solids_fraction"], height, color=colour, marker="o", markersize=3, label=label)
        right.plot(temperature, height, color=colour, marker="o", markersize=3, label=label)
    left.set_xlabel("solids fraction \u03bd")
    left.set_ylabel(height_label)
    right.set_xlabel("translational temperature \u27e8v\u2032\u00b2\u27e9/D"
                     + (" \u00d7 (H/U_T)\u00b2" if scaled else " (m\u00b2/s\u00b2)"))
    right.legend(loc="best", fontsize=7)
    for a in (left, right):
        a.grid(True, alpha=0.3)
        a.set_xlim(left=0.0)
    left.set_ylim(bottom=0.0)
    figure.suptitle(sweep.title("strip profiles (Campbell 1982, e.g. Fig. 3.10)"), fontsize=10)
    figure.tight_layout()
    return [save_atomically(figure, os.path.join(sweep.outdir, "sweep_strip_profiles.png"))]


def plot_profiles(sweep):
    members = member_profiles(sweep)
    if not members:
        return []
    figure, (left, right) = plt.subplots(1, 2, sharey=True, figsize=(9.0, 6.0))
    top = 0.0
    for label, colour, profile in members:
        count = occupied_zones(profile)
        if count == 0:
            continue
        y, solids = profile["Y"][:count], profile["solids_fraction"][:count]
        thickness = profile["position_hi"][:count] - profile["position_lo"][:count]
        dense, _ = dense_zones(None, solids, thickness)  # W of (nearly) empty zones is meaningless
        left.plot(np.where(dense, profile["W"][:count], np.nan), y, color=colour, marker="o", markersize=3,
                  label=label)
        right.plot(solids, y, color=colour, marker="o", markersize=3, label=label)
        top = max(top, float(y[-1]) + 0.5)
    left.set_xlabel("W = \u221a(T / g d)")
    left.set_ylabel("Y = y / d")
    right.set_xlabel("solids fraction \u03bd")
    right.legend(loc="upper right", fontsize=7)
    for a in (left, right):
        a.grid(True, alpha=0.3)
        a.set_xlim(left=0.0)
    if top > 0.0:
        left.set_ylim(0.0, top)
    figure.suptitle(sweep.title("depth profiles (Lan Figs. A4.4, A4.7, A4.18, A4.19)"), fontsize=10)
    figure.tight_layout()
    written = [save_atomically(figure, os.path.join(sweep.outdir, "sweep_profiles.png"))]

    figure, axes = plt.subplots(figsize=(6.0, 6.0))
    lowest = 0.0
    for label, colour, profile in members:
        curve = mass_below(profile)
        if curve is not None:
            draw_mass_below(axes, curve, color=colour, marker="o", markersize=2, label=label)
            lowest = min(lowest, float(curve[0][0]))
    finish_mass_below_axes(axes, lowest)
    axes.legend(loc="lower right", fontsize=7)
    figure.suptitle(sweep.title("mass below depth Y (Lan Fig. A4.9)"), fontsize=10)
    figure.tight_layout()
    written.append(save_atomically(figure, os.path.join(sweep.outdir, "sweep_mass_below.png")))
    return written


def component_temperatures(folder):
    """Solids-weighted mean of the profile's temperature_x|y|z over the zones ({axis: T}), or {}."""
    path = existing(folder, "profiles.csv")
    if path is None:
        return {}
    profile = read_table(path, PROFILE_COLUMNS)
    weight = profile["solids_fraction"] * (profile["position_hi"] - profile["position_lo"])
    if weight.sum() <= 0.0:
        return {}
    return {a: float(np.sum(weight * profile[f"temperature_{a}"]) / weight.sum())
            for a in AXES if f"temperature_{a}" in profile}


def json_number(mapping, key, default):
    value = number(mapping, key)
    return default if value is None else value


def plot_diffusion(sweep):
    points = []  # (x, {axis: T}, diffusion.json)
    gravity_axis = None
    for x, row in zip(sweep.x, sweep.rows):
        folder = sweep.folder(row)
        path = existing(folder, "analysis", "diffusion.json")
        if path is None:
            continue
        if gravity_axis is None:
            summary_path = existing(folder, "summary.json")
            gravity_axis = RunInfo(folder, read_json(summary_path) if summary_path else {}).gravity_axis
        temperatures = component_temperatures(folder)
        cell = sweep.value(row, "cell_temperature")
        if not math.isfinite(cell):
            cell = sweep.value(row, "granular_temperature")
        points.append((x, {a: temperatures.get(a, cell) for a in AXES}, read_json(path)))
    if not points:
        return []
    horizontal = [a for k, a in enumerate(AXES) if k != gravity_axis]
    panels = 2 if sweep.numeric else 1
    figure, axes = plt.subplots(1, panels, figsize=(6.0 * panels, 5.0), squeeze=False)
    by_temperature = axes[0, 0]
    for k, a in enumerate(horizontal):
        colour = f"C{k}"
        for kind, filled in (("vacf", True), ("msd", False)):
            d = np.array([json_number(p[2], f"d_{kind}_{a}", math.nan) for p in points])
            error = error_bars(np.array([json_number(p[2], f"d_{kind}_{a}_error", math.nan) for p in points]))
            t = np.array([p[1][a] for p in points])
            style = {"color": colour, "marker": "o", "linestyle": "none", "capsize": 3,
                     "markerfacecolor": colour if filled else "none",
                     "label": f"D_{a} from the {'VACF' if kind == 'vacf' else 'MSD'}"}
            by_temperature.errorbar(t, d, yerr=error, **style)
            if panels == 2:
                x = np.array([p[0] for p in points])
                axes[0, 1].errorbar(x, d, yerr=error, **style)
    by_temperature.set_xlabel("granular temperature T_a of the same component (m\u00b2/s\u00b2)")
    by_temperature.set_title("against temperature (Lan Fig. A4.24)", fontsize=9)
    if panels == 2:
        sweep.finish_x(axes[0, 1])
        axes[0, 1].set_title("against the varied value (Lan Fig. A4.23)", fontsize=9)
    for a in axes[0]:
        a.set_ylabel("self-diffusion coefficient (m\u00b2/s)")
        a.legend(loc="upper left", fontsize=8)
        a.grid(True, alpha=0.3)
    figure.suptitle(sweep.title("horizontal self-diffusion coefficients"), fontsize=10)
    figure.tight_layout()
    return [save_atomically(figure, os.path.join(sweep.outdir, "sweep_diffusion.png"))]


def plot_distributions(sweep):
    points = []  # distributions.json of each run that has one
    for row in sweep.rows:
        path = existing(sweep.folder(row), "analysis", "distributions.json")
        if path:
            points.append(read_json(path))
    if len(points) < 2:
        return []
    nu = np.array([json_number(p, "solids_fraction", math.nan) for p in points])
    s = np.array([json_number(p, "s", math.nan) for p in points])
    order = np.argsort(nu)
    figure, (left, right) = plt.subplots(1, 2, figsize=(12.0, 5.0))
    left.plot(nu[order], s[order], "ko-", label="S = 2R (du/dy) / <u'^2>^1/2")
    s_uv = np.array([json_number(p, "s_uv", math.nan) for p in points])
    if np.any(np.isfinite(s_uv)):
        left.plot(nu[order], s_uv[order], "s--", color="0.5", markerfacecolor="none",
                  label="S with <u'^2> + <v'^2> (the listing's)")
    left.set_xlabel("solids fraction \u03bd of the analysed strips")
    left.set_ylabel("Savage-Jeffrey S")
    left.set_title("S against density (Campbell Figs. 3.40-3.41)", fontsize=9)
    for k in range(1, 7):
        ratio = np.array([json_number(p, f"a{k}_ratio", math.nan) for p in points])
        if not np.any(np.isfinite(ratio)):
            continue
        error = error_bars(np.array([json_number(p, f"a{k}_ratio_error", math.nan) for p in points]))
        components = points[0].get(f"a{k}_components", "")
        right.errorbar(s[order], ratio[order], yerr=None if error is None else error[order], marker="o", capsize=3,
                       label=f"X{k} ({components})")
    right.axhline(1.0, color="k", lw=0.8, ls=":")
    right.set_xlabel("Savage-Jeffrey S")
    right.set_ylabel("a_i / a_mi (1: Maxwellian)")
    right.set_title("fitted exponents against S (Campbell section 3.4.1)", fontsize=9)
    for axis in (left, right):
        axis.legend(loc="best", fontsize=8)
        axis.grid(True, alpha=0.3)
    figure.suptitle(sweep.title("velocity distributions across the runs"), fontsize=10)
    figure.tight_layout()
    return [save_atomically(figure, os.path.join(sweep.outdir, "sweep_distributions.png"))]
