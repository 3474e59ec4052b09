#!/usr/bin/python3
"""Soft spheres against hard ones: the same elastic gas (382 smooth spheres of unit mass and
diameter at solids fraction 0.2, periodic cube, T = 1, started on a cubic lattice) run by the
event-driven engine and by the DEM engine with linear springs kn = 1e3, 1e4 and 1e5 (no damping,
no friction), both measuring the pressure tensor the same way (stresses.csv: one strip holding the
box, so Z = trace(total) / trace(kinetic), the temperature drops out).

- Hard spheres: Z agrees with Carnahan-Starling, (1 + eta + eta^2 - eta^3) / (1 - eta)^3 = 2.406,
  within 4 block-averaged standard errors.
- Soft spheres: a harmonic repulsion U = kn delta^2 / 2 acts as a hard sphere of the Barker-Henderson
  diameter d_BH = d - sqrt(pi T / (2 kn)) (the integral of 1 - exp(-U/T) over the overlap), so Z is
  Carnahan-Starling's at eta (d_BH / d)^3: 2.16, 2.32 and 2.38 for the three stiffnesses. Each run
  agrees with it within 4 standard errors plus 2% of Z - 1 (the perturbation theory's first order:
  its next term is of the order of the square of the softness sqrt(pi T / 2 kn) / d <= 0.04).
- So the DEM pressure converges onto the event-driven one as the contact duration shrinks: its
  shortfall falls with each tenfold stiffening (roughly as kn^(-1/2)), and at kn = 1e5 (contacts of
  0.007 time units, 3% of the mean free time) it is within 4 combined errors plus 2% of Z - 1.

Usage: /usr/bin/python3 tests/integration/test_soft_hard_spheres.py PATH_TO_grainflow  (from the repo root)
"""
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

COUNT = 382
BOX = 10.0
ETA = COUNT * math.pi / 6.0 / BOX**3

GAS = f"""
[engine]
kind = "{{engine}}"
dimension = 3
[domain]
lo = [0.0, 0.0, 0.0]
hi = [{BOX}, {BOX}, {BOX}]
boundary = {{{{ x = "periodic", y = "periodic", z = "periodic" }}}}
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "sphere"
diameter = 1.0
density = 1.9098593171027443
count = {COUNT}
[particles]
init = "lattice"
initial_temperature = 1.0
seed = 4
{{law}}
[run]
duration = {{duration}}
{{steps}}
[output]
interval = 1.0
average_start = 5.0
profile_interval = 0.02
zone_thickness = {BOX}
{{stresses}}
"""


def carnahan_starling(eta):
    return (1.0 + eta + eta * eta - eta**3) / (1.0 - eta) ** 3


def compressibility(out):
    """Z = trace(total) / trace(kinetic) of the one strip, and its standard error (the diagonal
    components' errors added, as if fully correlated: the pressure's fluctuations are isotropic)."""
    strip = read_csv(os.path.join(out, "stresses.csv"))[0]
    total = sum(float(strip[f"total_{a}{a}"]) for a in "xyz")
    kinetic = sum(float(strip[f"kinetic_{a}{a}"]) for a in "xyz")
    error = sum(float(strip[f"total_{a}{a}_error"]) for a in "xyz")
    return total / kinetic, error / kinetic, kinetic / 3.0 / (COUNT / BOX**3)


def run_gas(exe, tmp, name, text):
    case = os.path.join(tmp, f"{name}.toml")
    write_text(case, text)
    out = os.path.join(tmp, name)
    status, _, err = run(exe, "run", case, "-o", out, "--quiet")
    if not check(status == 0, f"{name}: exited {status}: {err.strip()}"):
        return None
    return compressibility(out)


def main():
    exe = executable_from_argv("usage: test_soft_hard_spheres.py PATH_TO_grainflow")
    if exe is None:
        return 2
    cs = carnahan_starling(ETA)
    with tempfile.TemporaryDirectory() as tmp:
        hard = run_gas(exe, tmp, "hard", GAS.format(engine="edmd", law="[collision]\nrestitution = 1.0", duration=200.0,
                                                    steps="", stresses=""))
        if hard is None:
            return finish("test_soft_hard_spheres")
        z_hard, e_hard, _ = hard
        check(abs(z_hard - cs) < 4.0 * e_hard, f"hard spheres: Z {z_hard:.4f} +- {e_hard:.4f}, Carnahan-Starling {cs:.4f}")
        shortfalls = []
        for kn in (1.0e3, 1.0e4, 1.0e5):
            law = f"[contact]\nmodel = \"linear_dashpot\"\nkn = {kn}\ngamma_n = 0.0\nfriction = 0.0"
            soft = run_gas(exe, tmp, f"soft_{kn:g}", GAS.format(engine="dem", law=law, duration=60.0,
                                                                 steps="collision_steps = 40", stresses="stresses = true"))
            if soft is None:
                return finish("test_soft_hard_spheres")
            z, e, temperature = soft
            d_bh = 1.0 - math.sqrt(math.pi * temperature / (2.0 * kn))
            z_bh = carnahan_starling(ETA * d_bh**3)
            check(abs(z - z_bh) < 4.0 * e + 0.02 * (z_bh - 1.0),
                  f"kn = {kn:g}: Z {z:.4f} +- {e:.4f} (T = {temperature:.3f}), Barker-Henderson {z_bh:.4f}")
            shortfalls.append((kn, z_hard - z, math.hypot(e, e_hard)))
        for (kn_a, a, _), (kn_b, b, _) in zip(shortfalls, shortfalls[1:]):
            check(b < a, f"the shortfall from the hard-sphere Z grows from kn = {kn_a:g} ({a:.4f}) to {kn_b:g} ({b:.4f})")
        kn, gap, error = shortfalls[-1]
        check(abs(gap) < 4.0 * error + 0.02 * (z_hard - 1.0),
              f"kn = {kn:g}: Z differs from the hard spheres' by {gap:.4f} (combined error {error:.4f})")
    return finish("test_soft_hard_spheres")


if __name__ == "__main__":
    sys.exit(main())
