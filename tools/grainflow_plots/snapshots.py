"""Projected snapshots of the bed at eight phases of the floor cycle (Lan 1994 Figs. A4.10, A5.10).

snapshots/particles.pvd + snapshots/particles_NNNNNN.vtu (or .pvtu with its pieces, from MPI ranks)
[+ timeseries.csv] -> snapshots_phases.png:
    every particle as a circle of 0.4 times its radius, projected on the plane of the gravity axis and
    one horizontal axis (the convection plane of convection.csv when it exists, else the horizontal
    axis along which the bed is widest), the floor as a dotted line where timeseries.csv puts it at
    that instant. The eight snapshots are those nearest to the phases 0, pi/4, ..., 7 pi/4 within the
    last floor cycle when the snapshots sample it that densely; else, when the floor moves, those
    nearest to the eight phases among the later half of the snapshots (from several cycles); else
    the last eight.

The VTU files are grainflow's ASCII unstructured grids (src/grainflow/io/vtu_writer.cpp), read with
the standard library's XML parser.
"""

import glob
import math
import os
import xml.etree.ElementTree as ET

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import EllipseCollection

from .common import AXES, PlotError, existing, floor_phase, pi_label, read_table, save_atomically
from .convection import axis_names

PANELS = 8
REDUCTION = 0.4  # drawn radius / true radius


def plot(outdir, info):
    folder = os.path.join(outdir, "snapshots")
    series = snapshot_list(folder)
    if not series:
        return []
    floor = floor_motion(outdir)
    picks, note = choose(series, floor, info)
    snapshots = [(series[k][0], read_vtu(series[k][1])) for k in picks]
    return [draw(outdir, info, snapshots, floor, note)]


def snapshot_list(folder):
    """[(time or None, path)] of the particles' files in time order: from particles.pvd (part 0; the
    walls' surfaces are further parts), else the VTU files by name."""
    pvd = os.path.join(folder, "particles.pvd")
    if os.path.isfile(pvd):
        try:
            root = ET.parse(pvd).getroot()
        except ET.ParseError as error:
            raise PlotError(f"{pvd}: not valid XML ({error})") from error
        entries = []
        for data_set in root.iter("DataSet"):
            try:
                time = float(data_set.get("timestep", ""))
            except ValueError as error:
                raise PlotError(f"{pvd}: DataSet timestep '{data_set.get('timestep')}' is not a number") from error
            name = data_set.get("file")
            if not name:
                raise PlotError(f"{pvd}: a DataSet has no file attribute")
            if data_set.get("part", "0") != "0":  # the walls' surfaces (.vtp) beside the particles
                continue
            path = os.path.join(folder, name)
            if os.path.isfile(path):  # an entry of an interrupted run may be missing
                entries.append((time, path))
        return sorted(entries, key=lambda entry: entry[0])
    return [(None, path) for path in sorted(glob.glob(os.path.join(folder, "particles_*.vtu")))]


def read_vtu(path):
    """{'position': [N, 3], 'radius': [N], 'species': [N] or None, 'velocity': [N, 3] or None,
    'id': [N] or None} of one
    grainflow VTU file, or of a parallel index (.pvtu, an MPI run's) with its pieces joined."""
    if path.endswith(".pvtu"):
        return read_pvtu(path)
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as error:
        raise PlotError(f"{path}: not a readable VTU file ({error})") from error
    piece = root.find("./UnstructuredGrid/Piece")
    if piece is None:
        raise PlotError(f"{path}: no UnstructuredGrid/Piece element")
    try:
        count = int(piece.get("NumberOfPoints", ""))
    except ValueError as error:
        raise PlotError(f"{path}: Piece has no NumberOfPoints") from error

    def array(element, components):
        if element is None:
            return None
        try:
            values = np.array((element.text or "").split(), dtype=float)
        except ValueError as error:
            raise PlotError(f"{path}: DataArray '{element.get('Name')}' holds a value that is not a number") from error
        if values.size != count * components:
            raise PlotError(f"{path}: DataArray '{element.get('Name')}' has {values.size} values, expected "
                            f"{count * components}")
        return values.reshape(count, components) if components > 1 else values

    position = array(piece.find("./Points/DataArray"), 3)
    if position is None:
        raise PlotError(f"{path}: no Points")
    data = {element.get("Name"): element for element in piece.findall("./PointData/DataArray")}
    radius = array(data.get("radius"), 1)
    if radius is None:
        diameter = array(data.get("diameter"), 1)
        if diameter is None:
            raise PlotError(f"{path}: no 'radius' or 'diameter' array")
        radius = 0.5 * diameter
    species = array(data.get("species"), 1)
    ids = array(data.get("id"), 1)
    return {"position": position, "radius": radius, "species": None if species is None else species.astype(int),
            "velocity": array(data.get("velocity"), 3), "id": None if ids is None else ids.astype(np.int64)}


