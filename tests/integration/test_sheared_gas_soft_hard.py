#!/usr/bin/python3
"""Soft against hard in unbounded simple shear: the same dilute sheared gas (1000 smooth inelastic
spheres of unit mass and diameter, e = 0.9, solids fraction 0.1, Lees-Edwards boundaries at shear
rate 1, started on a cubic lattice at T = 1 with the homogeneous profile) run by the event-driven
engine and by the DEM engine with linear spring-dashpots (kn = 1e3, 1e4, 1e5, the damping set for
e = 0.9 exactly, no friction), both measuring the stress tensor the same way (stresses.csv: one
strip holding the box). The shear heating balances the collisional loss at T ~ 11 (gamma d)^2.

- The DEM stresses converge onto the event-driven ones as the contact duration shrinks: the normal
  stresses P_yy, P_zz, the shear stress P_xy and the kinetic part P_yy^k differ from the hard
  gas's by at least 5 times less at kn = 1e5 than at kn = 1e3 (softness of order
  sqrt(T / kn) / d: a factor 10 over the range), and at kn = 1e5 (contacts of 0.007 time units,
  ~3 % of the mean free time) agree within 4 combined standard errors plus 2 % (the first-order
  softness term; measured: 0.2-1.6 %).
- The energy budget of every run closes: the event-driven one to round-off (1e-12), the DEM ones
  to velocity Verlet's error (the trapezoidal rule for the forces' work, measured 4e-7 to 8e-6,
  bound 1e-4).
- The boundaries' work is the shear work: over the averaging window the rate of
  energy_input_boundaries equals -P_xy gamma V within 4 standard errors of P_xy plus 0.5 % (the
  windows differ by a time step and the stresses are sampled every 0.1).
- Seam strips (DEM, kn = 1e4, strips one diameter thick): the two strips at the sliding seam have
  the interior's temperature and the imposed mean velocity within 4 standard errors; counting a
  straddling particle there with its own velocity instead of its image's made their temperature
  ten times the interior's.
- Event-driven strips one diameter thick: their dissipation rates add up to the run's
  dissipated_energy (collisions across the seam counted in the strip of their wrapped contact).

Usage: /usr/bin/python3 tests/integration/test_sheared_gas_soft_hard.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import (check, executable_from_argv, finish, periodic_gas_case, read_csv,  # noqa: E402
                    run_case_text)

COUNT, FRACTION, RESTITUTION, SHEAR_RATE = 1000, 0.1, 0.9, 1.0
BOX = (COUNT * math.pi / 6.0 / FRACTION) ** (1.0 / 3.0)
DURATION, AVERAGE_START = 160.0, 40.0

def case_text(engine, law, strips=True, duration=DURATION, start=AVERAGE_START):
    return periodic_gas_case(engine, 3, COUNT, BOX, BOX, 6.0 / math.pi, law, duration, start, interval=5.0,
                             profile_interval=0.1, zone_thickness=BOX if strips else None,
                             extra=f"[lees_edwards]\nshear_rate = {SHEAR_RATE!r}")


def dashpot(kn):
    """A linear spring-dashpot with e = 0.9 for two unit masses (m_eff = 1/2): F = -kn x - m_eff gamma v
    gives e = exp(-gamma pi / (2 omega)), omega^2 = kn / m_eff - gamma^2 / 4."""
    omega0 = math.sqrt(kn / 0.5)
    log_e = math.log(RESTITUTION)
    gamma = 2.0 * omega0 * (-log_e) / math.sqrt(math.pi**2 + log_e**2)
    return f'[contact]\nmodel = "linear_dashpot"\nkn = {kn!r}\ngamma_n = {gamma!r}\nfriction = 0.0'


QUANTITIES = ("total_yy", "total_zz", "total_xy", "kinetic_yy")


def measure(name, out):
    """The one strip's stresses with their errors, and the checks of the energy budget and shear work."""
    strip = read_csv(os.path.join(out, "stresses.csv"))[0]
    values = {q: (float(strip[q]), float(strip[q + "_error"])) for q in QUANTITIES}
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    bound = 1e-12 if summary["engine"] == "edmd" else 1e-4
    check(abs(summary["energy_budget_residual"]) < bound,
          f"{name}: energy budget residual {summary['energy_budget_residual']:.3g} (bound {bound:g})")
    series = read_csv(os.path.join(out, "timeseries.csv"))
    first = min(series, key=lambda r: abs(float(r["time"]) - AVERAGE_START))
    last = series[-1]
    rate = (float(last["energy_input"]) - float(first["energy_input"])) / (float(last["time"]) - float(first["time"]))
    shear_xy, error_xy = values["total_xy"]
    volume = BOX**3
    expected = -shear_xy * SHEAR_RATE * volume
    check(summary["energy_input_boundaries"] == summary["energy_input"] and expected > 0.0 and
          abs(rate - expected) < 4.0 * error_xy * SHEAR_RATE * volume + 0.005 * expected,
          f"{name}: boundary work rate {rate:.2f}, -P_xy gamma V = {expected:.2f} +- {error_xy * volume:.2f}")
    return values


