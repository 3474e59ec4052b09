#!/usr/bin/python3
"""Stresses, wall loads and collision angles of event-driven runs from the command line
(stresses.csv, walls.csv, collision_angles.csv; OUTPUTS.md, MODELS.md "Collision stresses"):

- Campbell's no-slip Couette cell (cases/campbell1982/couette_noslip.toml, no gravity), run 10^5
  R/U_T (~1 s): the walls' mean normal stress is the servo's target (within 5%: the servo balances
  the mean over its update periods, counted alike, not the time average; that leaves the time
  average 2% low with updates every 120 collisions, 0.5% with 1200); the strips' total P_yy is uniform and equal to it, and their P_yx uniform and equal to the
  walls' shear stress (momentum balance without gravity), the strip mean exactly so (the virial
  identity), each strip within 3 standard errors; the interior stress is symmetric on average;
  the weight integral reproduces P_yy; the angle distribution is a density (integral 1) that
  favours 90-180 degrees as Campbell's Fig. 3.32 (S > 0).
- Campbell's 30-degree chute (chute_30deg.toml), 600 sqrt(R/g): the floor carries the whole weight,
  N m g cos(30) / W, and the downslope weight, less the rates at which the flow gained momentum,
  exactly (the momentum balance of the bed, rolling particles included); the weight integral down
  from the free surface matches the measured P_yy strip by strip.
- output.collision_stresses = false writes none of the three files; the key is refused for DEM.

Usage: /usr/bin/python3 tests/integration/test_edmd_stresses.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run  # noqa: E402

COUETTE = "cases/campbell1982/couette_noslip.toml"
CHUTE = "cases/campbell1982/chute_30deg.toml"
FILES = ("stresses.csv", "walls.csv", "collision_angles.csv")


def load(out):
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return summary, read_csv(os.path.join(out, "stresses.csv")), read_csv(os.path.join(out, "walls.csv"))


def value(row, key):
    return float(row[key])


def check_couette(exe, tmp):
    out = os.path.join(tmp, "couette")
    status, _, err = run(exe, "run", COUETTE, "-o", out, "--quiet", "--set", "run.duration=100000",
                         "--set", "output.average_start=10000", "--set", "output.interval=100")
    if not check(status == 0, f"couette: exited {status}: {err.strip()}"):
        return
    summary, strips, walls = load(out)
    check(summary["errors"] == [] and summary["warnings"] == [], f"couette: {summary['errors']} {summary['warnings']}")
    columns = ["y", "y_over_H"] + [f"{part}_{c}{suffix}" for part in ("collisional", "kinetic", "total")
                                   for c in ("xx", "xy", "yx", "yy") for suffix in ("", "_error")]
    columns += ["number", "mass_density", "collision_rate", "collision_rate_per_particle", "dissipation_rate",
                "momentum_rate_x", "momentum_rate_y", "weight_yx", "weight_yy"]
    check(list(strips[0].keys()) == columns, f"couette: stresses.csv columns {list(strips[0].keys())}")
    check(len(strips) == 12, f"couette: {len(strips)} strips, expected 12 (gap 24 R, strips 2 R)")
    check([w["wall"] for w in walls] == ["ylo", "yhi"], f"couette: walls {[w['wall'] for w in walls]}")

    target = 9.84375e-4
    normal = 0.5 * sum(value(w, "normal_stress") for w in walls)
    shear = 0.5 * sum(value(w, "shear_stress") for w in walls)
    for w in walls:
        check(abs(value(w, "normal_stress") / target - 1.0) < 0.05,
              f"couette: {w['wall']} normal stress {w['normal_stress']}, servo target {target}")
        check(value(w, "shear_stress") < 0.0, f"couette: {w['wall']} shear {w['shear_stress']} (u grows with y: P_yx < 0)")
        check(abs(value(w, "friction") - value(w, "shear_stress") / value(w, "normal_stress")) < 1e-6,
              f"couette: {w['wall']} friction {w['friction']}")
        check(abs(math.tan(math.radians(value(w, "impulse_angle_deg"))) - value(w, "friction")) < 1e-6,
              f"couette: {w['wall']} impulse angle {w['impulse_angle_deg']}")
        check(summary[f"wall_normal_stress_{w['wall']}"] == float(w["normal_stress"]) or
              abs(summary[f"wall_normal_stress_{w['wall']}"] / value(w, "normal_stress") - 1) < 1e-8,
              f"couette: summary wall_normal_stress_{w['wall']}")
    # The mean over the strips equals the walls' stress by the virial identity (every impulse is
    # shared out along its branch vector, wall contacts included): only the servo's gap changes and
    # the window's ends make a difference, far below 1%.
    for comp, wall_value in (("yy", normal), ("yx", shear)):
        mean = sum(value(s, f"total_{comp}") for s in strips) / len(strips)
        check(abs(mean / wall_value - 1.0) < 0.01, f"couette: strip mean P_{comp} {mean:.6g}, walls {wall_value:.6g}")
        for s in strips:
            z = (value(s, f"total_{comp}") - mean) / value(s, f"total_{comp}_error")
            check(abs(z) < 3.0, f"couette: strip y = {s['y']}: P_{comp} {s[f'total_{comp}']} is {z:.1f} standard "
                                f"errors from the mean {mean:.6g}")
    # Interior strips (not touching a wall): the mean stress is symmetric (no mean spin change).
    for s in strips[1:-1]:
        diff = value(s, "total_xy") - value(s, "total_yx")
        bound = 3.0 * math.hypot(value(s, "total_xy_error"), value(s, "total_yx_error"))
        check(abs(diff) < bound, f"couette: strip y = {s['y']}: P_xy - P_yx = {diff:.3g} (3 sigma {bound:.3g})")
        check(value(s, "collision_rate_per_particle") > 0.0, f"couette: no collisions in strip y = {s['y']}")
    # Campbell's weight integral (no gravity: the top wall's stress plus the momentum changes).
    for s in strips:
        check(abs(value(s, "weight_yy") - value(s, "total_yy")) < 3.0 * value(s, "total_yy_error"),
              f"couette: strip y = {s['y']}: weight_yy {s['weight_yy']} against P_yy {s['total_yy']}")

    angles = read_csv(os.path.join(out, "collision_angles.csv"))
    check(len(angles) == 50, f"couette: {len(angles)} angle bins")
    width = math.pi / 50
    integral = sum(value(a, "density") for a in angles) * width
    check(abs(integral - 1.0) < 1e-4, f"couette: angle density integrates to {integral}")
    upper = sum(int(a["count"]) for a in angles if value(a, "theta_deg") > 90.0)
    lower = sum(int(a["count"]) for a in angles if value(a, "theta_deg") < 90.0)
    check(upper > 1.5 * lower, f"couette: collisions at 90-180 degrees {upper}, at 0-90 {lower}")
    check(summary["savage_jeffrey_S"] > 0.0, f"couette: S = {summary['savage_jeffrey_S']}")
    sj = sum(value(a, "savage_jeffrey") for a in angles) * width
    check(abs(sj - 1.0) < 1e-4, f"couette: Savage-Jeffrey column integrates to {sj}")


def check_chute(exe, tmp):
    out = os.path.join(tmp, "chute")
    status, _, err = run(exe, "run", CHUTE, "-o", out, "--quiet", "--set", "run.duration=600",
                         "--set", "output.average_start=100", "--set", "output.interval=10")
    if not check(status == 0, f"chute: exited {status}: {err.strip()}"):
        return
    summary, strips, walls = load(out)
    check(len(walls) == 1 and walls[0]["wall"] == "ylo", f"chute: walls {walls}")
    check("y_over_H" not in strips[0], "chute: y_over_H is for cells between walls")
    n, mass, g, width, angle = 40, 1.0, 1.0, 9.6, math.radians(30.0)
    floor = walls[0]
    # The bed's momentum balance: the floor holds the weight, N m g cos(30) / W, and the downslope
    # weight less the rate at which the flow gained momentum (from the strips' momenta at the start
    # and end of averaging), exactly but for the rolling particles' sampled push (~1e-4 of it).
    h = value(strips[1], "y") - value(strips[0], "y")
    gained = [sum(value(s, f"momentum_rate_{a}") for s in strips) * h for a in "xy"]
    expected = n * mass * g * math.cos(angle) / width + gained[1]
    check(abs(value(floor, "normal_stress") / expected - 1.0) < 1e-3,
          f"chute: floor normal stress {floor['normal_stress']}, expected {expected:.7g} (gain {gained[1]:.4g})")
    expected_shear = -(n * mass * g * math.sin(angle) / width - gained[0])
    check(abs(value(floor, "shear_stress") / expected_shear - 1.0) < 1e-3,
          f"chute: floor shear stress {floor['shear_stress']}, expected {expected_shear:.7g} (gain {gained[0]:.4g})")
    for s in strips:
        if value(s, "number") < 0.5:
            continue
        check(abs(value(s, "weight_yy") - value(s, "total_yy")) < 4.0 * value(s, "total_yy_error"),
              f"chute: strip y = {s['y']}: weight integral {s['weight_yy']} against measured P_yy {s['total_yy']}")


def check_switch(exe, tmp):
    out = os.path.join(tmp, "off")
    status, _, err = run(exe, "run", COUETTE, "-o", out, "--quiet", "--set", "run.duration=200",
                         "--set", "trajectory.start=0", "--set", "output.collision_stresses=false")
    if check(status == 0, f"off: exited {status}: {err.strip()}"):
        for name in FILES:
            check(not os.path.exists(os.path.join(out, name)), f"off: {name} written")
    status, _, err = run(exe, "run", "cases/bench/chute_hooke.toml", "-o", os.path.join(tmp, "dem"), "--quiet",
                         "--set", "output.collision_stresses=true")
    check(status == 2 and "collision_stresses" in err, f"dem: exited {status}: {err.strip()}")


def main():
    exe = executable_from_argv("usage: test_edmd_stresses.py PATH_TO_grainflow")
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        check_couette(exe, tmp)
        check_chute(exe, tmp)
        check_switch(exe, tmp)
    return finish("test_edmd_stresses")


if __name__ == "__main__":
    sys.exit(main())
