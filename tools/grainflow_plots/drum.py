"""A horizontal rotating drum (cases/geometry/rotating_drum.toml) and a vibrated cylindrical bed:
the free surface, the form of motion after Mellmann (2001), and the radial convection profile after
Knight, Jaeger & Nagel (1993).

Drum: cylinder axis along z through `center` = (x, y), radius R, gravity along -y, angular velocity
omega about +z (omega > 0: the wall at (R, 0) moves along +y, the bed is lifted on the +x side and
its surface rises towards +x, which this module counts as a positive angle).

  free_surface_angle(x, y, radius, R, center)   one snapshot's surface: angle, curvature, residual
  classify_regime(snapshots, omega, R, g, d)     slumping / rolling / cascading / cataracting /
                                                 centrifuging from a series of snapshots
  analyze_sweep(sweep_dir)                       drum_regimes.csv and drum_regimes.png of a
                                                 `grainflow sweep` over omega (drum_sweep.py)
  axial_convection_profile(snapshots, R)         mean vertical velocity in equal-area annuli of a
                                                 vibrated bed in a cylinder whose axis is along y

Snapshots are the dicts of snapshots.read_vtu ('position' [N, 3], 'radius' [N], 'velocity' [N, 3]).
Lengths are in the snapshots' unit (m); the thresholds are in particle diameters d. Mellmann
describes each form of motion qualitatively and bounds it by Fr, filling degree and wall friction;
the measurable thresholds below turn his descriptions into numbers with kinematic estimates (given at
each constant), not from fits to simulations.
"""

import math
from collections import namedtuple

import numpy as np

from .common import PlotError

REGIMES = ("slumping", "rolling", "cascading", "cataracting", "centrifuging")

# --- Free surface ---------------------------------------------------------------------------------

COLUMN_WIDTH = 2.0  # d: wide enough to hold several grains across, narrow against R ~ 20 d (20 columns)
END_EXCLUSION = 0.15  # share of the chord left out at each end: there the wall, not the flow, shapes the bed
GRID_STEP = 0.125  # d: height step of the solid-fraction profile (the crossing is interpolated)
MIN_BED = 1.5  # d: a dense stretch shorter than this is a lone grain (its dense core is < 1 d), not the bed
MIN_GAP = 1.0  # d: a dip below half density shorter than this is wall layering inside the bed, not its top

SurfaceFit = namedtuple("SurfaceFit", [
    "angle_deg",        # atan(slope) of the least-squares line through the central columns, degrees
    "curvature",        # h'' / (1 + h'^2)^1.5 of the quadratic fit at the middle of the span, 1/length
    "residual",         # rms distance of the column heights from the line, length
    "angle_error_deg",  # standard error of angle_deg from the line fit's scatter, degrees
    "bend_deg",         # largest minus smallest inclination of the cubic fit over the span, degrees
    "span",             # (x_lo, x_hi) of the fitted columns' centres, relative to the centre
    "x", "h",           # the fitted columns: centres and surface heights, relative to the centre
    "columns_x", "columns_h",  # every column's centre and surface height (NaN: no bed in it)
])


