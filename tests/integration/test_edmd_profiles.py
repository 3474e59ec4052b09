#!/usr/bin/python3
"""Strip profiles of event-driven runs ("Strip profiles", "Chute flow as an engineer reads
it"; OUTPUTS.md, profiles.csv and summary.json of an edmd run), on Campbell's two cases:

- cases/campbell1982/couette_noslip.toml (lengthened to 20000 R/U_T: 0.3 s of wall time): with
  no-slip walls the mean velocity runs linearly from ~0 at the bottom wall to U_T at the top
  (Campbell section 3.2, Fig. 3.16); the slips at the walls in summary.json are small and agree
  with the profile's end strips; the scaled temperatures are the temperatures times (H/U_T)^2.
- cases/campbell1982/chute_30deg.toml (its first 500 sqrt(R/g), averages from 200: 0.3 s): slip at the bottom
  (u_s > 0), flow depth H, Froude number, profile parameters and critical Froude number finite and
  positive; the mass flow is the mean velocity times the mass per width; every strip's solids
  fraction times its area is pi R^2 per particle in it; this chute accelerates throughout, so the
  convergence check reports steady_from = null with a warning.
- profiles.csv has its columns in both, with y_over_gap (Couette) or y_over_H (chute).

Usage: /usr/bin/python3 tests/integration/test_edmd_profiles.py PATH_TO_grainflow  (from the repo root)
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
COMMON_COLUMNS = ["strip", "y", "solids_fraction", "solids_fraction_error", "particles", "u", "u_error", "v",
                  "omega", "omega_error", "u_variance", "u_variance_error", "v_variance", "uv_covariance",
                  "rotational_temperature", "granular_temperature", "temperature", "translational_temperature",
                  "temperature_lan", "temperature_lan_error", "du_dy", "du_dy_error", "S_prose", "S_listing",
                  "plug_flow"]
COUETTE_COLUMNS = ["y_over_gap", "u_variance_scaled", "v_variance_scaled", "rotational_temperature_scaled",
                   "granular_temperature_scaled", "granular_temperature_scaled_error"]
CHUTE_KEYS = ["flow_depth", "mass_flow_per_width", "mass_per_width", "mean_velocity", "depth_mean_velocity",
              "max_velocity", "froude_number", "froude_number_normal", "mean_solids_fraction",
              "momentum_coefficient_gamma", "pressure_coefficient_Gamma", "critical_froude_number", "slip_velocity",
              "slip_fraction", "slip_velocity_scaled"]


def run_case(exe, tmp, name, case, *overrides):
    out = os.path.join(tmp, name)
    args = ["run", case, "-o", out, "--quiet"]
    for o in overrides:
        args += ["--set", o]
    status, _, err = run(exe, *args)
    if not check(status == 0, f"{name}: exited {status}: {err.strip()}"):
        return None, None
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    path = os.path.join(out, "profiles.csv")
    if not check(os.path.exists(path), f"{name}: no profiles.csv"):
        return summary, None
    rows = read_csv(path)
    with open(path) as f:
        check(any(line.startswith("# units:") for line in f), f"{name}: profiles.csv has no '# units:' line")
    return summary, rows


def check_columns(name, rows, columns):
    if not check(rows, f"{name}: profiles.csv has no rows"):
        return False
    missing = [c for c in columns if c not in rows[0]]
    return check(not missing, f"{name}: profiles.csv lacks columns {missing}")


def check_couette(exe, tmp):
    summary, rows = run_case(exe, tmp, "couette", COUETTE, "run.duration=20000")
    if rows is None or not check_columns("couette", rows, COMMON_COLUMNS + COUETTE_COLUMNS):
        return
    for key in ("mean_gap", "shear_speed", "slip_fraction_bottom", "slip_fraction_top", "steady_from",
                "slip_fraction_bottom_error", "slip_fraction_top_error", "averaged_when_steady"):
        check(key in summary, f"couette: summary.json lacks '{key}'")
    speed, gap = summary["shear_speed"], summary["mean_gap"]
    # keep_shear_rate: U_T / H stays at its start value 1/24, up to the gap's drift between servo
    # updates (the top speed is reset at each; the gap moves by < 0.1 R between them, of ~26 R).
    check(abs(speed / gap * 24.0 - 1.0) < 4e-3, f"couette: U_T/H = {speed / gap}, expected 1/24")
    # Linear from 0 (bottom wall at rest) to U_T: u / U_T against y / gap. With 40 discs the strips'
    # means scatter by 1-2 % of U_T about a straight line (longer runs and other seeds: within 2.5 %)
    # and each wall slips by ~3 %; a plug or wall-bound shear zones (Campbell's rough walls, Fig.
    # 3.15: ~20 % slip and most shear next to the walls) would leave it by 10 % or more.
    worst = 0.0
    for r in rows:
        deviation = float(r["u"]) / speed - float(r["y_over_gap"])
        worst = max(worst, abs(deviation))
    check(worst < 0.05, f"couette: u/U_T departs from y/gap by up to {worst:.3f} of U_T (no-slip: linear)")
    # Slips as fractions of U_T: small, and the end strips' velocities relative to the walls.
    bottom, top = summary["slip_fraction_bottom"], summary["slip_fraction_top"]
    check(0 <= bottom < 0.1 and 0 <= top < 0.1, f"couette: slip fractions {bottom}, {top}: no-slip walls slip < 10 %")
    check(abs(bottom - float(rows[0]["u"]) / speed) < 1e-6, f"couette: slip_fraction_bottom {bottom} is not u_0 / U_T")
    # The shear rate from the fit: in the middle about U_T/H (within the 5 % of the linearity check).
    middle = rows[len(rows) // 2]
    check(abs(float(middle["du_dy"]) / (speed / gap) - 1.0) < 0.3,
          f"couette: du/dy at mid-gap {middle['du_dy']}, U_T/H = {speed / gap}")
    # Scaled temperatures are the temperatures times (H/U_T)^2 (10 printed digits).
    for r in rows:
        for col in ("u_variance", "v_variance", "granular_temperature"):
            scaled = float(r[col]) * (gap / speed) ** 2
            check(abs(float(r[col + "_scaled"]) - scaled) <= 1e-6 * scaled, f"couette: {col}_scaled is not (H/U_T)^2 x {col}")
    # Campbell's Fig. 3.16: density practically uniform, no plugs at nu ~ 0.45.
    check(all(r["plug_flow"] == "0" for r in rows), "couette: a strip flagged as plug flow at nu < pi/4")


def check_chute(exe, tmp):
    # The case runs 3000 sqrt(R/g) to steady state; its first 500 (averages from 200) still accelerate.
    summary, rows = run_case(exe, tmp, "chute", CHUTE, "run.duration=500", "output.average_start=200")
    if rows is None or not check_columns("chute", rows, COMMON_COLUMNS + ["y_over_H"]):
        return
    missing = [k for k in CHUTE_KEYS + ["steady_from", "flow_regime"] if k not in summary]
    if not check(not missing, f"chute: summary.json lacks {missing}"):
        return
    for key in CHUTE_KEYS:
        value = summary[key]
        check(isinstance(value, (int, float)) and math.isfinite(value) and value > 0, f"chute: {key} = {value!r}")
    # Standard errors of the scalars: positive, and (300 sqrt(R/g) of samples every 1) well under the
    # values themselves; the slip velocity's is the bottom strip's u error.
    for key in ("flow_depth", "mass_flow_per_width", "mean_velocity", "froude_number", "slip_velocity", "slip_fraction"):
        error = summary.get(key + "_error")
        check(isinstance(error, (int, float)) and 0 < error < 0.5 * summary[key], f"chute: {key}_error = {error!r}")
    check(summary["slip_velocity_error"] == float(rows[0]["u_error"]) or
          abs(summary["slip_velocity_error"] - float(rows[0]["u_error"])) < 1e-6 * summary["slip_velocity_error"],
          "chute: slip_velocity_error is not the bottom strip's u_error")
    check(summary["averaged_when_steady"] is False, "chute: averaged_when_steady for an accelerating flow")
    # Slip at the bottom (Campbell: ~40 % of the maximum velocity at 30 degrees).
    check(0 < summary["slip_fraction"] < 1, f"chute: slip_fraction {summary['slip_fraction']}")
    check(abs(summary["slip_velocity"] - float(rows[0]["u"])) < 1e-6 * summary["slip_velocity"],
          "chute: slip_velocity is not the bottom strip's mean velocity")
    # Mass flow = mean velocity x mass per width; Fr = u / sqrt(g H) with g = 1; cos 30 in Fr_c.
    check(abs(summary["mass_flow_per_width"] - summary["mean_velocity"] * summary["mass_per_width"])
          < 1e-6 * summary["mass_flow_per_width"], "chute: mass flow is not mean velocity x mass per width")
    check(abs(summary["froude_number"] - summary["mean_velocity"] / math.sqrt(summary["flow_depth"])) < 1e-6 * summary["froude_number"],
          "chute: froude_number is not u / sqrt(g H)")
    fr_c = math.sqrt(summary["pressure_coefficient_Gamma"] * math.cos(math.radians(30)) / summary["momentum_coefficient_gamma"])
    check(abs(summary["critical_froude_number"] - fr_c) < 1e-6 * fr_c, "chute: Fr_c is not (Gamma cos(alpha) / gamma)^1/2")
    regime = "supercritical" if summary["froude_number"] > fr_c else "subcritical"
    check(summary["flow_regime"] == regime, f"chute: flow_regime {summary['flow_regime']!r}, expected {regime!r}")
    # Fixed strips 2 R thick across the 9.6 R width: solids fraction x area = pi R^2 x particles in it.
    for r in rows:
        area, particles = float(r["solids_fraction"]) * 2.0 * 9.6, float(r["particles"])
        check(abs(area - math.pi * particles) < 1e-6 * (1 + area), f"chute: strip {r['strip']}: nu A = {area}, pi n = {math.pi * particles}")
    h = summary["flow_depth"]
    check(all(abs(float(r["y_over_H"]) - float(r["y"]) / h) < 1e-6 for r in rows), "chute: y_over_H is not y / H")
    # This case accelerates for its whole 500 sqrt(R/g) (its kinetic energy grows 3.3-fold after t = 200).
    check(summary["steady_from"] is None, f"chute: steady_from {summary['steady_from']}, expected null (accelerating)")
    check(any("not converged" in w for w in summary["warnings"]), f"chute: no convergence warning in {summary['warnings']}")


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    os.chdir(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))  # the repo root
    with tempfile.TemporaryDirectory(prefix="grainflow_profiles_") as tmp:
        check_couette(exe, tmp)
        check_chute(exe, tmp)
    return finish("test_edmd_profiles")


if __name__ == "__main__":
    sys.exit(main())
