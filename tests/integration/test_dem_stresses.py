#!/usr/bin/python3
"""Stresses and wall loads of soft-sphere runs from the command line (output.stresses = true:
stresses.csv, walls.csv; OUTPUTS.md):

- A bed of 200 frictional spheres (mu = 0.5 with each other and the floor) settled on a flat floor
  under gravity tilted 10 degrees from the floor's normal, in reduced units (d = rho = g = 1), its
  stresses averaged over the last 5 time units, when it is at rest (kinetic energy ~1e-12 of its
  potential). At rest every particle's forces balance, so the force carried across a plane y by
  the branch vectors crossing it is the weight of the particles whose centres lie above: each
  strip's total P_yb equals -(1/(h A)) sum_i m_i g_b clamp(y_i - lo, 0, h) exactly, computed here
  from final_state.csv. Bound 1e-6 of the bottom strip's P_yy: the residual motion (velocities
  ~1e-8) and the force recomputed at full-step velocities leave ~1e-8. Hence P_yx / P_yy =
  -tan(10 deg) at every depth; the floor carries N m g cos(theta) / A normally and -N m g
  sin(theta) / A in shear (its friction -tan theta), to the same bound; the kinetic part vanishes.
- The same bed on a bumpy floor (half-spheres of one diameter on a square lattice of one diameter):
  the bumps carry it, and their contact forces are the floor's load in walls.csv: the weight less
  the momentum the still-creeping bed gains over the window (from stresses.csv), normal and
  downslope, to 1e-6.
- The same bed coarse-grained ([coarse_grain], a Gaussian of width 0.5 on cells 0.5 wide,
  coarse_grained.vti read with VTK's reader): the density integrates over the cells to the
  particles' mass to 1e-12 (round-off: the kernel is normalized over the cells for each particle);
  the contact stress's y rows integrate to the contact virial, which at rest is the weight's moment
  -sum_i m_i g_b y_i (floor at y = 0), to 1e-6 of its yy part (the residual motion, as above). The
  plane-averaged fields keep the momentum balance d sigma_yb / dy = rho g_b: sigma_yy(y) equals the
  weight of the coarse-grained density above, to 1% of the bottom value, and sigma_yx / sigma_yy =
  -tan(10 deg) to 0.5%, at 4 widths and more above the floor (next to it the kernel, renormalized
  inside the box, is no longer the continuous one the balance holds for exactly; the tolerance is the
  rectangle rule's on cells one kernel width thick plus the discrete kernel's departure from it,
  measured 3e-3 and 1.3e-3).
- A layer of 600 spheres flowing down a bumpy incline at 24 degrees (soft contacts, kn = 2e4, so it
  is quick), still accelerating while its stresses are averaged (t = 20-60): each strip's total
  P_yy and P_yx carry the weight above less the momentum the layer above gains, Campbell's weight
  integral (weight_yy, weight_yx: momentum balance, steady or not), within 4 block-averaged standard
  errors, in every strip at least half as full as the fullest (the surface's sparse strips are left
  out: the weight integral's rectangle rule over a strip is crude where the density falls to zero).
  The kinetic part is nonzero there (the test of the full tensor, not the contacts alone).
- The columns are the event-driven file's with the non-kinetic part named contact_*; the collision
  rates are nan (a soft-sphere run has contacts, not collisions).
- Without output.stresses no stresses.csv or walls.csv is written; the key is refused for edmd.

Usage: /usr/bin/python3 tests/integration/test_dem_stresses.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run, run_case_text, write_text  # noqa: E402

ANGLE = math.radians(10.0)
WIDTH = 6.0  # the box is WIDTH x 30 x WIDTH, periodic in x and z
COUNT = 200

BED = f"""
[engine]
kind = "dem"
dimension = 3
[domain]
lo = [0.0, 0.0, 0.0]
hi = [{WIDTH}, 30.0, {WIDTH}]
boundary = {{ x = "periodic", y = ["wall", "open"], z = "periodic" }}
[gravity]
vector = [{math.sin(ANGLE)!r}, {-math.cos(ANGLE)!r}, 0.0]
[[species]]
name = "grain"
diameter = 1.0
density = 1.0
count = {COUNT}
[particles]
init = "random"
region_lo = [0.0, 0.0, 0.0]
region_hi = [{WIDTH}, 20.0, {WIDTH}]
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
"""


CHUTE_ANGLE = math.radians(24.0)
CHUTE = f"""
[engine]
kind = "dem"
dimension = 3
[domain]
lo = [0.0, 0.0, 0.0]
hi = [10.0, 40.0, 6.0]
boundary = {{ x = "periodic", y = ["bumpy", "open"], z = "periodic" }}
[gravity]
vector = [{math.sin(CHUTE_ANGLE)!r}, {-math.cos(CHUTE_ANGLE)!r}, 0.0]
[[species]]
name = "grain"
diameter = 1.0
density = 1.0
count = 600
[particles]
init = "random"
region_lo = [0.0, 1.0, 0.0]
region_hi = [10.0, 30.0, 6.0]
seed = 3
[contact]
model = "linear_dashpot"
kn = 2.0e4
kt = {2.0e4 * 2.0 / 7.0!r}
gamma_n = 15.8
gamma_t = 0.0
friction = 0.5
[walls.ylo]
bump_diameter = 1.0
spacing = 1.0
[run]
duration = 60.0
time_step = 3.0e-4
[output]
interval = 5.0
average_start = 20.0
profile_interval = 0.1
stresses = true
"""


def value(row, key):
    return float(row[key])


def check_bed_at_rest(exe, tmp):
    case = os.path.join(tmp, "bed.toml")
    write_text(case, BED)
    out = os.path.join(tmp, "bed")
    status, _, err = run(exe, "run", case, "-o", out, "--quiet")
    if not check(status == 0, f"bed: exited {status}: {err.strip()}"):
        return
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    check(summary["errors"] == [] and summary["warnings"] == [], f"bed: {summary['errors']} {summary['warnings']}")
    strips = read_csv(os.path.join(out, "stresses.csv"))
    walls = read_csv(os.path.join(out, "walls.csv"))
    particles = read_csv(os.path.join(out, "final_state.csv"))
    columns = ["y"] + [f"{part}_{a}{b}{suffix}" for part in ("contact", "kinetic", "total")
                       for a in "xyz" for b in "xyz" for suffix in ("", "_error")]
    columns += ["number", "mass_density", "collision_rate", "collision_rate_per_particle", "dissipation_rate",
                "momentum_rate_x", "momentum_rate_y", "momentum_rate_z", "weight_yx", "weight_yy", "weight_yz"]
    check(list(strips[0].keys()) == columns, f"bed: stresses.csv columns {list(strips[0].keys())}")
    check(math.isnan(value(strips[0], "collision_rate")), "bed: a soft-sphere run's collision_rate is not nan")
    check(summary["stress_samples"] == 100, f"bed: {summary['stress_samples']} stress samples, expected 100")

    mass = math.pi / 6.0
    g = (math.sin(ANGLE), -math.cos(ANGLE))
    area = WIDTH * WIDTH
    bottom = None
    for s in strips:
        lo = value(s, "y") - 0.5
        share = sum(mass * min(max(float(p["y"]) - lo, 0.0), 1.0) for p in particles) / area
        expected_yy, expected_yx = -share * g[1], -share * g[0]
        if bottom is None:
            bottom = expected_yy
        bound = 1e-6 * bottom
        check(abs(value(s, "total_yy") - expected_yy) < bound,
              f"bed: strip y = {s['y']}: P_yy {s['total_yy']}, weight above {expected_yy:.10g}")
        check(abs(value(s, "total_yx") - expected_yx) < bound,
              f"bed: strip y = {s['y']}: P_yx {s['total_yx']}, downslope weight above {expected_yx:.10g}")
        check(abs(value(s, "kinetic_yy")) < bound, f"bed: strip y = {s['y']}: kinetic P_yy {s['kinetic_yy']} at rest")
        if expected_yy > 0.1 * bottom:  # the ratio where the stresses are well above the bound
            ratio = value(s, "total_yx") / value(s, "total_yy")
            check(abs(ratio + math.tan(ANGLE)) < 1e-5, f"bed: strip y = {s['y']}: P_yx/P_yy {ratio}, -tan 10 deg")
    floor = walls[0]
    check(floor["wall"] == "ylo", f"bed: walls.csv lists {floor['wall']}")
    weight = COUNT * mass / area
    check(abs(value(floor, "normal_stress") / (weight * math.cos(ANGLE)) - 1.0) < 1e-6,
          f"bed: floor normal stress {floor['normal_stress']}, weight {weight * math.cos(ANGLE):.10g}")
    check(abs(value(floor, "shear_stress") / (-weight * math.sin(ANGLE)) - 1.0) < 1e-6,
          f"bed: floor shear stress {floor['shear_stress']}, downslope weight {-weight * math.sin(ANGLE):.10g}")
    check(abs(value(floor, "friction") + math.tan(ANGLE)) < 1e-6, f"bed: floor friction {floor['friction']}")
    check(abs(summary["wall_normal_stress_ylo"] / value(floor, "normal_stress") - 1.0) < 1e-8,
          "bed: summary wall_normal_stress_ylo differs from walls.csv")
    check(summary["coarse_grain_samples"] == 101, f"bed: {summary['coarse_grain_samples']} coarse-grained samples, "
          "expected 101 (t = 35, 35.05, ..., 40)")
    check_coarse_grained_bed(out, particles)


# The same bed on a bumpy floor (half-spheres of the grains' size on a square lattice of one
# diameter): the bumps carry the whole weight, and their pushes are the floor's load.
BUMPY_BED = (BED.replace('y = ["wall", "open"]', 'y = ["bumpy", "open"]')
             .replace("region_lo = [0.0, 0.0, 0.0]", "region_lo = [0.0, 1.0, 0.0]")
             .replace("[walls.ylo]\nfriction = 0.5", "[walls.ylo]\nfriction = 0.5\nbump_diameter = 1.0\nspacing = 1.0"))


def check_bumpy_floor(exe, tmp):
    out = run_case_text(exe, tmp, "bumpy_bed", BUMPY_BED)
    if out is None:
        return
    strips = read_csv(os.path.join(out, "stresses.csv"))
    floor = read_csv(os.path.join(out, "walls.csv"))[0]
    check(floor["wall"] == "ylo", f"bumpy bed: walls.csv lists {floor['wall']}")
    # The bed's momentum balance: the floor holds the weight less the rate at which the bed gained
    # momentum over the averaging window (from the strips' momenta at its start and end). On bumps
    # the bed still creeps at ~1e-5 d per unit time, which moves the floor's load by a few 1e-6 of
    # the weight from its static value; the gain accounts for that, leaving the rectangle rule of
    # the sampled forces (measured 5e-8 and 1.2e-7 at t = 40 and 60): bound 1e-6. Without the
    # bumps' pushes the floor reads zero.
    h = value(strips[1], "y") - value(strips[0], "y")
    gained = [sum(value(s, f"momentum_rate_{a}") for s in strips) * h for a in "xy"]
    weight = COUNT * math.pi / 6.0 / (WIDTH * WIDTH)
    expected_normal = weight * math.cos(ANGLE) + gained[1]
    expected_shear = -(weight * math.sin(ANGLE) - gained[0])
    check(abs(value(floor, "normal_stress") / expected_normal - 1.0) < 1e-6,
          f"bumpy bed: floor normal stress {floor['normal_stress']}, weight {expected_normal:.10g}")
    check(abs(value(floor, "shear_stress") / expected_shear - 1.0) < 1e-6,
          f"bumpy bed: floor shear stress {floor['shear_stress']}, downslope weight {expected_shear:.10g}")
    # And so, to the creep's few 1e-6, the static weight.
    check(abs(value(floor, "friction") + math.tan(ANGLE)) < 1e-4, f"bumpy bed: floor friction {floor['friction']}")


def check_flowing_chute(exe, tmp):
    out = run_case_text(exe, tmp, "chute", CHUTE)
    if out is None:
        return
    strips = read_csv(os.path.join(out, "stresses.csv"))
    fullest = max(value(s, "number") for s in strips)
    compared = 0
    for s in strips:
        if value(s, "number") < 0.5 * fullest:
            continue
        compared += 1
        for part in ("yy", "yx"):
            total, error, weight = value(s, f"total_{part}"), value(s, f"total_{part}_error"), value(s, f"weight_{part}")
            check(error > 0.0 and abs(total - weight) < 4.0 * error,
                  f"chute: strip y = {s['y']}: P_{part} {total:.5g} +- {error:.2g}, weight integral {weight:.5g}")
    check(compared >= 8, f"chute: only {compared} strips hold the flowing layer")
    kinetic = max(value(s, "kinetic_xx") for s in strips)
    check(kinetic > 0.01 * value(strips[0], "total_yy"), f"chute: kinetic P_xx at most {kinetic}: the layer did not flow")


def read_vti(path):
    """The cell arrays of an image-data file as numpy arrays indexed [z, y, x, component], and the spacing."""
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


def check_coarse_grained_bed(out, particles):
    path = os.path.join(out, "coarse_grained.vti")
    if not check(os.path.exists(path), "bed: no coarse_grained.vti"):
        return
    fields, spacing = read_vti(path)
    check(sorted(fields) == sorted(["density", "solid_fraction", "momentum_density", "velocity", "kinetic_stress",
                                    "contact_stress", "total_stress"]), f"bed: coarse_grained.vti holds {sorted(fields)}")
    rho, contact = fields["density"], fields["contact_stress"]
    check(rho.shape == (12, 60, 12), f"bed: coarse-graining grid {rho.shape}, expected 12 x 60 x 12 cells")
    cell = spacing[0] * spacing[1] * spacing[2]
    mass = math.pi / 6.0
    total = COUNT * mass
    check(abs(rho.sum() * cell - total) < 1e-12 * total, f"bed: coarse-grained mass {rho.sum() * cell!r}, particles {total!r}")
    g = (math.sin(ANGLE), -math.cos(ANGLE), 0.0)
    heights = [float(p["y"]) for p in particles]
    moment_yy = sum(mass * -g[1] * y for y in heights)
    for b, name in enumerate("xyz"):
        moment = sum(mass * -g[b] * y for y in heights)
        integral = contact[..., 3 + b].sum() * cell
        check(abs(integral - moment) < 1e-6 * moment_yy,
              f"bed: integral of sigma_y{name} {integral:.10g}, weight's moment {moment:.10g}")
    # Plane averages (x and z periodic) against the weight of the density above.
    dy = spacing[1]
    rho_y = rho.mean(axis=(0, 2))
    syy, syx = contact[..., 4].mean(axis=(0, 2)), contact[..., 3].mean(axis=(0, 2))
    above = np.array([rho_y[k + 1:].sum() * dy + 0.5 * rho_y[k] * dy for k in range(len(rho_y))])
    weight = -g[1] * above
    width = 0.5
    for k in range(len(rho_y)):
        y = (k + 0.5) * dy
        if y < 4 * width or weight[k] < 0.1 * weight[0]:
            continue
        check(abs(syy[k] - weight[k]) < 0.01 * weight[0],
              f"bed: coarse-grained sigma_yy({y}) {syy[k]:.6g}, weight of the density above {weight[k]:.6g}")
        check(abs(syx[k] / syy[k] + math.tan(ANGLE)) < 5e-3 * math.tan(ANGLE),
              f"bed: coarse-grained sigma_yx / sigma_yy at y = {y}: {syx[k] / syy[k]:.6g}, -tan 10 deg")
    kinetic = np.abs(fields["kinetic_stress"]).max()
    check(kinetic < 1e-6 * weight[0], f"bed: coarse-grained kinetic stress {kinetic} at rest")


def check_switch(exe, tmp):
    out = os.path.join(tmp, "off")
    status, _, err = run(exe, "run", "cases/demo/vibrated_bed.toml", "-o", out, "--quiet", "--set", "run.duration=0.01")
    if check(status == 0, f"off: exited {status}: {err.strip()}"):
        for name in ("stresses.csv", "walls.csv", "coarse_grained.vti"):
            check(not os.path.exists(os.path.join(out, name)), f"off: {name} written")
    status, _, err = run(exe, "run", "cases/campbell1982/couette_noslip.toml", "-o", os.path.join(tmp, "edmd"),
                         "--quiet", "--set", "output.stresses=true")
    check(status == 2 and "output.stresses" in err and "collision_stresses" in err, f"edmd: exited {status}: {err.strip()}")


def main():
    exe = executable_from_argv("usage: test_dem_stresses.py PATH_TO_grainflow")
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        check_bed_at_rest(exe, tmp)
        check_bumpy_floor(exe, tmp)
        check_flowing_chute(exe, tmp)
        check_switch(exe, tmp)
    return finish("test_dem_stresses")


if __name__ == "__main__":
    sys.exit(main())
