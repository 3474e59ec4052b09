#!/usr/bin/python3
"""Discs in the soft-sphere engine (engine.dimension = 2) from the command line: a bed of 200
frictional discs (d = 1, 1 kg per unit area, mu = 0.5 with each other and the floor) settled on a
flat floor under gravity tilted 10 degrees from the floor's normal, in a box 20 wide, periodic in x,
its outputs averaged over the last 5 time units, when it is at rest. Every check is a closed form
of the statics of discs (masses pi d^2 / 4 per unit thickness; stresses per unit length, N/m):

- The discs stay in their plane: every z in final_state.csv is the box's mid-z 0.5, every vz, wx, wy
  exactly 0 (no force off the plane, no torque in it, to the bit); summary.json says dimension 2.
- At rest the force carried across a line y by the branch vectors crossing it is the weight of the
  discs whose centres lie above: each strip's total P_yb equals -(1/(h L)) sum_i m_i g_b
  clamp(y_i - lo, 0, h), to 1e-6 of the bottom strip's P_yy (the residual motion, velocities ~1e-6,
  as in the spheres' test); hence P_yx / P_yy = -tan 10 deg, and the floor carries N m g cos / L
  normally and -N m g sin / L in shear; the file has the x-y components only, as the event-driven
  engine's in 2D. A 3D measure anywhere (a volume for an area, a wall's area
  for its length) is off by a factor of order one.
- Zone profiles weigh each disc by its exact disc-strip areas: sum over zones of solids_fraction x
  zone area (L h) is the discs' total area N pi d^2 / 4, less the slivers pressed into the floor,
  to 1e-9 (the file's digits), where a sphere-slab weighting is off by a third.
- Coarse graining in 2D (a Gaussian of width 0.5 on cells 0.5 wide, one cell along z): the density
  integrates over the cells' areas to the discs' mass to 1e-12; the contact stress's y rows to the
  weight's moment -sum_i m_i g_b y_i to 1e-6 of its yy part, and to the strips' contact virial over
  the same samples to 1e-8 (the file's digits); nothing along z.
- The bed's mass hold-up m_t (eq. 4-1-3) is the discs' area over the floor length and d: N pi / (4 L).
- On two MPI ranks (the box cut across x) the stresses, the floor's load and the coarse-grained
  fields of the falling and landing bed (t = 1.5-2, 56-200 contacts, some across the cut) are
  those of one rank to 1e-9 of each column's largest value (measured: 2e-12, round-off grown over
  20,000 steps). Each rank adds its own particles and the contacts listed at them, and the sums
  are added over the ranks; the contact forces' damping needs the ghosts' velocities at the step's
  end, which left half a step old made the contact stresses differ by ~1 %.

Usage: /usr/bin/python3 tests/integration/test_dem_discs.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import subprocess  # noqa: E402

from gftest import (check, executable_from_argv, finish, mpi_environment, mpirun_found, read_csv, run,  # noqa: E402
                    write_text)

ANGLE = math.radians(10.0)
WIDTH = 20.0
COUNT = 200
MASS = math.pi / 4.0  # a disc of unit diameter, 1 kg per unit area

BED = f"""
[engine]
kind = "dem"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [{WIDTH}, 40.0, 1.0]
boundary = {{ x = "periodic", y = ["wall", "open"], z = "periodic" }}
[gravity]
vector = [{math.sin(ANGLE)!r}, {-math.cos(ANGLE)!r}, 0.0]
[[species]]
name = "disc"
diameter = 1.0
density = 1.0
count = {COUNT}
[particles]
init = "random"
region_lo = [0.0, 0.0, 0.0]
region_hi = [{WIDTH}, 30.0, 1.0]
seed = 3
[contact]
model = "linear_dashpot"
kn = 2.0e5
gamma_n = 300.0
friction = 0.5
[walls.ylo]
friction = 0.5
[run]
duration = 40.0
time_step = 1.0e-4
[output]
interval = 1.0
average_start = 35.0
profile_interval = 0.05
stresses = true
[coarse_grain]
width = 0.5
start = 35.02                      # the stresses' 100 samples (t = 35.05 ... 40), not t = 35 as well
"""


def value(row, key):
    return float(row[key])


def read_vti(path):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    nx, ny, nz = (n - 1 for n in image.GetDimensions())
    cells = image.GetCellData()
    arrays = {}
    for k in range(cells.GetNumberOfArrays()):
        a = vtk_to_numpy(cells.GetArray(k))
        arrays[cells.GetArrayName(k)] = a.reshape((nz, ny, nx) + a.shape[1:])
    return arrays, image.GetSpacing()


def check_plane(particles, summary):
    check(summary["dimension"] == 2, f"summary dimension {summary['dimension']}")
    off = [p["id"] for p in particles if float(p["z"]) != 0.5 or float(p["vz"]) != 0.0 or float(p["wx"]) != 0.0
           or float(p["wy"]) != 0.0]
    check(not off, f"discs {off[:5]} left the plane z = 0.5 (or move or spin out of it)")
    holdup = COUNT * math.pi / (4.0 * WIDTH)
    check(abs(summary["mass_holdup"] / holdup - 1.0) < 1e-9, f"mass_holdup {summary['mass_holdup']}, {holdup}")


def check_stresses(out, particles):
    strips = read_csv(os.path.join(out, "stresses.csv"))
    walls = read_csv(os.path.join(out, "walls.csv"))
    g = (math.sin(ANGLE), -math.cos(ANGLE))
    check(not any("z" in key.split("_")[-1] for key in strips[0] if key.startswith("total_")),
          f"stresses.csv of discs has components along z: {list(strips[0])}")
    bottom = None
    for s in strips:
        lo = value(s, "y") - 0.5
        share = sum(MASS * min(max(float(p["y"]) - lo, 0.0), 1.0) for p in particles) / WIDTH
        expected_yy, expected_yx = -share * g[1], -share * g[0]
        if bottom is None:
            bottom = expected_yy
        bound = 1e-6 * bottom
        check(abs(value(s, "total_yy") - expected_yy) < bound,
              f"strip y = {s['y']}: P_yy {s['total_yy']}, weight above {expected_yy:.10g}")
        check(abs(value(s, "total_yx") - expected_yx) < bound,
              f"strip y = {s['y']}: P_yx {s['total_yx']}, downslope weight above {expected_yx:.10g}")
    floor = walls[0]
    weight = COUNT * MASS / WIDTH
    check(abs(value(floor, "area") - WIDTH) < 1e-12, f"the floor's measure {floor['area']}, its length {WIDTH}")
    check(abs(value(floor, "normal_stress") / (weight * math.cos(ANGLE)) - 1.0) < 1e-6,
          f"floor normal stress {floor['normal_stress']}, weight {weight * math.cos(ANGLE):.10g}")
    check(abs(value(floor, "shear_stress") / (-weight * math.sin(ANGLE)) - 1.0) < 1e-6,
          f"floor shear stress {floor['shear_stress']}, downslope weight {-weight * math.sin(ANGLE):.10g}")


def segment_below(r, y):
    """The area of a disc of radius r centred at height y that lies below y = 0."""
    if y >= r:
        return 0.0
    return r * r * math.acos(y / r) - y * math.sqrt(r * r - y * y)


def check_profiles(out, particles):
    zones = read_csv(os.path.join(out, "profiles.csv"))
    area = sum(value(z, "solids_fraction") * (value(z, "position_hi") - value(z, "position_lo")) * WIDTH for z in zones)
    # The zones start at the floor: the slivers of the discs pressed into it (overlaps ~1e-3 d) lie
    # below them.
    total = COUNT * MASS - sum(segment_below(0.5, float(p["y"])) for p in particles)
    check(abs(area - total) < 1e-9 * total, f"zone profiles hold {area!r} of disc area, the discs above the floor {total!r}")


def check_coarse_grained(out, particles, strips):
    fields, spacing = read_vti(os.path.join(out, "coarse_grained.vti"))
    rho, contact = fields["density"], fields["contact_stress"]
    check(rho.shape == (1, 80, 40), f"coarse-graining grid {rho.shape}, expected 1 x 80 x 40 cells (z x y x x)")
    cell = spacing[0] * spacing[1]  # per unit area in 2D
    total = COUNT * MASS
    check(abs(rho.sum() * cell - total) < 1e-12 * total, f"coarse-grained mass {rho.sum() * cell!r}, discs {total!r}")
    g = (math.sin(ANGLE), -math.cos(ANGLE), 0.0)
    heights = [float(p["y"]) for p in particles]
    moment_yy = sum(MASS * -g[1] * y for y in heights)
    for b, name in enumerate("xy"):
        moment = sum(MASS * -g[b] * y for y in heights)
        integral = contact[..., 3 + b].sum() * cell
        check(abs(integral - moment) < 1e-6 * moment_yy,
              f"integral of sigma_y{name} {integral:.10g}, weight's moment {moment:.10g}")
        # The strips of stresses.csv share each branch vector by its length over the same contacts
        # and samples: the same virial, to the file's 10 digits.
        virial = sum(value(s, f"contact_y{name}") for s in strips) * 1.0 * WIDTH
        check(abs(integral - virial) < 1e-8 * moment_yy, f"integral of sigma_y{name} {integral:.10g}, strips' {virial:.10g}")
    check(abs(contact[..., 5]).max() == 0.0 and abs(contact[..., 2]).max() == 0.0, "contact stress off the plane")


def numeric_columns(rows):
    """{column: [values]} of a CSV file's numeric columns (NaN kept)."""
    out = {}
    for key in rows[0]:
        try:
            out[key] = [float(r[key]) for r in rows]
        except ValueError:
            pass
    return out


