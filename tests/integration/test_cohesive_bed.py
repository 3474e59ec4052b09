#!/usr/bin/python3
"""Cohesion loosens a poured bed (cases/soft_sphere/cohesive_bed.toml): 400 JKR spheres rain onto a
floor at surface energies Gamma = 0, 2 and 20 (granular Bond numbers F_c / mg = 0, 9 and 90).

- Without adhesion the bed settles at a frictional random packing (mu = 0.5): bulk solids fraction
  in [0.55, 0.64], between random loose and random close packing.
- Each tenfold rise of the Bond number makes it looser by more than 0.02 (measured 0.045 and 0.075;
  bulk_solids_fraction is resolved to ~0.01 by the bed height's d/10 slices), and at Bo = 90 it is
  below 0.5, as fine cohesive powders pack.
- Every bed ends at rest: kinetic energy below 1e-6 of the bed's potential energy scale N m g d (a
  time step too long for the bonded pairs' oscillations pumps energy into the adhesive contacts
  and keeps the bed shivering, at up to the scale itself with Gamma = 200 and 0.2 Rayleigh times).

Usage: /usr/bin/python3 tests/integration/test_cohesive_bed.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, run  # noqa: E402

CASE = "cases/soft_sphere/cohesive_bed.toml"
SCALE = 400 * math.pi / 6.0  # N m g d in reduced units


def main():
    exe = executable_from_argv("usage: test_cohesive_bed.py PATH_TO_grainflow")
    if exe is None:
        return 2
    fractions = []
    with tempfile.TemporaryDirectory() as tmp:
        for gamma in (0.0, 2.0, 20.0):
            out = os.path.join(tmp, f"gamma_{gamma:g}")
            status, _, err = run(exe, "run", CASE, "-o", out, "--quiet", "--set", f"contact.surface_energy={gamma}")
            if not check(status == 0, f"Gamma = {gamma:g}: exited {status}: {err.strip()}"):
                return finish("test_cohesive_bed")
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
            fractions.append(summary["bulk_solids_fraction"])
            check(summary["kinetic_energy"] < 1e-6 * SCALE,
                  f"Gamma = {gamma:g}: kinetic energy {summary['kinetic_energy']:.3g} at the end, not at rest")
    dry, weak, strong = fractions
    check(0.55 <= dry <= 0.64, f"dry bed: solids fraction {dry:.3f}, not a frictional random packing")
    check(dry - weak > 0.02, f"Bo = 9 packs at {weak:.3f}, not looser than the dry bed's {dry:.3f}")
    check(weak - strong > 0.02, f"Bo = 90 packs at {strong:.3f}, not looser than Bo = 9's {weak:.3f}")
    check(strong < 0.5, f"Bo = 90 packs at {strong:.3f}, not below 0.5")
    return finish("test_cohesive_bed")


if __name__ == "__main__":
    sys.exit(main())
