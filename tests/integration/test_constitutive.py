#!/usr/bin/python3
"""Campbell's constitutive functions from the command line (constitutive.csv, `grainflow
constitutive`, constitutive_chi.png; OUTPUTS.md, Campbell 1982 sections 3.1.1 and 3.3.1):

- An elastic gas of discs (Henderson) and one of spheres (Carnahan-Starling), periodic, at rest:
  every strip's chi = P_yy / (rho_p sum <u_i'^2>) matches the equation of state the engine tests
  use, chi = nu Z(nu) / D at the strip's measured nu, within 1% (the equations' own accuracy at
  these densities, 0.3-0.5%, with finite-size effects of O(1/N)) plus 3 of the strip's standard
  errors; no strip is against a wall, so all count for chi.
- `grainflow constitutive ROOT` gathers both runs' files into ROOT/constitutive_table.csv: one row
  per strip of each run, the run's folder first, then whether it was averaged once steady (an
  elastic gas is steady from the start); `grainflow plot ROOT` draws constitutive_chi.png
  from it (and no f figure: a gas at rest has no resolved shear rate).
- A folder without any constitutive.csv, a missing folder, and a file whose columns differ are
  refused with exit status 2, naming the folder or file, before anything is written.

Usage: /usr/bin/python3 tests/integration/test_constitutive.py PATH_TO_grainflow  (from the repo root)
"""
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, elastic_gas_case, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

def henderson_chi(nu):
    return nu * (1 + nu * nu / 8) / (1 - nu) ** 2 / 2


def carnahan_starling_chi(nu):
    return nu * (1 + nu + nu * nu - nu ** 3) / (1 - nu) ** 3 / 3


def gas_case(dim, side, phi, strips, duration):
    """`side`^dim unit-mass particles of diameter 1 at packing fraction phi, in `strips` strips."""
    _, length = elastic_gas_case(dim, side, phi, duration, "")
    output = f"interval = 2.0\naverage_start = 10.0\nprofile_interval = 0.5\nzone_thickness = {length / strips!r}"
    return elastic_gas_case(dim, side, phi, duration, output)[0]


def check_gas(exe, root, name, dim, side, phi, strips, duration, reference):
    case = write_text(os.path.join(root, f"{name}.toml"), gas_case(dim, side, phi, strips, duration))
    out = os.path.join(root, name)
    status, _, err = run(exe, "run", case, "-o", out, "--quiet")
    if not check(status == 0, f"{name}: exited {status}: {err.strip()}"):
        return 0
    rows = read_csv(os.path.join(out, "constitutive.csv"))
    check(len(rows) == strips, f"{name}: {len(rows)} strips in constitutive.csv, expected {strips}")
    for row in rows:
        nu, chi, error = float(row["solids_fraction"]), float(row["chi"]), float(row["chi_error"])
        expected = reference(nu)
        print(f"{name} strip {row['strip']}: nu = {nu:.4f}, chi = {chi:.4f} +- {error:.4f}, equation of state "
              f"{expected:.4f} ({100 * (chi / expected - 1):+.2f}%)")
        check(math.isfinite(error) and error < 0.02 * expected, f"{name}: chi error {error} too large to test")
        check(abs(chi - expected) < 0.01 * expected + 3 * error,
              f"{name} strip {row['strip']}: chi {chi} vs {expected} (1% + 3 x {error})")
        check(abs(float(row["chi_elastic"]) - expected) < 1e-9 * expected,
              f"{name}: chi_elastic {row['chi_elastic']} vs {expected}")
        check(row["usable_chi"] == "1", f"{name} strip {row['strip']}: usable_chi {row['usable_chi']} without walls")
        if dim == 3:
            check(row["solids_fraction_3d"] == row["solids_fraction"], f"{name}: spheres' nu_3D is their nu")
    return len(rows)


def check_table(exe, root, expected_rows):
    status, out, err = run(exe, "constitutive", root)
    if not check(status == 0, f"constitutive: exited {status}: {err.strip()}"):
        return
    table = os.path.join(root, "constitutive_table.csv")
    rows = read_csv(table)
    check(len(rows) == expected_rows, f"constitutive table: {len(rows)} rows, expected {expected_rows}")
    check({row["run"] for row in rows} == {"discs", "spheres"}, f"constitutive table: runs {({r['run'] for r in rows})}")
    # An elastic gas is steady from the start: its averages (from t = 10) count.
    check(all(row["steady"] == "1" for row in rows), "constitutive table: a gas run not marked steady")
    check("2 runs" in out, f"constitutive: output {out!r}")
    status, _, err = run(exe, "plot", root)
    check(status == 0, f"plot of the table: exited {status}: {err.strip()}")
    check(os.path.isfile(os.path.join(root, "constitutive_chi.png")), "plot: no constitutive_chi.png")
    check(not os.path.exists(os.path.join(root, "constitutive_f.png")), "plot: an f figure for a gas at rest")


def check_refusals(exe, tmp):
    empty = os.path.join(tmp, "empty")
    os.makedirs(empty)
    status, _, err = run(exe, "constitutive", empty)
    check(status == 2 and "empty" in err and "constitutive.csv" in err, f"empty folder: {status}, {err.strip()}")
    check(not os.path.exists(os.path.join(empty, "constitutive_table.csv")), "empty folder: a table was written")
    status, _, err = run(exe, "constitutive", os.path.join(tmp, "missing"))
    check(status == 2 and "missing" in err, f"missing folder: {status}, {err.strip()}")
    mixed = os.path.join(tmp, "mixed")
    for run_folder in ("a", "b"):
        os.makedirs(os.path.join(mixed, run_folder))
    write_text(os.path.join(mixed, "a", "constitutive.csv"), "strip,y,chi\n0,0.5,1\n")
    write_text(os.path.join(mixed, "b", "constitutive.csv"), "strip,y,chi,f_s\n0,0.5,1,2\n")
    status, _, err = run(exe, "constitutive", mixed)
    check(status == 2 and "b/constitutive.csv" in err and "columns differ" in err, f"mixed columns: {status}, {err.strip()}")
    check(not os.path.exists(os.path.join(mixed, "constitutive_table.csv")), "mixed columns: a table was written")


def main():
    exe = executable_from_argv(__doc__)
    with tempfile.TemporaryDirectory() as tmp:
        root = os.path.join(tmp, "gases")
        os.makedirs(root)
        # 576 discs at 0.45, 4 strips; 343 spheres at 0.3, 3 strips: ~1e6 / 4e5 collisions.
        rows = check_gas(exe, root, "discs", 2, 24, 0.45, 4, 250.0, henderson_chi)
        rows += check_gas(exe, root, "spheres", 3, 7, 0.3, 3, 200.0, carnahan_starling_chi)
        check_table(exe, root, rows)
        check_refusals(exe, tmp)
    return finish("test_constitutive")


if __name__ == "__main__":
    sys.exit(main())
