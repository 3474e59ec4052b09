#!/usr/bin/python3
"""tools/grainflow_plots/drum.py on synthetic particle configurations with known answers; needs no
grainflow binary (numpy and matplotlib only).

- the free-surface angle of a bed packed below a line at +30 and -20 degrees, within a tolerance
  derived from the column width and the grain size (and a 25-degree bed must fail the 30-degree
  check);
- the curvature of a bed under a parabola: its sign and size;
- the forms of motion: a co-rotating ring (centrifuging), a bed with 20% of its grains on ballistic
  paths far above it (cataracting), a steady flat bed (rolling), a steady curved bed (cascading), a
  bed whose angle alternates between 25 and 40 degrees (slumping);
- the radial convection profile of a cylindrical bed going down at the wall and up in the centre;
- analyze_sweep and tools/drum_analysis.py on a small synthetic sweep folder written as grainflow
  writes one, and `drum_analysis.py --convection` on a synthetic run folder.

Usage: /usr/bin/python3 tests/unit/test_drum_analysis.py   (from anywhere)
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from grainflow_plots import drum  # noqa: E402
from grainflow_plots.drum_sweep import analyze_sweep  # noqa: E402

CLI = os.path.join(ROOT, "tools", "drum_analysis.py")

FAILURES = []
D = 1.0e-3  # grain diameter (m)
R = 20.0 * D  # drum radius, as cases/geometry/rotating_drum.toml
DEPTH = 4.0 * D  # periodic length along the axis
G = 9.81


def check(condition, message):
    if not condition:
        FAILURES.append(message)
        print("FAIL: " + message, file=sys.stderr)
    return condition


# --- Synthetic packings -----------------------------------------------------------------------------

def packing(rng, half_width, low, high, z_low, z_high, spacing=1.02):
    """Centres of a jittered face-centred cubic packing (nearest neighbours `spacing` d apart, solid
    fraction ~0.70, a random orientation so that no lattice plane lines up with the surface) filling
    |x| <= half_width, low <= y <= high, z_low <= z < z_high."""
    a = spacing * math.sqrt(2.0) * D  # cube edge
    extent = math.sqrt(half_width ** 2 + max(abs(low), abs(high)) ** 2 + max(abs(z_low), abs(z_high)) ** 2) + a
    n = int(math.ceil(extent / a))
    cells = np.arange(-n, n + 1) * a
    corner = np.stack(np.meshgrid(cells, cells, cells, indexing="ij"), axis=-1).reshape(-1, 3)
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]]) * a
    points = (corner[:, None, :] + basis[None, :, :]).reshape(-1, 3)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))  # a random rotation
    points = points @ q.T + rng.uniform(0.0, a, size=3) + rng.uniform(-0.03 * D, 0.03 * D, size=points.shape)
    keep = ((np.abs(points[:, 0]) <= half_width) & (points[:, 1] >= low) & (points[:, 1] <= high)
            & (points[:, 2] >= z_low) & (points[:, 2] < z_high))
    return points[keep]


def drum_bed(rng, surface, radius=R, depth=DEPTH):
    """Grains inside the drum (centres at most R - d/2 from the axis) below the curve y = surface(x)."""
    points = packing(rng, radius, -radius, radius, 0.0, depth)
    inside = np.hypot(points[:, 0], points[:, 1]) <= radius - 0.5 * D
    points = points[inside]
    return points[points[:, 1] <= surface(points[:, 0])]


def snapshot(points, velocity=None):
    return {"position": points, "radius": np.full(len(points), 0.5 * D),
            "velocity": np.zeros_like(points) if velocity is None else velocity}


def rigid(points, omega):
    """v = omega z x r: the wall's rigid rotation about the drum's axis."""
    return np.stack([-omega * points[:, 1], omega * points[:, 0], np.zeros(len(points))], axis=1)


def line_surface(angle_deg, offset=0.0):
    slope = math.tan(math.radians(angle_deg))
    return lambda x: offset + slope * x


def angle_tolerance(fit, angle_deg):
    """3 standard errors of the fitted angle when every column height is off by up to a grain radius
    either way (uniform: sigma_h = d / sqrt(12), one grain layer's position unknown within a
    diameter): sigma_slope = sigma_h / sqrt(sum (x - <x>)^2) over the fitted columns, and
    d(angle) = cos^2(angle) d(slope). With 2 d columns over the central 70% of a 40 d chord this
    is ~1.2 degrees."""
    sigma_h = D / math.sqrt(12.0)
    spread = math.sqrt(np.sum((fit.x - fit.x.mean()) ** 2))
    return 3.0 * math.degrees(sigma_h / spread) * math.cos(math.radians(angle_deg)) ** 2


def parabola_surface(slope_deg, c):
    slope = math.tan(math.radians(slope_deg))
    return lambda x: slope * x + c * x * x


def omega_for(froude):
    return math.sqrt(froude * G / R)


# --- The free surface ---------------------------------------------------------------------------------

def test_flat_angles(rng):
    for angle in (30.0, -20.0):
        points = drum_bed(rng, line_surface(angle))
        fit = drum.free_surface_angle(points[:, 0], points[:, 1], np.full(len(points), 0.5 * D), R)
        tolerance = angle_tolerance(fit, angle)
        check(tolerance < 2.5, f"the {angle} degree tolerance {tolerance:.2f} is too loose to tell 5 degrees apart")
        check(abs(fit.angle_deg - angle) <= tolerance,
              f"flat bed at {angle} degrees: measured {fit.angle_deg:.2f} (tolerance {tolerance:.2f})")
        check(fit.residual < 0.5 * D, f"flat bed at {angle} degrees: line residual {fit.residual / D:.2f} d")
        check(fit.bend_deg < drum.CASCADING_BEND, f"flat bed at {angle} degrees: bend {fit.bend_deg:.1f} degrees")
        # The chord's central 70%: the fitted columns lie inside the bed's chord, away from its ends.
        chord = drum.circle_crossings(math.tan(math.radians(angle)), 0.0, R)
        inner = 0.1 * (chord[1] - chord[0])
        check(fit.span[0] > chord[0] + inner and fit.span[1] < chord[1] - inner,
              f"flat bed at {angle} degrees: fitted columns {fit.span} reach the chord's ends {chord}")
    # The check can fail: a 25-degree bed is outside the 30-degree tolerance.
    points = drum_bed(rng, line_surface(25.0))
    fit = drum.free_surface_angle(points[:, 0], points[:, 1], np.full(len(points), 0.5 * D), R)
    check(abs(fit.angle_deg - 30.0) > angle_tolerance(fit, 30.0),
          f"a 25-degree bed ({fit.angle_deg:.2f}) passes the 30-degree check")


def test_curvature(rng):
    """y = tan(20 deg) x + c x^2: curvature 2c / (1 + y'^2)^1.5 at the span's middle, within 3
    standard errors of the quadratic coefficient for column heights uniform within +-d/2."""
    c = 0.012 / D  # 4.8 d above the tangent at the walls: a clear kidney, bend ~30 degrees
    points = drum_bed(rng, parabola_surface(20.0, c))
    fit = drum.free_surface_angle(points[:, 0], points[:, 1], np.full(len(points), 0.5 * D), R)
    middle = 0.5 * (fit.span[0] + fit.span[1])
    slope = math.tan(math.radians(20.0)) + 2.0 * c * middle
    expected = 2.0 * c / (1.0 + slope * slope) ** 1.5
    design = np.stack([(fit.x - middle) ** 2, fit.x - middle, np.ones_like(fit.x)], axis=1)
    sigma_c = D / math.sqrt(12.0) * math.sqrt(np.linalg.inv(design.T @ design)[0, 0])
    tolerance = 3.0 * 2.0 * sigma_c / (1.0 + slope * slope) ** 1.5
    check(tolerance < 0.5 * expected, f"curvature tolerance {tolerance * D:.4f}/d is too loose against "
          f"{expected * D:.4f}/d")
    check(fit.curvature > 0.0, f"a bed steepening towards +x has curvature {fit.curvature * D:.4f}/d, not > 0")
    check(abs(fit.curvature - expected) <= tolerance,
          f"curvature {fit.curvature * D:.4f}/d, expected {expected * D:.4f}/d +- {tolerance * D:.4f}/d")
    mirrored = drum.free_surface_angle(-points[:, 0], points[:, 1], np.full(len(points), 0.5 * D), R)
    check(mirrored.curvature > 0.0 and mirrored.angle_deg < 0.0,
          f"the mirrored bed: curvature {mirrored.curvature * D:.4f}/d (> 0), angle {mirrored.angle_deg:.1f} (< 0)")
    flat_bed = drum_bed(rng, line_surface(20.0))
    flat = drum.free_surface_angle(flat_bed[:, 0], flat_bed[:, 1], np.full(len(flat_bed), 0.5 * D), R)
    check(abs(flat.curvature) < tolerance, f"a flat bed has curvature {flat.curvature * D:.4f}/d")


# --- The forms of motion ------------------------------------------------------------------------------

SNAPSHOTS = 8


def flowing_bed(rng, surface, omega, layer=4.0 * D, speed_factor=10.0):
    """A bed whose grains turn with the wall except those within `layer` of the surface, which flow
    downhill along it at speed_factor times the wall speed (Mellmann's rolling bed: a plug and a
    flowing layer)."""
    points = drum_bed(rng, surface)
    velocity = rigid(points, omega)
    x = points[:, 0]
    depth = surface(x) - points[:, 1]
    slope = (surface(x + 1e-6) - surface(x - 1e-6)) / 2e-6
    flowing = depth < layer
    norm = np.sqrt(1.0 + slope[flowing] ** 2)
    speed = speed_factor * omega * R
    velocity[flowing, 0] = -speed / norm
    velocity[flowing, 1] = -speed * slope[flowing] / norm
    return snapshot(points, velocity)


def ballistic_grains(rng, count, omega, surface):
    """`count` grains in free flight: thrown from the wall at 60 degrees on the rising side with
    the wall's velocity, seen once gravity has changed their velocity by at least a quarter of the
    wall speed omega R (t >= vy0 / 2g: before that a grain still moves as the wall does), kept
    where they are inside the drum and more than 5 d above the bed's surface."""
    start = math.radians(60.0)
    x0, y0 = (R - D) * math.cos(start), (R - D) * math.sin(start)
    vx0, vy0 = -omega * y0, omega * x0
    points, velocities = [], []
    while len(points) < count:
        t = rng.uniform(0.5 * vy0 / G, 3.0 * vy0 / G)
        x, y = x0 + vx0 * t, y0 + vy0 * t - 0.5 * G * t * t
        if math.hypot(x, y) < R - D and y > surface(x) + 5.0 * D:
            points.append((x, y, rng.uniform(0.0, DEPTH)))
            velocities.append((vx0, vy0 - G * t, 0.0))
    return np.array(points), np.array(velocities)


def classify(snapshots, froude):
    return drum.classify_regime(snapshots, omega_for(froude), R, G, D)


def test_centrifuging(rng):
    omega = omega_for(1.5)
    ring = packing(rng, R, -R, R, 0.0, DEPTH)
    r = np.hypot(ring[:, 0], ring[:, 1])
    ring = ring[(r <= R - 0.5 * D) & (r > R - 2.5 * D)]
    snapshots = []
    for k in range(SNAPSHOTS):
        turn = omega * 0.01 * k
        c, s = math.cos(turn), math.sin(turn)
        points = ring @ np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
        velocity = rigid(points, omega) + rng.normal(0.0, 0.02 * omega * R, size=points.shape)
        snapshots.append(snapshot(points, velocity))
    result = classify(snapshots, 1.5)
    check(result["regime"] == "centrifuging", f"co-rotating ring: {result['regime']} ({result})")
    check(abs(result["froude"] - 1.5) < 1e-9, f"co-rotating ring: Fr {result['froude']}, expected 1.5")


def test_cataracting(rng):
    omega = omega_for(0.5)
    surface = line_surface(35.0)
    snapshots, shares = [], []
    for _ in range(SNAPSHOTS):
        bed = drum_bed(rng, surface)
        flying, velocity = ballistic_grains(rng, len(bed) // 4, omega, surface)  # 20% of all grains
        points = np.concatenate([bed, flying])
        snapshots.append(snapshot(points, np.concatenate([rigid(bed, omega), velocity])))
        # In flight by the docstring's definition: a flying grain that happens to move as the wall
        # does where it is (|v - omega x r| < 0.2 omega R) cannot be told from a lifted one.
        relative = np.hypot(velocity[:, 0] + omega * flying[:, 1], velocity[:, 1] - omega * flying[:, 0])
        shares.append(np.count_nonzero(relative >= 0.2 * omega * R) / len(points))
    result = classify(snapshots, 0.5)
    check(result["regime"] == "cataracting", f"bed with 20% in flight: {result['regime']} ({result})")
    check(np.mean(shares) > 0.8 * 0.2, f"only {np.mean(shares):.3f} of the grains fly off the wall's motion")
    check(abs(result["airborne_fraction"] - np.mean(shares)) < 0.002,
          f"airborne fraction {result['airborne_fraction']:.4f}, {np.mean(shares):.4f} placed in flight")
    check(abs(result["angle_deg"] - 35.0) < 2.0, f"the bed under the flying grains: angle {result['angle_deg']:.2f}")


def test_rolling_and_cascading(rng):
    omega = omega_for(1e-3)
    rolling = classify([flowing_bed(rng, line_surface(30.0), omega) for _ in range(SNAPSHOTS)], 1e-3)
    check(rolling["regime"] == "rolling", f"steady flat bed: {rolling['regime']} ({rolling})")
    check(abs(rolling["angle_deg"] - 30.0) < 1.0, f"steady flat bed: angle {rolling['angle_deg']:.2f}")
    check(rolling["angle_std_deg"] < drum.SLUMPING_ANGLE_STD, f"steady flat bed: std {rolling['angle_std_deg']:.2f}")
    omega = omega_for(3e-2)
    curved = classify([flowing_bed(rng, parabola_surface(30.0, 0.012 / D), omega) for _ in range(SNAPSHOTS)], 3e-2)
    check(curved["regime"] == "cascading", f"steady curved bed: {curved['regime']} ({curved})")
    check(curved["surface_curvature"] > 0.0, f"steady curved bed: curvature x chord {curved['surface_curvature']}")


def test_slumping(rng):
    omega = omega_for(1e-4)
    snapshots = []
    for k in range(SNAPSHOTS):
        points = drum_bed(rng, line_surface(25.0 if k % 2 == 0 else 40.0))
        snapshots.append(snapshot(points, rigid(points, omega)))
    result = classify(snapshots, 1e-4)
    check(result["regime"] == "slumping", f"angle alternating 25/40 degrees: {result['regime']} ({result})")
    check(abs(result["angle_std_deg"] - 7.5) < 1.0, f"angle alternating 25/40: std {result['angle_std_deg']:.2f}")


# --- Convection in a vibrated cylindrical bed -----------------------------------------------------------

def test_convection(rng):
    """Down (-1) within 2 d of the wall, up (+1) inside half the radius, still between; the top and
    bottom 2 d move at +10 and must be left out of the bulk."""
    radius, height = 10.0 * D, 30.0 * D
    outer = radius - 0.5 * D  # the centres' disc
    snapshots = []
    for _ in range(4):
        points = packing(rng, radius, 0.0, height, -radius, radius)
        r = np.hypot(points[:, 0], points[:, 2])
        points, r = points[r <= outer], r[r <= outer]
        vy = np.where(r > outer - 2.0 * D, -1.0, np.where(r < 0.5 * outer, 1.0, 0.0))
        vy[(points[:, 1] < 2.0 * D) | (points[:, 1] > height - 2.0 * D)] = 10.0
        velocity = np.zeros_like(points)
        velocity[:, 1] = vy
        snapshots.append(snapshot(points, velocity))
    r_mid, mean_vy, count = drum.axial_convection_profile(snapshots, radius)
    check(r_mid.size == 8 and np.all(np.diff(r_mid) > 0.0), f"annuli mid radii {r_mid}")
    check(abs(mean_vy[0] - 1.0) < 1e-9, f"centre annulus: mean vy {mean_vy[0]}, expected +1")
    check(abs(mean_vy[-1] + 1.0) < 1e-9, f"wall annulus: mean vy {mean_vy[-1]}, expected -1")
    signs = np.sign(mean_vy[np.abs(mean_vy) > 1e-12])
    check(np.count_nonzero(np.diff(signs) != 0) == 1, f"profile {mean_vy}: not one change from up to down")
    check(count.min() > 0 and count.max() < 1.3 * count.min(), f"equal-area annuli hold {count} grains")


def test_drift(rng):
    """Phase-locked snapshots of a bed whose grains rise 0.3 d a period inside half the radius and
    sink 0.5 d a period within 1.5 d of the wall: the drift profile gives +0.3 in the centre, -0.5
    in the wall layer (each grain moves exactly, so the mean is exact), in particle-id order even when
    the snapshots list them shuffled."""
    radius, height = 10.0 * D, 30.0 * D
    outer = radius - 0.5 * D
    points = packing(rng, radius, 0.0, height, -radius, radius)
    r = np.hypot(points[:, 0], points[:, 2])
    points, r = points[r <= outer], r[r <= outer]
    rise = np.where(r > radius - 1.5 * D, -0.5 * D, np.where(r < 0.5 * radius, 0.3 * D, 0.0))
    ids = np.arange(len(points))
    snapshots = []
    for k in range(3):
        order = rng.permutation(len(points))
        moved = points.copy()
        moved[:, 1] += k * rise
        s = snapshot(moved[order], np.zeros_like(moved))
        s["id"] = ids[order]
        snapshots.append(s)
    edges, mean, error, pairs = drum.axial_drift_profile(snapshots, radius, bulk_fraction=1.0)
    check(pairs == 2, f"{pairs} pairs of snapshots, expected 2")
    check(abs(mean[0] - 0.3 * D) < 1e-9 * D, f"centre: {mean[0] / D:.6g} d a period, expected +0.3")
    check(abs(mean[-1] + 0.5 * D) < 1e-9 * D, f"wall layer: {mean[-1] / D:.6g} d a period, expected -0.5")
    check(abs(edges[-2] - (radius - 1.5 * D)) < 1e-12 and edges[-1] == radius, f"the wall layer's annulus {edges[-2:]}")


# --- A sweep folder -------------------------------------------------------------------------------------

def write_vtu(path, points, velocity):
    """A snapshot in the layout of src/grainflow/io/vtu_writer.cpp (the arrays the reader uses)."""
    n = len(points)

    def block(name, values, components):
        rows = "\n".join(" ".join(repr(float(v)) for v in np.atleast_1d(row)) for row in values)
        return (f'        <DataArray type="Float64" Name="{name}" NumberOfComponents="{components}" '
                f'format="ascii">\n{rows}\n        </DataArray>\n')

    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">\n'
                f'  <UnstructuredGrid>\n    <Piece NumberOfPoints="{n}" NumberOfCells="{n}">\n'
                '      <PointData Scalars="diameter" Vectors="velocity">\n')
        f.write(block("diameter", np.full(n, D), 1) + block("radius", np.full(n, 0.5 * D), 1)
                + block("velocity", velocity, 3))
        f.write("      </PointData>\n      <Points>\n" + block("position", points, 3)
                + "      </Points>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n")


def test_sweep(rng):
    froudes = [1e-3, 1.5]
    with tempfile.TemporaryDirectory() as folder:
        with open(os.path.join(folder, "sweep.csv"), "w") as f:
            f.write("# grainflow sweep of cases/geometry/rotating_drum.toml: 2 runs\n# units: ...\n")
            f.write("geometry.drum.angular_velocity,run,status,particles\n")
            for k, froude in enumerate(froudes):
                omega = omega_for(froude)
                run = f"geometry.drum.angular_velocity={omega:.6g}"
                f.write(f"{omega:.6g},{run},0,1000\n")
                os.makedirs(os.path.join(folder, run, "snapshots"))
                with open(os.path.join(folder, run, "resolved_case.toml"), "w") as case:
                    case.write(f'[gravity]\nvector = [0.0, {-G}, 0.0]\n\n[[geometry]]\nkind = "cylinder"\n'
                               f"radius = {R}\ncenter = [0.0, 0.0, 0.0]\n")  # omega only in sweep.csv
                entries = []
                for s in range(4):  # the first half (unsteady) is left out: make it centrifuge
                    if froude < 1.0 and s >= 2:
                        snap = flowing_bed(rng, line_surface(30.0), omega)
                        points, velocity = snap["position"], snap["velocity"]
                    else:
                        ring = packing(rng, R, -R, R, 0.0, DEPTH)
                        r = np.hypot(ring[:, 0], ring[:, 1])
                        points = ring[(r <= R - 0.5 * D) & (r > R - 2.5 * D)]
                        velocity = rigid(points, omega)
                    name = f"particles_{s:06d}.vtu"
                    write_vtu(os.path.join(folder, run, "snapshots", name), points, velocity)
                    entries.append(f'    <DataSet timestep="{0.1 * s}" group="" part="0" file="{name}"/>\n')
                with open(os.path.join(folder, run, "snapshots", "particles.pvd"), "w") as pvd:
                    pvd.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
                              + "".join(entries) + "  </Collection>\n</VTKFile>\n")
        rows, written = analyze_sweep(folder)
        check([row["regime"] for row in rows] == ["rolling", "centrifuging"],
              f"sweep regimes {[row['regime'] for row in rows]}, expected rolling then centrifuging")
        for row, froude in zip(rows, froudes):
            check(abs(row["Fr"] / froude - 1.0) < 1e-5, f"sweep Fr {row['Fr']}, expected {froude}")
        check(all(os.path.isfile(p) for p in written) and len(written) == 2, f"sweep wrote {written}")
        with open(os.path.join(folder, "drum_regimes.csv")) as f:
            table = list(csv.DictReader(line for line in f if not line.startswith("#")))
        check(len(table) == 2 and list(table[0])[:8] == ["Fr", "angular_velocity", "regime", "angle_deg",
                                                         "angle_std_deg", "surface_curvature", "airborne_fraction",
                                                         "corotating_fraction"], f"drum_regimes.csv: {table[:1]}")
        check(abs(float(table[0]["angle_deg"]) - 30.0) < 1.0, f"drum_regimes.csv rolling angle {table[0]['angle_deg']}")
        result = subprocess.run([sys.executable, CLI, folder], capture_output=True, text=True)
        check(result.returncode == 0 and "rolling" in result.stdout and "centrifuging" in result.stdout,
              f"drum_analysis.py SWEEP_DIR: status {result.returncode}, {result.stdout} {result.stderr}")
        result = subprocess.run([sys.executable, CLI, os.path.join(folder, "nothing")], capture_output=True, text=True)
        check(result.returncode == 1 and "no sweep.csv" in result.stderr,
              f"drum_analysis.py on a missing folder: status {result.returncode}, {result.stderr}")