def free_surface_angle(x, y, radius, R, center=(0.0, 0.0), column_width=COLUMN_WIDTH,
                       end_exclusion=END_EXCLUSION):
    """The bed's free surface in one snapshot, from the particles projected on the x-y plane.

    The cross-section is cut into vertical columns `column_width` diameters wide. In each, the
    solid-fraction profile along y is the sum of the spheres' horizontal slices; the bed's top is
    where it first falls below half the bulk value (the mass-weighted median of the profiles) for
    at least MIN_GAP d, going up from the wall, above a dense stretch at least MIN_BED d long, so
    that grains in flight above a gap do not count. Columns whose top is the upper wall (beyond the
    chord's ends) are dropped. The chord runs between the fitted line's crossings of the circle;
    `end_exclusion` of it at each end is left out and the line fitted again until the chord stays.

    Returns a SurfaceFit (NaN numbers when fewer than 3 columns hold a free surface)."""
    u = np.asarray(x, dtype=float) - center[0]
    w = np.asarray(y, dtype=float) - center[1]
    radius = np.asarray(radius, dtype=float)
    if u.size == 0:
        raise PlotError("free_surface_angle: no particles")
    d = 2.0 * float(np.median(radius))
    columns_x, columns_h = column_surfaces(u, w, radius, R, d, column_width * d)
    wall_top = np.sqrt(np.maximum(R * R - columns_x ** 2, 0.0))
    free = np.isfinite(columns_h) & (columns_h < wall_top - d)  # a column filled to the wall has no free surface
    nan = SurfaceFit(math.nan, math.nan, math.nan, math.nan, math.nan, (math.nan, math.nan), np.zeros(0),
                     np.zeros(0), columns_x, columns_h)
    if np.count_nonzero(free) < 3:
        return nan
    half = 0.5 * column_width * d
    lo, hi = columns_x[free].min() - half, columns_x[free].max() + half
    chosen = None
    for _ in range(5):
        length = hi - lo
        chosen_now = free & (columns_x >= lo + end_exclusion * length) & (columns_x <= hi - end_exclusion * length)
        if np.count_nonzero(chosen_now) < 3:
            break
        chosen = chosen_now
        slope, intercept = np.polyfit(columns_x[chosen], columns_h[chosen], 1)
        ends = circle_crossings(slope, intercept, R)
        if ends is None or np.allclose(ends, (lo, hi), atol=1e-9 * R):
            break
        lo, hi = ends
    if chosen is None:
        return nan
    xs, hs = columns_x[chosen], columns_h[chosen]
    return fit_surface(xs, hs, columns_x, columns_h)


def column_surfaces(u, w, radius, R, d, width):
    """(column centres, surface heights: NaN where a column holds no bed) of columns `width` wide
    tiling [-R, R]."""
    count = max(1, int(round(2.0 * R / width)))
    width = 2.0 * R / count
    centres = -R + width * (np.arange(count) + 0.5)
    inside = np.abs(u) <= R
    u, w, radius = u[inside], w[inside], radius[inside]
    column = np.clip(((u + R) / width).astype(int), 0, count - 1)
    step = GRID_STEP * d
    y0 = -R - d
    size = int(math.ceil((2.0 * R + 2.0 * d) / step)) + 1
    rho = np.zeros((count, size))
    base = np.rint((w - y0) / step).astype(int)
    reach = int(math.ceil(radius.max(initial=0.0) / step)) + 1
    for k in range(-reach, reach + 1):  # each sphere's slice area at the grid heights it spans
        index = base + k
        area = math.pi * (radius ** 2 - (y0 + index * step - w) ** 2)
        ok = (area > 0.0) & (index >= 0) & (index < size)
        np.add.at(rho, (column[ok], index[ok]), area[ok])
    values = rho[rho > 0.0]
    if values.size == 0:
        return centres, np.full(count, math.nan)
    # Bulk value: the mass-weighted median, so that dilute grains above the bed (many grid points,
    # little mass) do not pull it down as they would an unweighted median.
    order = np.sort(values)
    cumulative = np.cumsum(order)
    bulk = order[np.searchsorted(cumulative, 0.5 * cumulative[-1])]
    heights = np.array([column_top(profile, 0.5 * bulk, y0, step, d) for profile in rho])
    return centres, heights


def column_top(profile, half, y0, step, d):
    """Height where the profile first drops below `half` for at least MIN_GAP d, above a dense
    stretch at least MIN_BED d long; NaN when there is none."""
    dense = profile >= half
    if not np.any(dense):
        return math.nan
    edges = np.diff(np.concatenate(([0], dense.astype(np.int8), [0])))
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)  # runs [start, end)
    merged = []  # runs joined across dips shorter than MIN_GAP
    for start, end in zip(starts, ends):
        if merged and (start - merged[-1][1]) * step < MIN_GAP * d:
            merged[-1][1] = end
        else:
            merged.append([start, end])
    for start, end in merged:
        if (end - start) * step >= MIN_BED * d:
            if end >= profile.size:
                return y0 + (profile.size - 1) * step
            above, below = profile[end], profile[end - 1]
            return y0 + (end - 1) * step + step * (below - half) / (below - above)
    return math.nan


