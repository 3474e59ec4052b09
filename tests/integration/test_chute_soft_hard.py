#!/usr/bin/python3
"""Soft against hard on Campbell's 30 degree chute: 40 rough discs (R = m = g = 1, e_p = 0.6 between
discs, e_w = 0.8 at the rough floor, the 10 x 4 block of cases/campbell1982/chute_30deg.toml started
at u = 3) run by the event-driven engine with Campbell's own collision rule (after each collision the
pair is put 2.00001 R apart and every collision is inelastic and rough) and with the TC model (a
collision within 1e-4 of a previous one is elastic and smooth), and by the DEM engine as soft discs
made by tools/campbell_soft_discs.py: linear springs kn = 1e3 and 1e5, gamma_n giving e_p and e_w
exactly, no sliding (friction 1000) and kt = (kn / 12) (omega_d / omega_0)^2, which ends the
tangential spring's quarter period with the contact: tangential restitution 0, Campbell's fully
rough collisions.

The flow is a transient (the dense block accelerates down the chute), so the comparison is of the
ensemble mean over 32 seeds of the kinetic energy over t = 25-50 sqrt(R/g). Measured (32 seeds):
Campbell's scheme 838 +- 35, TC 1343 +- 36, kn = 1e3 1774 +- 42, kn = 1e5 1110 +- 34.

- The soft discs converge onto Campbell's scheme: their difference from it falls by more than half
  from kn = 1e3 to 1e5 (measured: to 0.29 of it; the full-length study in
  docs/validation/campbell1982.md finds it falling as about kn^-0.27 up to kn = 1e6 and
  extrapolating onto Campbell's scheme).
- They do not converge onto the TC model: already at kn = 1e5 the soft discs keep less kinetic
  energy than TC discs, whose elastic smooth collisions inside dense clusters dissipate less than
  any contact law with these restitutions. Both margins are above 3.5 standard errors of the
  differences (4.4 and 4.7).
- The energy budget of every run closes (event-driven: round-off, with the reseparations' work
  booked; DEM: velocity Verlet's error, bound 1e-4).

Usage: /usr/bin/python3 tests/integration/test_chute_soft_hard.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run_case_text  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from campbell_soft_discs import soft_disc_case  # noqa: E402

SEEDS = range(1, 33)
WINDOW = (25.0, 50.0)
RESTITUTION_PAIRS, RESTITUTION_WALL = 0.6, 0.8

CHUTE = """[engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [9.6, 80.0, 1.0]
boundary = {{ x = "periodic", y = ["wall", "open"], z = "periodic" }}
[gravity]
vector = [0.5, -0.8660254037844386, 0.0]
[[species]]
name = "disc"
diameter = 2.0
density = 0.3183098861837907
count = 40
[particles]
init = "lattice"
region_hi = [9.6, 24.0, 1.0]
lattice_spacing = 1.2
lattice_jitter = 0.3
initial_velocity = [3.0, 0.0, 0.0]
initial_temperature = 0.01
seed = {seed}
{law}
[run]
duration = {duration!r}
[output]
interval = 1.0
average_start = {start!r}
"""

CAMPBELL = f"""[collision]
restitution = {RESTITUTION_PAIRS!r}
roughness = "rough"
inertia_factor = 0.5
rolling_speed = 1.0e-4
{{rule}}
[walls.ylo]
restitution = {RESTITUTION_WALL!r}
condition = "rough"
"""


CAMPBELL_SCHEME = CAMPBELL.format(rule="contact_duration = 0.0\nseparation_gap = 1.0e-5")
VARIANTS = {  # name: (law, stiffness of the soft twin or None)
    "campbell": (CAMPBELL_SCHEME, None),
    "tc": (CAMPBELL.format(rule="contact_duration = 1.0e-4"), None),
    "kn_1e3": (CAMPBELL_SCHEME, 1.0e3),
    "kn_1e5": (CAMPBELL_SCHEME, 1.0e5),
}


def window_energy(exe, tmp, name, law, kn, seed):
    """The run's mean kinetic energy over WINDOW (the soft twin's when `kn` is given), or None after a
    failed check."""
    text = CHUTE.format(seed=seed, law=law, duration=WINDOW[1], start=WINDOW[0])
    if kn is not None:
        text = soft_disc_case(text, kn)
    out = run_case_text(exe, tmp, f"{name}_{seed}", text)
    if out is None:
        return None
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    bound = 1e-10 if kn is None else 1e-4
    check(abs(summary["energy_budget_residual"]) < bound,
          f"{name} seed {seed}: energy budget residual {summary['energy_budget_residual']:.3g} (bound {bound:g})")
    rows = read_csv(os.path.join(out, "timeseries.csv"))
    energies = [float(r["kinetic_energy"]) for r in rows if WINDOW[0] - 1e-6 <= float(r["time"]) <= WINDOW[1] + 1e-6]
    return sum(energies) / len(energies) if check(energies, f"{name} seed {seed}: no samples in {WINDOW}") else None


def main():
    exe = executable_from_argv("usage: test_chute_soft_hard.py PATH_TO_grainflow")
    if exe is None:
        return 2
    means = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, (law, kn) in VARIANTS.items():
            values = [window_energy(exe, tmp, name, law, kn, seed) for seed in SEEDS]
            if None in values:
                return finish("test_chute_soft_hard")
            means[name] = (statistics.fmean(values), statistics.stdev(values) / math.sqrt(len(values)))
            print(f"{name}: mean kinetic energy over t = {WINDOW[0]:g}-{WINDOW[1]:g}: "
                  f"{means[name][0]:.1f} +- {means[name][1]:.1f}")
    hard, hard_error = means["campbell"]
    soft, stiff = means["kn_1e3"], means["kn_1e5"]
    half_soft_gap = (soft[0] - hard) / 2.0
    check(stiff[0] - hard < half_soft_gap,
          f"soft discs against Campbell's scheme ({hard:.1f} +- {hard_error:.1f}): kn = 1e3 differs by "
          f"{soft[0] - hard:.1f}, kn = 1e5 by {stiff[0] - hard:.1f}, not less than half of it")
    check(stiff[0] < means["tc"][0],
          f"kn = 1e5 keeps {stiff[0]:.1f} +- {stiff[1]:.1f}, not less than the TC model's "
          f"{means['tc'][0]:.1f} +- {means['tc'][1]:.1f}")
    return finish("test_chute_soft_hard")


if __name__ == "__main__":
    sys.exit(main())
