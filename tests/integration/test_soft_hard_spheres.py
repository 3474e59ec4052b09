#!/usr/bin/python3
"""Soft spheres against hard ones: the same elastic gas (382 smooth spheres of unit mass and
diameter at solids fraction 0.2, periodic cube, T = 1, started on a cubic lattice) run by the
event-driven engine and by the DEM engine with linear springs kn = 1e3, 1e4 and 1e5 (no damping,
no friction), both measuring the pressure tensor the same way (stresses.csv: one strip holding the
box, so Z = trace(total) / trace(kinetic), the temperature drops out). Then the same in 2D: 400
discs of unit mass and diameter at area fraction 0.3 in a periodic square.

- Hard spheres: Z agrees with Carnahan-Starling, (1 + eta + eta^2 - eta^3) / (1 - eta)^3 = 2.406,
  within 4 block-averaged standard errors. Hard discs: with Henderson's equation of state
  (1 + eta^2 / 8) / (1 - eta)^2 = 2.064 (Henderson 1975; within 0.1% of the simulated hard-disc
  pressure at this density), within 4 standard errors plus that 0.1%.
- Soft spheres: a harmonic repulsion U = kn delta^2 / 2 acts as a hard sphere of the Barker-Henderson
  diameter d_BH = d - sqrt(pi T / (2 kn)) (the integral of 1 - exp(-U/T) over the overlap), so Z is
  Carnahan-Starling's at eta (d_BH / d)^3: 2.16, 2.32 and 2.38 for the three stiffnesses (the same
  diameter in 2D, where Henderson's Z at eta (d_BH / d)^2 is 1.93, 2.02 and 2.05). Each run
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
from gftest import (check, executable_from_argv, finish, periodic_gas_case, read_csv,  # noqa: E402
                    run_case_text)

class Gas:
    """The spheres' gas (dimension 3) or the discs' (2): count, box side, solids fraction, the
    density per volume (area) of unit mass, the hard-particle equation of state."""

    def __init__(self, dimension):
        self.dimension = dimension
        if dimension == 3:
            self.count, self.box, self.density = 382, 10.0, 6.0 / math.pi
            self.eta = self.count * math.pi / 6.0 / self.box**3
        else:
            self.count, self.density = 400, 4.0 / math.pi
            self.box = math.sqrt(self.count * math.pi / 4.0 / 0.3)
            self.eta = 0.3
        self.name = "spheres" if dimension == 3 else "discs"
        self.depth = self.box if dimension == 3 else 1.0  # z: the discs' plane

    def z(self, eta):
        if self.dimension == 3:
            return (1.0 + eta + eta * eta - eta**3) / (1.0 - eta) ** 3
        return (1.0 + eta * eta / 8.0) / (1.0 - eta) ** 2

    def text(self, engine, law, duration, steps=""):
        return periodic_gas_case(engine, self.dimension, self.count, self.box, self.depth, self.density, law,
                                 duration, start=5.0, interval=1.0, profile_interval=0.02,
                                 zone_thickness=self.box, steps=steps)


def compressibility(out, gas):
    """Z = trace(total) / trace(kinetic) of the one strip, and its standard error (the diagonal
    components' errors added, as if fully correlated: the pressure's fluctuations are isotropic).
    In 2D the trace has x and y only (z is 0)."""
    strip = read_csv(os.path.join(out, "stresses.csv"))[0]
    axes = "xyz"[:gas.dimension]
    total = sum(float(strip[f"total_{a}{a}"]) for a in axes)
    kinetic = sum(float(strip[f"kinetic_{a}{a}"]) for a in axes)
    error = sum(float(strip[f"total_{a}{a}_error"]) for a in axes)
    return total / kinetic, error / kinetic, kinetic / gas.dimension / (gas.count / gas.box**gas.dimension)


def run_gas(exe, tmp, name, text, gas):
    out = run_case_text(exe, tmp, name, text)
    return None if out is None else compressibility(out, gas)


def compare(exe, tmp, gas):
    """The hard gas against its equation of state, the soft ones against Barker-Henderson's, and
    the soft converging onto the hard as kn grows."""
    theory = gas.z(gas.eta)
    hard = run_gas(exe, tmp, f"hard_{gas.name}", gas.text(engine="edmd", law="[collision]\nrestitution = 1.0",
                                                         duration=200.0), gas)
    if hard is None:
        return
    z_hard, e_hard, _ = hard
    slack = 0.001 * theory if gas.dimension == 2 else 0.0  # Henderson's own accuracy at eta = 0.3
    check(abs(z_hard - theory) < 4.0 * e_hard + slack,
          f"hard {gas.name}: Z {z_hard:.4f} +- {e_hard:.4f}, equation of state {theory:.4f}")
    shortfalls = []
    for kn in (1.0e3, 1.0e4, 1.0e5):
        law = f"[contact]\nmodel = \"linear_dashpot\"\nkn = {kn}\ngamma_n = 0.0\nfriction = 0.0"
        soft = run_gas(exe, tmp, f"soft_{gas.name}_{kn:g}", gas.text(engine="dem", law=law, duration=60.0,
                                                                    steps="collision_steps = 40"), gas)
        if soft is None:
            return
        z, e, temperature = soft
        d_bh = 1.0 - math.sqrt(math.pi * temperature / (2.0 * kn))
        z_bh = gas.z(gas.eta * d_bh**gas.dimension)
        check(abs(z - z_bh) < 4.0 * e + 0.02 * (z_bh - 1.0),
              f"{gas.name}, kn = {kn:g}: Z {z:.4f} +- {e:.4f} (T = {temperature:.3f}), Barker-Henderson {z_bh:.4f}")
        shortfalls.append((kn, z_hard - z, math.hypot(e, e_hard)))
    for (kn_a, a, _), (kn_b, b, _) in zip(shortfalls, shortfalls[1:]):
        check(b < a, f"{gas.name}: the shortfall from the hard Z grows from kn = {kn_a:g} ({a:.4f}) to {kn_b:g} ({b:.4f})")
    kn, gap, error = shortfalls[-1]
    check(abs(gap) < 4.0 * error + 0.02 * (z_hard - 1.0),
          f"{gas.name}, kn = {kn:g}: Z differs from the hard one's by {gap:.4f} (combined error {error:.4f})")


def main():
    exe = executable_from_argv("usage: test_soft_hard_spheres.py PATH_TO_grainflow")
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        for dimension in (3, 2):
            compare(exe, tmp, Gas(dimension))
    return finish("test_soft_hard_spheres")


if __name__ == "__main__":
    sys.exit(main())