def circle_crossings(slope, intercept, R):
    """x of the line h = intercept + slope x crossing the circle of radius R, or None."""
    a, b, c = 1.0 + slope * slope, 2.0 * slope * intercept, intercept * intercept - R * R
    disc = b * b - 4.0 * a * c
    if disc <= 0.0:
        return None
    root = math.sqrt(disc)
    return (-b - root) / (2.0 * a), (-b + root) / (2.0 * a)


def fit_surface(xs, hs, columns_x, columns_h):
    """The SurfaceFit of the chosen columns: line, quadratic and (5 columns or more) cubic fits."""
    slope, intercept = np.polyfit(xs, hs, 1)
    residuals = hs - (intercept + slope * xs)
    n = xs.size
    spread = np.sum((xs - xs.mean()) ** 2)
    slope_error = math.sqrt(np.sum(residuals ** 2) / (n - 2) / spread) if n > 2 and spread > 0 else math.nan
    angle = math.atan(slope)
    middle = 0.5 * (xs.min() + xs.max())
    curvature = bend = math.nan
    if n >= 3:
        quadratic = np.polyfit(xs - middle, hs, 2)
        curvature = 2.0 * quadratic[0] / (1.0 + quadratic[1] ** 2) ** 1.5
        degree = 3 if n >= 5 else 2
        derivative = np.polyder(np.polyfit(xs - middle, hs, degree))
        inclinations = np.degrees(np.arctan(np.polyval(derivative, np.linspace(xs.min(), xs.max(), 41) - middle)))
        bend = float(inclinations.max() - inclinations.min())
    return SurfaceFit(math.degrees(angle), float(curvature), float(np.sqrt(np.mean(residuals ** 2))),
                      math.degrees(slope_error * math.cos(angle) ** 2), bend, (float(xs.min()), float(xs.max())),
                      xs, hs, columns_x, columns_h)


# --- Form of motion -------------------------------------------------------------------------------

# A grain co-rotates with the wall when |v - omega x r| < CO_ROTATION_TOLERANCE omega R. Mass balance
# puts the flowing layer far above it: the layer (thickness delta < R/2) carries back what the plug
# lifts, ~omega R^2 / 2 per unit length, so its mean speed relative to the wall motion is
# ~omega R * R / (2 delta) > omega R; the plug differs from rigid rotation only by creep.
CO_ROTATION_TOLERANCE = 0.2
# Mellmann's centrifuging: the charge forms a ring on the wall that turns with it. "Most" grains:
# 90%. A rolling or cascading bed always has its flowing layer moving against the wall (above); a
# layer a few d thick along a chord of ~2R on a bed ~R deep holds more than a tenth of the charge, so
# such a bed stays below 0.9. "Whole circumference": at most one of the WALL_SECTORS 10-degree
# sectors without a grain within WALL_LAYER d of the wall (a ring is at least one grain thick).
CENTRIFUGING_COROTATING = 0.9
WALL_SECTORS = 36
WALL_LAYER = 2.0
CENTRIFUGING_COVERAGE = 0.95
# Mellmann's cataracting: grains leave the bed and fly freely across the drum. In flight: more than
# AIRBORNE_HEIGHT d above its column's local bed top (a saltating grain on a dense flowing surface
# rises ~1 d, the half-density top sits within ~1 d of the top grains) and not co-rotating (which
# excludes grains lifted along the wall). Cataracting when on average more than CATARACTING_AIRBORNE
# of the charge is in flight: rolling and cascading beds throw only occasional grains, a cataracting
# bed a curtain of them across the drum, a sizeable share of the charge.
AIRBORNE_HEIGHT = 3.0
CATARACTING_AIRBORNE = 0.05
# Mellmann's slumping: the bed turns with the wall as a rigid body up to the upper angle of repose,
# then a segment avalanches down to the lower one. Sampled over the cycle the angle is a sawtooth of
# height D, std D / sqrt(12); D of a few degrees (>= ~3.5 deg) gives >= SLUMPING_ANGLE_STD. The std
# must also stand 3 times above the angle's measurement error, and in at least SLUMPING_RESTING of the
# snapshots the bed must rest on the wall (co-rotating share >= CENTRIFUGING_COROTATING): the lifting
# phase is the long part of the cycle, the avalanche the short one.
SLUMPING_ANGLE_STD = 1.0
SLUMPING_NOISE_FACTOR = 3.0
SLUMPING_RESTING = 0.25
# Mellmann's cascading: the surface is no longer flat but kidney (S) shaped, steeper in its upper part.
# Cascading when the inclination of the cubic fit varies by more than CASCADING_BEND along the central
# chord: a rolling surface is flat to the measurement's scatter (a couple of degrees over the central
# 70% of a 40 d chord with 2 d columns), a visibly curved one bends by tens of degrees.
CASCADING_BEND = 10.0