def read_pvtu(path):
    """The pieces a .pvtu names (each MPI rank's particles), joined as one snapshot."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as error:
        raise PlotError(f"{path}: not a readable PVTU file ({error})") from error
    sources = [piece.get("Source") for piece in root.iter("Piece")]
    if not sources or not all(sources):
        raise PlotError(f"{path}: no Piece with a Source")
    pieces = [read_vtu(os.path.join(os.path.dirname(path), source)) for source in sources]
    joined = {}
    for key in ("position", "radius", "species", "velocity", "id"):
        values = [piece[key] for piece in pieces]
        joined[key] = None if any(v is None for v in values) else np.concatenate(values)
    return joined


def floor_motion(outdir):
    """(time, floor_position, floor_velocity) from timeseries.csv, or None (no file, no such columns)."""
    path = existing(outdir, "timeseries.csv")
    if path is None:
        return None
    try:
        table = read_table(path, ["time", "floor_position", "floor_velocity"])
    except PlotError:
        return None  # the time-series figure reports a malformed file; event-driven runs have no floor
    return (table["time"], table["floor_position"], table["floor_velocity"]) if len(table) else None


def floor_at(floor, time):
    """(position, velocity) of the floor at `time` (linear interpolation of the time series)."""
    t, x, v = floor
    return float(np.interp(time, t, x)), float(np.interp(time, t, v))


def choose(series, floor, info):
    """Indices of the PANELS snapshots to draw, and a note for the title."""
    count = len(series)
    last = list(range(max(0, count - PANELS), count))
    times = np.array([t if t is not None else np.nan for t, _ in series])
    if count <= PANELS or floor is None or np.any(np.isnan(times)):
        return last, f"the last {len(last)} snapshots"
    states = np.array([floor_at(floor, t) for t in times])
    phase = floor_phase(states[:, 0], states[:, 1], reference=floor[1:])
    if phase is None:
        return last, "the last 8 snapshots (the floor rests)"
    f = info.drive_frequency
    cycle = times >= times[-1] - 1.0 / f if f else np.zeros(count, dtype=bool)
    if np.count_nonzero(cycle) >= PANELS:
        candidates, note = np.nonzero(cycle)[0], "phases 0, \u03c0/4, ..., 7\u03c0/4 of the last floor cycle"
    else:
        candidates = np.arange(count // 2, count)
        note = "nearest to phases 0, \u03c0/4, ..., 7\u03c0/4 among the later snapshots (several cycles)"
    picks = []
    for k in range(PANELS):
        target = k * 2.0 * math.pi / PANELS
        distance = np.abs(np.angle(np.exp(1j * (phase[candidates] - target))))
        best = np.flatnonzero(distance <= distance.min() + 1e-9)[-1]  # the latest of equals
        picks.append(int(candidates[best]))
    return picks, note


def plane_axes(outdir, info, snapshots):
    """(horizontal, vertical) axis indices of the projection plane."""
    vertical = info.gravity_axis
    path = existing(outdir, "convection.csv")
    if path:
        try:
            (name, _), _ = axis_names(read_table(path))
        except PlotError:
            name = None
        if name and name in AXES and AXES.index(name) != vertical:
            return AXES.index(name), vertical
    position = snapshots[-1][1]["position"]
    others = [k for k in range(3) if k != vertical]
    return max(others, key=lambda k: float(np.ptp(position[:, k])) if position.size else 0.0), vertical


def draw(outdir, info, snapshots, floor, note):
    h, v = plane_axes(outdir, info, snapshots)
    scale, unit = info.length_scale()
    left = min(float((s["position"][:, h] - s["radius"]).min(initial=np.inf)) for _, s in snapshots)
    right = max(float((s["position"][:, h] + s["radius"]).max(initial=-np.inf)) for _, s in snapshots)
    bottom = min(float((s["position"][:, v] - s["radius"]).min(initial=np.inf)) for _, s in snapshots)
    top = max(float((s["position"][:, v] + s["radius"]).max(initial=-np.inf)) for _, s in snapshots)
    floors = [floor_at(floor, t)[0] if floor is not None and t is not None else None for t, _ in snapshots]
    bottom = min([bottom] + [x for x in floors if x is not None])
    if not np.isfinite(left):  # no particles
        left, right, bottom, top = 0.0, 1.0, 0.0, 1.0
    aspect = (right - left) / max(top - bottom, 1e-30)
    # Panels side by side for a tall bed, stacked for a long one (Lan's 100 d x 1 d cell).
    ncols, panel_height = ((8, 5.5) if aspect < 0.4 else (4, 3.6) if aspect < 1.5 else
                           (2, 2.6) if aspect < 5.0 else (1, 1.3))
    nrows = math.ceil(len(snapshots) / ncols)
    figure, axes = plt.subplots(nrows, ncols, figsize=(12.0, nrows * panel_height + 1.0), squeeze=False,
                                sharex=True, sharey=True)
    for k, ((time, snapshot), floor_position) in enumerate(zip(snapshots, floors)):
        a = axes[k // ncols, k % ncols]
        position, radius = snapshot["position"], snapshot["radius"]
        species = snapshot["species"] if snapshot["species"] is not None else np.zeros(radius.size, dtype=int)
        size = 2.0 * REDUCTION * scale * radius
        circles = EllipseCollection(size, size, np.zeros(radius.size), units="xy",
                                    offsets=scale * position[:, [h, v]], offset_transform=a.transData,
                                    facecolors=[f"C{s % 10}" for s in species], edgecolors="k", linewidths=0.3)
        a.add_collection(circles)
        title = "" if time is None else f"t = {time:.4g} s"
        if floor_position is not None:
            a.axhline(scale * floor_position, color="k", linestyle=":", linewidth=1.0)
            state = floor_at(floor, time)
            phase = floor_phase(np.array([state[0]]), np.array([state[1]]), reference=floor[1:])
            if phase is not None:
                title += f", \u03c6 = {pi_label(float(phase[0]))}"
        a.set_title(title, fontsize=8)
        a.set_aspect("equal")
    for k in range(len(snapshots), nrows * ncols):
        axes[k // ncols, k % ncols].set_visible(False)
    a = axes[0, 0]
    a.set_xlim(scale * left, scale * right)
    a.set_ylim(scale * bottom, scale * top)
    label = (lambda k: f"{AXES[k]} / d") if unit == "/ d" else (lambda k: f"{AXES[k]} (m)")
    for a in axes[-1, :]:
        a.set_xlabel(label(h), fontsize=8)
    for a in axes[:, 0]:
        a.set_ylabel(label(v), fontsize=8)
    figure.suptitle(info.title() + f"\nspheres at {REDUCTION:g}\u00d7 their radius projected on the "
                    f"{AXES[h]}-{AXES[v]} plane, floor dotted (Lan Figs. A4.10, A5.10): {note}", fontsize=9)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "snapshots_phases.png"))