def seam_strips(exe, tmp):
    """Strips one diameter thick: the two at the sliding seam against the interior's mean."""
    out = run_case_text(exe, tmp, "dem_strips", case_text("dem", dashpot(1.0e4), strips=False, duration=120.0, start=30.0))
    if out is None:
        return
    rows = read_csv(os.path.join(out, "stresses.csv"))
    profile = read_csv(os.path.join(out, "profiles.csv"))
    temperature = [float(r["kinetic_yy"]) / float(r["number"]) for r in rows]
    error = [float(r["kinetic_yy_error"]) / float(r["number"]) for r in rows]
    interior = sum(temperature[2:-2]) / len(temperature[2:-2])
    for k in (0, len(rows) - 1):
        check(abs(temperature[k] - interior) < 4.0 * error[k] + 0.02 * interior,
              f"seam strip {k}: T_yy {temperature[k]:.3f} +- {error[k]:.3f}, interior {interior:.3f}")
    # The zone profiles' mean velocity follows the imposed profile across the box, seam zones included.
    for zone in (profile[0], profile[-1]):
        y = float(zone["position"])
        u = float(zone["mean_velocity_x"])
        expected = SHEAR_RATE * (y - 0.5 * BOX)
        check(abs(u - expected) < 0.1 * SHEAR_RATE * BOX / 2.0,
              f"zone at y = {y:.2f}: mean velocity {u:.3f}, imposed profile {expected:.3f}")


def dissipation_in_strips(exe, tmp):
    """Event-driven strips: their dissipation rates, times each strip's volume and the averaging
    time, add up to the energy dissipated over that time (every collision's loss lands in the strip
    of its contact point, wrapped across the sliding seam). The average starts at the first profile
    sample after average_start (4.95: the sample at t = 5, a timeseries.csv row) and ends at the
    last (t = 40). stresses.csv and timeseries.csv print 10 significant digits: bound 1e-8."""
    out = run_case_text(exe, tmp, "edmd_strips", case_text("edmd", f"[collision]\nrestitution = {RESTITUTION!r}",
                                                           strips=False, duration=40.0, start=4.95))
    if out is None:
        return
    rows = read_csv(os.path.join(out, "stresses.csv"))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    dissipated = {float(r["time"]): float(r["energy_dissipated"]) for r in read_csv(os.path.join(out, "timeseries.csv"))}
    thickness = BOX / len(rows)  # the strips span the period exactly
    total = sum(float(r["dissipation_rate"]) for r in rows) * thickness * BOX * BOX * summary["stress_averaging_time"]
    expected = dissipated[40.0] - dissipated[5.0]
    check(len(rows) >= 8 and summary["stress_averaging_time"] == 35.0 and abs(total / expected - 1.0) < 1e-8,
          f"edmd strips: dissipation rates add up to {total!r} over {len(rows)} strips and "
          f"{summary['stress_averaging_time']} s, energy dissipated meanwhile {expected!r}")


def main():
    exe = executable_from_argv("usage: test_sheared_gas_soft_hard.py PATH_TO_grainflow")
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        hard_out = run_case_text(exe, tmp, "edmd", case_text("edmd", f"[collision]\nrestitution = {RESTITUTION!r}"))
        if hard_out is None:
            return finish("test_sheared_gas_soft_hard")
        hard = measure("edmd", hard_out)
        gaps = {}
        for kn in (1.0e3, 1.0e4, 1.0e5):
            out = run_case_text(exe, tmp, f"dem_{kn:g}", case_text("dem", dashpot(kn)))
            if out is None:
                return finish("test_sheared_gas_soft_hard")
            soft = measure(f"dem kn = {kn:g}", out)
            for q in QUANTITIES:
                gaps[(kn, q)] = (soft[q][0] - hard[q][0], math.hypot(soft[q][1], hard[q][1]), soft[q][0])
        for q in QUANTITIES:
            stiff, error, value = gaps[(1.0e5, q)]
            soft_gap = gaps[(1.0e3, q)][0]
            check(abs(stiff) < 4.0 * error + 0.02 * abs(hard[q][0]),
                  f"{q}: kn = 1e5 gives {value:.4f}, hard {hard[q][0]:.4f} (difference {stiff:.4f}, error {error:.4f})")
            check(abs(stiff) < abs(soft_gap) / 5.0,
                  f"{q}: the difference from the hard gas falls only from {soft_gap:.4f} (kn = 1e3) to {stiff:.4f} (1e5)")
        seam_strips(exe, tmp)
        dissipation_in_strips(exe, tmp)
    return finish("test_sheared_gas_soft_hard")


if __name__ == "__main__":
    sys.exit(main())