def corotation(position, velocity, omega, R, center):
    """Boolean array: the particles moving with the wall's rigid rotation (see CO_ROTATION_TOLERANCE)."""
    u, w = position[:, 0] - center[0], position[:, 1] - center[1]
    relative = np.sqrt((velocity[:, 0] + omega * w) ** 2 + (velocity[:, 1] - omega * u) ** 2 + velocity[:, 2] ** 2)
    return relative <= CO_ROTATION_TOLERANCE * abs(omega) * R


def snapshot_state(snapshot, omega, R, d, center):
    """The per-snapshot measures classify_regime combines."""
    position, radius, velocity = snapshot["position"], snapshot["radius"], snapshot.get("velocity")
    if velocity is None:
        raise PlotError("classify_regime: a snapshot has no velocities")
    fit = free_surface_angle(position[:, 0], position[:, 1], radius, R, center)
    co = corotation(position, velocity, omega, R, center)
    u, w = position[:, 0] - center[0], position[:, 1] - center[1]
    # The local bed top: the columns' surfaces; where a column holds no bed, the wall at its bottom.
    bottom = -np.sqrt(np.maximum(R * R - fit.columns_x ** 2, 0.0))
    tops = np.where(np.isfinite(fit.columns_h), fit.columns_h, bottom)
    airborne = (w > np.interp(u, fit.columns_x, tops) + AIRBORNE_HEIGHT * d) & ~co
    near_wall = np.hypot(u, w) > R - WALL_LAYER * d
    sector = ((np.arctan2(w[near_wall], u[near_wall]) + math.pi) / (2.0 * math.pi) * WALL_SECTORS).astype(int)
    coverage = np.unique(np.clip(sector, 0, WALL_SECTORS - 1)).size / WALL_SECTORS
    span = fit.span[1] - fit.span[0]
    return {"angle": fit.angle_deg, "error": fit.angle_error_deg, "bend": fit.bend_deg,
            "curvature": fit.curvature * span, "corotating": float(np.mean(co)),
            "airborne": float(np.mean(airborne)), "coverage": coverage}


