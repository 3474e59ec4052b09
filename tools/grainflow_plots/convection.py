"""Convection: the long-term mean velocity field in a vertical plane (Lan 1994 chapter 5).

convection.csv -> convection.png: arrows of the mean velocity of each cell, length proportional to
    the speed, empty cells left blank (Figs. A5.1, A5.3-A5.8, A5.16).
convection.csv -> convection_columns.png: the mean speed of each column of cells against the
    horizontal position, and the speed over the plane as a colour map (Figs. A5.2, A5.9).
convection_phases.csv -> convection_phases.png: one small arrow field per bin of the floor cycle,
    on a common scale (Fig. A5.11).

The comment line `# convection field: horizontal axis z, vertical axis y, cell 0.1 m` names the
axes; positions are drawn in diameters when d is known.
"""

import math
import os
import re

import matplotlib.pyplot as plt
import numpy as np

from .common import PlotError, existing, read_table, save_atomically

COLUMNS = ["column", "row", "horizontal", "vertical", "visits", "velocity_horizontal", "velocity_vertical", "speed"]
ARROW_CELL_SHARE = 0.9  # the fastest cell's arrow spans this share of a cell


def plot_mean(outdir, info):
    """convection.png and convection_columns.png from convection.csv."""
    path = existing(outdir, "convection.csv")
    if path is None:
        return []
    table = read_table(path, COLUMNS)
    if len(table) == 0:
        return []
    field = Field(table, info)
    return [plot_field(outdir, info, field), plot_columns(outdir, info, field)]


def plot_phase_bins(outdir, info):
    """convection_phases.png from convection_phases.csv."""
    path = existing(outdir, "convection_phases.csv")
    if path is None:
        return []
    table = read_table(path, ["phase_bin"] + COLUMNS)
    return [plot_phases(outdir, info, table)] if len(table) else []


class Field:
    """The cells of a convection table (or of one phase bin of it) in plot units."""

    def __init__(self, table, info, rows=None):
        keep = np.ones(len(table), dtype=bool) if rows is None else rows
        self.axes, cell = axis_names(table)
        self.scale, unit = info.length_scale()
        self.unit = unit
        self.h = self.scale * table["horizontal"][keep]
        self.v = self.scale * table["vertical"][keep]
        self.column = table["column"][keep].astype(int)
        self.samples = table["visits"][keep]
        self.u = table["velocity_horizontal"][keep]
        self.w = table["velocity_vertical"][keep]
        self.speed = table["speed"][keep]
        self.filled = self.samples > 0
        self.cell = self.scale * cell if cell else self.spacing()

    def spacing(self):
        """Cell size from the centres when the comment does not give it."""
        steps = np.diff(np.unique(np.concatenate([self.h, self.v])))
        steps = steps[steps > 1e-12 * max(1.0, float(np.abs(self.h).max(initial=1.0)))]
        return float(steps.min()) if steps.size else 1.0

    def label(self, which):
        name = self.axes[0 if which == "horizontal" else 1]
        return f"{name} {self.unit}" if self.unit == "/ d" else f"{name} (m)"

    def max_speed(self):
        return float(self.speed[self.filled].max()) if np.any(self.filled) else 0.0


def axis_names(table):
    """(horizontal, vertical) axis names and the cell size (m, None if not given) from the comment."""
    horizontal, vertical, cell = "horizontal", "vertical", None
    for line in table.comments:
        match = re.search(r"horizontal axis\s+(\w+)", line)
        if match:
            horizontal = match.group(1)
            match = re.search(r"vertical axis\s+(\w+)", line)
            vertical = match.group(1) if match else vertical
            match = re.search(r"cell\s+([0-9.eE+-]+)\s*m", line)
            if match:
                try:
                    cell = float(match.group(1))
                except ValueError as error:
                    raise PlotError(f"{table.path}: cell size '{match.group(1)}' is not a number") from error
            break
    return (horizontal, vertical), cell


def draw_field(axes, field, max_speed, key=True):
    """Arrows of the filled cells on one axes, the fastest spanning ARROW_CELL_SHARE of a cell."""
    if max_speed <= 0.0:
        axes.text(0.5, 0.5, "no motion", ha="center", va="center", transform=axes.transAxes)
        return
    scale = max_speed / (ARROW_CELL_SHARE * field.cell)  # speed per plot unit of arrow length
    f = field.filled
    arrows = axes.quiver(field.h[f], field.v[f], field.u[f], field.w[f], angles="xy", scale_units="xy", scale=scale,
                         width=0.004, headwidth=3.5, pivot="middle", color="k")
    if key:
        axes.quiverkey(arrows, 0.82, 1.02, max_speed, f"{max_speed:.3g} m/s", labelpos="E", coordinates="axes",
                       fontproperties={"size": 8})
    half = 0.5 * field.cell
    axes.set_xlim(field.h.min() - half, field.h.max() + half)
    axes.set_ylim(field.v.min() - half, field.v.max() + half)
    axes.set_aspect("equal")


