#!/usr/bin/python3
"""The bundled angle-of-repose case (cases/soft_sphere/angle_of_repose.toml) at three rolling
frictions: the heap's angle rises with mu_r (rolling resistance, epsd).

600 spheres (mu = 0.5) slump from a loose column into a half heap against a wall. The angle is the
slope of the heap's surface, the highest sphere top in each 1 d wide column of the box, fitted by
least squares where the surface lies between 20 % and 80 % of its highest point. Measured with
seeds 3, 5 and 8: 16.1-17.6 degrees at mu_r = 0, 20.5 at 0.1, 23.5-25.2 at 0.3, so the seed moves
an angle by about 1 degree. The test asks each step in mu_r to raise the angle by more than
1.5 degrees (measured ~4.5): without the torque all three would be the same heap within the
seed's degree. At mu_r = 0 the heap must stand below the sliding friction's angle,
atan(0.5) = 26.6 degrees, since spheres free to roll cannot lock into a steeper slope. Each heap
must be at rest (kinetic energy below 1e-6 of its weight times a diameter).

Usage: /usr/bin/python3 tests/integration/test_angle_of_repose.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, run  # noqa: E402

CASE = "cases/soft_sphere/angle_of_repose.toml"


def surface_angle(path):
    """Degrees: the least-squares slope of the highest sphere tops per unit-wide column."""
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    header = lines[0].strip().split(",")
    x_at, y_at, d_at = header.index("x"), header.index("y"), header.index("diameter")
    top = {}
    for line in lines[1:]:
        v = line.strip().split(",")
        column = int(float(v[x_at]) // 1.0)
        top[column] = max(top.get(column, 0.0), float(v[y_at]) + 0.5 * float(v[d_at]))
    highest = max(top.values())
    points = [(c + 0.5, h) for c, h in top.items() if 0.2 * highest < h < 0.8 * highest]
    mx = sum(p[0] for p in points) / len(points)
    mh = sum(p[1] for p in points) / len(points)
    slope = sum((p[0] - mx) * (p[1] - mh) for p in points) / sum((p[0] - mx) ** 2 for p in points)
    return math.degrees(math.atan(-slope))


def heap(exe, tmp, mu_r):
    out = os.path.join(tmp, f"mu_r_{mu_r}")
    args = ["--set", f"contact.rolling_friction={mu_r}"]
    if mu_r == 0:
        args += ["--set", 'contact.rolling_model="none"']
    status, _, err = run(exe, "run", CASE, "-o", out, "--quiet", *args)
    if not check(status == 0, f"mu_r = {mu_r}: exited {status}: {err.strip()}"):
        return None
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    weight = 600 * math.pi / 6.0  # N m g d in reduced units
    check(summary["kinetic_energy"] < 1e-6 * weight, f"mu_r = {mu_r}: still moving, kinetic energy {summary['kinetic_energy']}")
    angle = surface_angle(os.path.join(out, "final_state.csv"))
    print(f"mu_r = {mu_r}: heap angle {angle:.2f} degrees")
    return angle


def main():
    exe = executable_from_argv("usage: test_angle_of_repose.py PATH_TO_grainflow")
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        angles = [heap(exe, tmp, mu_r) for mu_r in (0, 0.1, 0.3)]
    if None not in angles:
        check(0.0 < angles[0] < math.degrees(math.atan(0.5)), f"mu_r = 0: heap at {angles[0]:.2f} degrees, above atan(mu)")
        check(angles[1] > angles[0] + 1.5, f"mu_r = 0.1 heap at {angles[1]:.2f} degrees, not above mu_r = 0's {angles[0]:.2f}")
        check(angles[2] > angles[1] + 1.5, f"mu_r = 0.3 heap at {angles[2]:.2f} degrees, not above mu_r = 0.1's {angles[1]:.2f}")
    return finish("test_angle_of_repose")


if __name__ == "__main__":
    sys.exit(main())