def classify_regime(snapshots, omega, R, g, d, center=(0.0, 0.0)):
    """The form of motion (Mellmann 2001, Powder Technol. 118:251) of a drum from a time series of
    snapshots (the steady part of a run). The criteria, tested in this order:

    centrifuging  the median share of grains co-rotating with the wall (|v - omega x r| <
                  0.2 omega R) is >= 0.9 and grains lie within 2 d of the wall all around (>= 95%
                  of 36 sectors);
    cataracting   on average > 5% of the grains are in flight: > 3 d above their column's bed
                  top and not co-rotating;
    slumping      the surface angle's std over the snapshots is >= 1 degree and >= 3 times its
                  measurement error, and in >= 25% of the snapshots >= 90% of the bed co-rotates
                  (it rests on the wall between avalanches);
    cascading     the surface bends: the cubic fit's inclination varies by > 10 degrees along the
                  central chord (mean over the snapshots);
    rolling       otherwise: a flat surface at a steady angle.

    The reasons for the thresholds are at their constants. Returns a dict: regime, froude (omega^2
    R / g: context only, not a criterion), angle_deg and angle_std_deg (mean and std over the
    snapshots), angle_error_deg (the median fit error), surface_curvature (curvature x fitted chord
    length: the change of slope along it), surface_bend_deg, airborne_fraction,
    corotating_fraction, wall_coverage, snapshots. The angle and surface measures are NaN when
    centrifuging: there is no free surface."""
    if not snapshots:
        raise PlotError("classify_regime: no snapshots")
    states = [snapshot_state(s, omega, R, d, center) for s in snapshots]

    def series(key):
        return np.array([s[key] for s in states], dtype=float)

    def mean(values):
        values = values[np.isfinite(values)]
        return float(values.mean()) if values.size else math.nan

    angles, corotating = series("angle"), series("corotating")
    finite = angles[np.isfinite(angles)]
    angle_std = float(finite.std()) if finite.size >= 2 else math.nan
    errors = series("error")
    angle_error = float(np.median(errors[np.isfinite(errors)])) if np.any(np.isfinite(errors)) else math.nan
    result = {"froude": omega * omega * R / g if g > 0.0 else math.nan, "angle_deg": mean(angles),
              "angle_std_deg": angle_std, "angle_error_deg": angle_error,
              "surface_curvature": mean(series("curvature")), "surface_bend_deg": mean(series("bend")),
              "airborne_fraction": mean(series("airborne")), "corotating_fraction": mean(corotating),
              "wall_coverage": float(np.median(series("coverage"))), "snapshots": len(states)}
    resting = float(np.mean(corotating >= CENTRIFUGING_COROTATING))
    if float(np.median(corotating)) >= CENTRIFUGING_COROTATING and result["wall_coverage"] >= CENTRIFUGING_COVERAGE:
        regime = "centrifuging"  # no free surface: its measures would describe the ring's inner edge
        for key in ("angle_deg", "angle_std_deg", "surface_curvature", "surface_bend_deg"):
            result[key] = math.nan
    elif result["airborne_fraction"] > CATARACTING_AIRBORNE:
        regime = "cataracting"
    elif (np.isfinite(angle_std) and angle_std >= SLUMPING_ANGLE_STD
          and not angle_std < SLUMPING_NOISE_FACTOR * angle_error and resting >= SLUMPING_RESTING):
        regime = "slumping"
    elif result["surface_bend_deg"] > CASCADING_BEND:
        regime = "cascading"
    else:
        regime = "rolling"
    result["regime"] = regime
    return result


# --- Vibrated cylindrical bed: convection -----------------------------------------------------------

def axial_convection_profile(snapshots, R, axis_center=(0.0, 0.0), annuli=8, exclude_diameters=3.0,
                             subtract_bed_velocity=False):
    """Mean vertical velocity of a vibrated bed in a cylinder (axis along y, the gravity axis,
    through (x, z) = axis_center, radius R) in `annuli` equal-area annuli of r = sqrt(x^2 + z^2).

    The annuli tile the disc the centres can reach, r <= R - a (a: the median particle radius), so
    that each holds about the same number of grains. Only the bulk counts: grains more than
    `exclude_diameters` d above the bed's bottom and below its top (the 1st and 99th percentiles of
    the snapshot's heights, robust to a few grains in flight). The mean is over every grain sample
    of every snapshot; with `subtract_bed_velocity` each snapshot's mean vy of the counted grains is
    removed first (the whole bed's motion with the floor, which the snapshots may sample unevenly:
    the convection roll itself carries no net flux). Knight, Jaeger & Nagel (1993): with frictional
    walls, grains go down in a thin layer at the wall and up in the centre.

    Returns (r_mid, mean_vy, count): the annuli's mid radii, their mean vy (NaN when empty) and the
    grain samples in each."""
    if not snapshots:
        raise PlotError("axial_convection_profile: no snapshots")
    outer = R - float(np.median(np.concatenate([s["radius"] for s in snapshots])))
    if outer <= 0.0:
        raise PlotError(f"axial_convection_profile: radius {R} is not larger than the particles'")
    edges = outer * np.sqrt(np.arange(annuli + 1) / annuli)
    total, count = np.zeros(annuli), np.zeros(annuli, dtype=int)
    for snapshot in snapshots:
        position, velocity = snapshot["position"], snapshot.get("velocity")
        if velocity is None:
            raise PlotError("axial_convection_profile: a snapshot has no velocities")
        d = 2.0 * float(np.median(snapshot["radius"]))
        y = position[:, 1]
        bottom, top = np.percentile(y, 1.0), np.percentile(y, 99.0)
        bulk = (y > bottom + exclude_diameters * d) & (y < top - exclude_diameters * d)
        r = np.hypot(position[bulk, 0] - axis_center[0], position[bulk, 2] - axis_center[1])
        vy = velocity[bulk, 1]
        if subtract_bed_velocity and vy.size:
            vy = vy - vy.mean()
        which = np.clip(np.searchsorted(edges, r, side="right") - 1, 0, annuli - 1)
        total += np.bincount(which, weights=vy, minlength=annuli)
        count += np.bincount(which, minlength=annuli)
    mean = np.divide(total, count, out=np.full(annuli, math.nan), where=count > 0)
    return 0.5 * (edges[:-1] + edges[1:]), mean, count