def plot_field(outdir, info, field):
    width = float(np.ptp(field.h)) + field.cell
    height = float(np.ptp(field.v)) + field.cell
    aspect = width / height if height > 0 else 1.0
    figure, axes = plt.subplots(figsize=(min(14.0, max(5.0, 1.6 + 6.0 * aspect)), 6.5))
    draw_field(axes, field, field.max_speed())
    axes.set_xlabel(field.label("horizontal"))
    axes.set_ylabel(field.label("vertical"))
    empty = int(np.count_nonzero(~field.filled))
    figure.suptitle(info.title() + "\nmean velocity field (Lan Figs. A5.1, A5.3-A5.8)"
                    + (f"; {empty} empty cells left blank" if empty else ""), fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "convection.png"))


def plot_columns(outdir, info, field):
    f = field.filled
    columns = np.unique(field.column[f])
    position = np.array([field.h[f][field.column[f] == c].mean() for c in columns])
    # Sample-weighted mean speed of a column's filled cells.
    speed, samples, column = field.speed[f], field.samples[f], field.column[f]
    mean_speed = np.array([np.average(speed[column == c], weights=samples[column == c]) for c in columns])
    figure, (line, surface) = plt.subplots(2, 1, figsize=(8.0, 8.0), sharex=True)
    line.plot(position, mean_speed, color="C0", marker="o", markersize=4)
    line.set_ylabel("mean speed of the column (m/s)")
    line.set_ylim(0.0, 1.1 * float(mean_speed.max()) if mean_speed.size and mean_speed.max() > 0.0 else 1.0)
    line.grid(True, alpha=0.3)

    # Speed over the plane: cells on a regular grid, empty ones masked (blank).
    hs, vs = np.unique(np.round(field.h, 9)), np.unique(np.round(field.v, 9))
    grid = np.full((vs.size, hs.size), np.nan)
    grid[np.searchsorted(vs, np.round(field.v[f], 9)), np.searchsorted(hs, np.round(field.h[f], 9))] = field.speed[f]
    half = 0.5 * field.cell
    image = surface.imshow(np.ma.masked_invalid(grid), origin="lower", aspect="equal", cmap="viridis",
                           extent=(hs[0] - half, hs[-1] + half, vs[0] - half, vs[-1] + half), interpolation="nearest")
    figure.colorbar(image, ax=surface, label="speed (m/s)", shrink=0.9)
    surface.set_xlabel(field.label("horizontal"))
    surface.set_ylabel(field.label("vertical"))
    figure.suptitle(info.title() + "\nmean speed per column and over the plane (Lan Figs. A5.2, A5.9)", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "convection_columns.png"))


def plot_phases(outdir, info, table):
    bins = table["phase_bin"].astype(int)
    count = int(bins.max()) + 1
    if bins.min() < 0:
        raise PlotError(f"{table.path}: phase_bin must be 0 or more, found {bins.min()}")
    fields = [Field(table, info, bins == b) for b in range(count)]
    top = max(field.max_speed() for field in fields)
    first = fields[0]
    aspect = (float(np.ptp(first.h)) + first.cell) / max(float(np.ptp(first.v)) + first.cell, 1e-30)
    # Four panels a row for a square field, fewer for a long one (Lan's 100 d x 1 d cell: one).
    ncols = min(count, 4 if aspect < 1.5 else 2 if aspect < 5.0 else 1)
    nrows = math.ceil(count / ncols)
    panel_width = 15.0 / ncols
    panel_height = min(4.0, max(1.2, 0.9 * panel_width / aspect)) + 0.6
    figure, axes = plt.subplots(nrows, ncols, figsize=(ncols * panel_width + 0.6, nrows * panel_height + 0.8),
                                squeeze=False, sharex=True, sharey=True)
    for b, field in enumerate(fields):
        a = axes[b // ncols, b % ncols]
        if field.h.size:
            draw_field(a, field, top, key=False)
        else:
            a.text(0.5, 0.5, "no cells", ha="center", va="center", transform=a.transAxes)
        a.set_title(f"bin {b}: \u03c6 from {2 * b / count:.3g}\u03c0 to {2 * (b + 1) / count:.3g}\u03c0", fontsize=8)
    for b in range(count, nrows * ncols):
        axes[b // ncols, b % ncols].set_visible(False)
    for a in axes[-1, :]:
        a.set_xlabel(first.label("horizontal"), fontsize=8)
    for a in axes[:, 0]:
        a.set_ylabel(first.label("vertical"), fontsize=8)
    figure.suptitle(info.title() + f"\nmean velocity field in {count} bins of the floor cycle (Lan Fig. A5.11);"
                    f" common scale: an arrow {ARROW_CELL_SHARE:g} cell long is {top:.3g} m/s", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "convection_phases.png"))