def test_convection_command(rng):
    """--convection RUN_DIR --radius R writes convection_profile.csv from the later half of the
    snapshots (the first half here moves up everywhere and must be left out)."""
    radius, height = 8.0 * D, 20.0 * D
    with tempfile.TemporaryDirectory() as folder:
        os.makedirs(os.path.join(folder, "snapshots"))
        for s in range(4):
            points = packing(rng, radius, 0.0, height, -radius, radius)
            r = np.hypot(points[:, 0], points[:, 2])
            points, r = points[r <= radius - 0.5 * D], r[r <= radius - 0.5 * D]
            velocity = np.zeros_like(points)
            velocity[:, 1] = 1.0 if s < 2 else np.where(r > radius - 2.5 * D, -1.0, 1.0)
            write_vtu(os.path.join(folder, "snapshots", f"particles_{s:06d}.vtu"), points, velocity)
        result = subprocess.run([sys.executable, CLI, "--convection", folder, "--radius", repr(radius)],
                                capture_output=True, text=True)
        check(result.returncode == 0, f"--convection: status {result.returncode}, {result.stderr}")
        path = os.path.join(folder, "convection_profile.csv")
        if check(os.path.isfile(path), "--convection wrote no convection_profile.csv"):
            with open(path) as f:
                table = list(csv.DictReader(line for line in f if not line.startswith("#")))
            vy = [float(row["mean_vy"]) for row in table]
            check(len(vy) == 8 and vy[0] == 1.0 and vy[-1] == -1.0, f"convection_profile.csv mean_vy {vy}")
        result = subprocess.run([sys.executable, CLI, "--convection", folder], capture_output=True, text=True)
        check(result.returncode != 0 and "--radius" in result.stderr, "--convection without --radius was accepted")


def main():
    tests = [test_drift, test_flat_angles, test_curvature, test_centrifuging, test_cataracting, test_rolling_and_cascading,
             test_slumping, test_convection, test_sweep, test_convection_command]
    failed = 0
    for number, test in enumerate(tests):
        before = len(FAILURES)
        test(np.random.default_rng(20240 + number))  # fixed seeds: the same grains every run
        failed += len(FAILURES) > before
        print(f"{test.__name__}: {'ok' if len(FAILURES) == before else 'FAILED'}")
    print(f"test_drum_analysis: {len(tests) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