def axial_drift_profile(snapshots, R, axis_center=(0.0, 0.0), edges=None, bulk_fraction=0.7):
    """The convection of a vibrated bed in a cylinder (axis along y through (x, z) = axis_center,
    radius R), from snapshots one drive period apart (output.snapshot_interval = 1 / f: the same
    phase each time, so the floor's and the bed's oscillation cancel): each grain's vertical
    displacement from one snapshot to the next, averaged per annulus of its radius r = sqrt(x^2 + z^2)
    over the grains in the bed's bulk (the middle `bulk_fraction` of the heights, away from the floor
    and the free surface), then over the pairs of snapshots. Knight, Jaeger & Nagel (1993): down in a
    layer at a frictional wall, up in the centre.

    `edges`: the annuli's radii (default: the wall layer, r > R - 1.5 d, and four equal-area annuli
    inside it). Returns (edges, mean dy per period, its standard error over the pairs, pairs)."""
    frames = []
    for snapshot in snapshots:
        if snapshot.get("id") is None:
            raise PlotError("axial_drift_profile: the snapshots carry no particle ids")
        order = np.argsort(snapshot["id"])
        frames.append((snapshot["id"][order], snapshot["position"][order]))
    if len(frames) < 2:
        raise PlotError("axial_drift_profile: needs at least two snapshots")
    if edges is None:
        d = 2.0 * float(np.median(snapshots[0]["radius"]))
        inner = R - 1.5 * d
        edges = np.append(inner * np.sqrt(np.arange(5) / 4.0), R)
    edges = np.asarray(edges, dtype=float)
    rows = []
    for (ids_a, xa), (ids_b, xb) in zip(frames[:-1], frames[1:]):
        if ids_a.shape != ids_b.shape or np.any(ids_a != ids_b):
            raise PlotError("axial_drift_profile: the snapshots hold different particles")
        dy = xb[:, 1] - xa[:, 1]
        height = 0.5 * (xa[:, 1] + xb[:, 1])
        lo, hi = np.percentile(height, [50.0 * (1.0 - bulk_fraction), 50.0 * (1.0 + bulk_fraction)])
        bulk = (height > lo) & (height < hi)
        r = np.hypot(xa[:, 0] - axis_center[0], xa[:, 2] - axis_center[1])
        row = []
        for a, b in zip(edges[:-1], edges[1:]):
            m = bulk & (r >= a) & (r < b)
            row.append(dy[m].mean() if m.any() else math.nan)
        rows.append(row)
    rows = np.array(rows)
    pairs = rows.shape[0]
    mean = np.nanmean(rows, axis=0)
    error = np.nanstd(rows, axis=0) / math.sqrt(pairs) if pairs > 1 else np.full(len(mean), math.nan)
    return edges, mean, error, pairs


def analyze_sweep(sweep_dir, **options):
    """drum_regimes.csv and drum_regimes.png of a sweep folder: see drum_sweep.analyze_sweep."""
    from .drum_sweep import analyze_sweep as analyze  # the sweep's files and figure live there

    return analyze(sweep_dir, **options)
