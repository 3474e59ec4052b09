"""A film of an event-driven run, like the one Campbell (1982 section 2.15) made of his flows.

snapshots/ of an edmd run -> animation.mp4 (with /usr/bin/ffmpeg) or animation.gif (matplotlib's
    PillowWriter, when pillow is importable): the particles as discs of their true radius (3D:
    spheres projected on the x-y plane, flow along x, velocity gradient along y), coloured by their
    velocity along the flow. At most MAX_FRAMES frames, spread evenly over the snapshots (the first
    and the last included), at most MAX_PIXELS on the longer side, so a plot stays fast. Without ffmpeg and pillow
    no film is made and a line on stdout says so.

DEM runs have snapshots_phases.png instead (snapshots.py); their folders get no film.
"""

import os
import subprocess
import tempfile

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import EllipseCollection

from .common import PlotError, is_edmd
from .snapshots import read_vtu, snapshot_list

MAX_FRAMES = 100
FRAMES_PER_SECOND = 12
DPI = 80
MAX_PIXELS = 560  # the frame's longer side
FFMPEG = "/usr/bin/ffmpeg"

try:
    import PIL  # noqa: F401  (python3-pil comes with python3-matplotlib)
    from matplotlib.animation import PillowWriter
except ImportError:  # pragma: no cover
    PillowWriter = None


def plot(outdir, info):
    series = snapshot_list(os.path.join(outdir, "snapshots"))
    if not series or not is_edmd(info):
        return []
    if not os.path.exists(FFMPEG) and PillowWriter is None:
        print(f"plot_run: no animation: neither {FFMPEG} nor Python's pillow is installed")
        return []
    frames = [series[k] for k in frame_indices(len(series), MAX_FRAMES)]
    snapshots = [(time, read_vtu(path)) for time, path in frames]
    return [film(outdir, info, snapshots)]


def frame_indices(count, limit):
    """Up to `limit` indices spread evenly over range(count), the first and the last included."""
    if count <= limit:
        return list(range(count))
    return sorted(set(int(round(k)) for k in np.linspace(0, count - 1, limit)))


def extent(snapshots):
    """(left, right, bottom, top) over every frame, particles' edges included."""
    left = min(float((s["position"][:, 0] - s["radius"]).min(initial=np.inf)) for _, s in snapshots)
    right = max(float((s["position"][:, 0] + s["radius"]).max(initial=-np.inf)) for _, s in snapshots)
    bottom = min(float((s["position"][:, 1] - s["radius"]).min(initial=np.inf)) for _, s in snapshots)
    top = max(float((s["position"][:, 1] + s["radius"]).max(initial=-np.inf)) for _, s in snapshots)
    if not np.isfinite(left):
        return 0.0, 1.0, 0.0, 1.0
    return left, right, bottom, top


def speed_range(snapshots):
    """Colour limits for u: the 2nd and 98th percentiles over all frames (a few fast particles
    would wash out the shear profile)."""
    u = np.concatenate([s["velocity"][:, 0] for _, s in snapshots if s.get("velocity") is not None] or [np.zeros(1)])
    lo, hi = np.percentile(u, [2.0, 98.0])
    return (float(lo), float(hi)) if hi > lo else (float(lo) - 1.0, float(hi) + 1.0)


def film(outdir, info, snapshots):
    left, right, bottom, top = extent(snapshots)
    aspect = (top - bottom) / max(right - left, 1e-30)
    longest = MAX_PIXELS / DPI
    # The box's shape, within 1:3 either way, plus room for the title and the labels.
    aspect = min(max(aspect, 1.0 / 3.0), 3.0)
    width, height = (longest, longest * aspect) if aspect <= 1.0 else (longest / aspect, longest)
    width, height = max(width, 2.5), max(height, 2.5)
    figure, axes = plt.subplots(figsize=(width, height))
    axes.set_xlim(left, right)
    axes.set_ylim(bottom, top)
    axes.set_aspect("equal")
    axes.set_xlabel("x (flow)")
    axes.set_ylabel("y")
    colours = plt.get_cmap("coolwarm")
    lo, hi = speed_range(snapshots)
    drawn = []

    def draw(time, snapshot):
        for artist in drawn:
            artist.remove()
        drawn.clear()
        position, radius = snapshot["position"], snapshot["radius"]
        velocity = snapshot.get("velocity")
        order = np.argsort(position[:, 2])  # 3D: nearer (larger z) spheres on top
        u = velocity[order, 0] if velocity is not None else np.zeros(order.size)
        size = 2.0 * radius[order]
        discs = EllipseCollection(size, size, np.zeros(order.size), units="xy", offsets=position[order, :2],
                                  offset_transform=axes.transData, facecolors=colours(np.clip((u - lo) / (hi - lo), 0, 1)),
                                  edgecolors="k", linewidths=0.3)
        drawn.append(axes.add_collection(discs))
        axes.set_title(f"{info.name}   t = {time:.4g}" if time is not None else info.name, fontsize=9)

    figure.tight_layout()
    path = os.path.join(outdir, "animation.mp4" if os.path.exists(FFMPEG) else "animation.gif")
    directory, name = os.path.split(path)
    stem, extension = os.path.splitext(name)
    temporary = os.path.join(directory, f".{stem}.tmp-{os.getpid()}{extension}")  # the writer needs the suffix
    try:
        if extension == ".mp4":
            encode_with_ffmpeg(figure, snapshots, draw, temporary)
        else:
            writer = PillowWriter(fps=FRAMES_PER_SECOND)
            with writer.saving(figure, temporary, DPI):
                for time, snapshot in snapshots:
                    draw(time, snapshot)
                    writer.grab_frame()
        os.replace(temporary, path)
    except (OSError, subprocess.CalledProcessError) as error:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise PlotError(f"cannot write {path}: {error}") from error
    finally:
        plt.close(figure)
    return path


def encode_with_ffmpeg(figure, snapshots, draw, target):
    """Frames to PNG files in a scratch folder, then one H.264 film (even pixel sizes for yuv420p)."""
    with tempfile.TemporaryDirectory(prefix="grainflow_film_") as scratch:
        for k, (time, snapshot) in enumerate(snapshots):
            draw(time, snapshot)
            figure.savefig(os.path.join(scratch, f"frame_{k:04d}.png"), dpi=DPI)
        subprocess.run([FFMPEG, "-y", "-loglevel", "error", "-framerate", str(FRAMES_PER_SECOND), "-i",
                        os.path.join(scratch, "frame_%04d.png"), "-vf", "scale=trunc(iw/2)*2:trunc(ih/2)*2",
                        "-pix_fmt", "yuv420p", target], check=True, capture_output=True)