def largest_relative_difference(a, b):
    """The largest |a - b| of matching columns over the column's largest |a|, and the column."""
    worst = (0.0, "")
    for key, values in a.items():
        scale = max((abs(v) for v in values if not math.isnan(v)), default=0.0)
        for x, y in zip(values, b[key]):
            if math.isnan(x) != math.isnan(y):
                worst = max(worst, (math.inf, key))
            elif scale > 0.0 and not math.isnan(x):
                worst = max(worst, (abs(x - y) / scale, key))
    return worst


def check_ranks(exe, case, tmp):
    """The landing bed's stresses and fields on two MPI ranks against one rank's."""
    if not mpirun_found():
        return
    window = ["--set", "run.duration=2.0", "--set", "output.average_start=1.5", "--set", "coarse_grain.start=1.52",
              "--set", "output.interval=0.1"]
    outs = {}
    for ranks in (1, 2):
        out = os.path.join(tmp, f"window_{ranks}")
        command = [exe, "run", case, "-o", out, "--quiet", *window]
        if ranks > 1:
            command = ["mpirun", "--oversubscribe", "-np", str(ranks), *command]
        result = subprocess.run(command, capture_output=True, text=True, env=mpi_environment())
        if not check(result.returncode == 0, f"{ranks} ranks: exited {result.returncode}: {result.stderr.strip()}"):
            return
        outs[ranks] = out
    for name in ("stresses.csv", "walls.csv"):
        one, two = (numeric_columns(read_csv(os.path.join(outs[r], name))) for r in (1, 2))
        difference, column = largest_relative_difference(one, two)
        check(difference < 1e-9, f"{name} on 2 ranks: {column} differs from one rank's by {difference:.3g} of its largest value")
    floor = read_csv(os.path.join(outs[1], "walls.csv"))[0]
    check(value(floor, "normal_stress") > 0.0, f"the bed has not reached the floor in the window: {floor['normal_stress']}")
    one, _ = read_vti(os.path.join(outs[1], "coarse_grained.vti"))
    two, _ = read_vti(os.path.join(outs[2], "coarse_grained.vti"))
    for name, field in one.items():
        scale = abs(field).max()
        difference = abs(field - two[name]).max() / scale if scale > 0.0 else abs(two[name]).max()
        check(difference < 1e-9, f"coarse-grained {name} on 2 ranks differs from one rank's by {difference:.3g} of its largest")


def main():
    exe = executable_from_argv("usage: test_dem_discs.py PATH_TO_grainflow")
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        case = os.path.join(tmp, "bed.toml")
        write_text(case, BED)
        out = os.path.join(tmp, "bed")
        status, _, err = run(exe, "run", case, "-o", out, "--quiet")
        if check(status == 0, f"bed: exited {status}: {err.strip()}"):
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
            check(summary["errors"] == [] and summary["warnings"] == [], f"{summary['errors']} {summary['warnings']}")
            particles = read_csv(os.path.join(out, "final_state.csv"))
            check_plane(particles, summary)
            check_stresses(out, particles)
            check_profiles(out, particles)
            check_coarse_grained(out, particles, read_csv(os.path.join(out, "stresses.csv")))
        check_ranks(exe, case, tmp)
    return finish("test_dem_discs")


if __name__ == "__main__":
    sys.exit(main())
