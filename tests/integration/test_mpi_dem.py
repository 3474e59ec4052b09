"""The soft-sphere engine on several MPI ranks: `mpirun -np N grainflow run CASE` with the
case files and outputs of a serial run.

- A short run of Lan's bed (pouring, then shaking) on 1, 2 and 4 ranks ends in the same state. The
  ranks evaluate every pair from the same numbers in the same orientation, and sum each particle's
  forces over the same cell-ordered pairs. Only a different order of summation could make them
  differ, by round-off (1e-16 relative), which 300 steps of a dense bed amplify to at most ~1e-12 of
  a diameter; a lost pair or contact history would move particles by >= 1e-7 d within a few steps
  (a tangential force of mu k1 delta on a 3 mm glass sphere). The bound, 1e-9 d, lies between.
- Its energy budget (every input part, the change, the dissipation) is one rank's to 1e-9 of the
  input, summed over the ranks.
- The summary shows particles did cross between ranks and ghosts were held, so the comparison
  covers the exchange.
- A longer run on 1 and 2 ranks gives statistically identical profiles: each zone's solids fraction
  and granular temperature agree within 4 combined standard errors (block averages; chaos makes the
  two runs independent samples after ~0.05 s).
- The same holds with walls at the ends of the cut axis (the end ranks own the wall contacts), with
  walls on all four sides on 4 ranks (a 2 x 2 grid of columns: particles cross the sub-domains'
  edges and corners, and ghosts go to diagonal neighbours), and with two OpenMP threads inside each
  of two ranks.
- Campbell's pressure-controlled Couette cell with soft discs (tools/campbell_soft_discs.py on
  cases/campbell1982/couette_rough.toml, kn = 1e3; 40 discs, the cell cut across its gap, so that
  discs cross between the ranks while the servo moves both walls) on 2 ranks steers the walls as on
  one: the walls' loads and the contacts begun are summed over the ranks before each servo step,
  so the gap, the walls' speed and the kinetic energy of every row over 300 R/U_T (300 servo
  updates) are one rank's to 1e-9 (measured: identical); without the sum each rank would steer by
  its own share of the load. A restart on another rank count is refused (the portable state does not
  carry the walls' servo state), naming the key.
- The rotating drum (cases/geometry/rotating_drum.toml, a [[geometry]] cylinder turning about its
  axis) on 2 ranks ends in one rank's state, with the same wall contacts and energy input: the wall
  contacts' histories travel with their particles between ranks. So does the drum with lifters
  (cases/geometry/mesh_drum.toml, a turning STL mesh), whose contacts' slots and last normals travel too.
- A fault all ranks see at an output time stops them together, with the outputs written.
- The sampled outputs, snapshots and checkpoints on several ranks: test_mpi_outputs.py.

Runs on this 2-core machine with `mpirun --oversubscribe`; as root Open MPI needs its two
OMPI_ALLOW_RUN_AS_ROOT variables.

Usage: /usr/bin/python3 tests/integration/test_mpi_dem.py PATH_TO_grainflow
"""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from campbell_soft_discs import soft_disc_case  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, mpi_environment, mpirun_found, read_csv  # noqa: E402

BED = "cases/demo/vibrated_bed.toml"
DIAMETER = 0.003  # m, the bed's spheres
SHORT = ["--set", "particles.expansion_time=0.02", "--set", "drive.start=0.05", "--set", "drive.ramp=0.05",
         "--set", "run.duration=0.03", "--set", "output.interval=0.005"]
LONG = ["--set", "particles.expansion_time=0.02", "--set", "drive.start=0.05", "--set", "drive.ramp=0.05",
        "--set", "run.duration=1.2", "--set", "output.average_start=0.3"]


def run_ranks(exe, ranks, out, args, threads=1, case=BED):
    command = [exe, "run", case, "-o", out, "--quiet", "--threads", str(threads), *args]
    if ranks > 1:
        command = ["mpirun", "--oversubscribe", "-np", str(ranks), *command]
    result = subprocess.run(command, capture_output=True, text=True, env=mpi_environment())
    return result.returncode, result.stderr


def states(path):
    return {int(r["id"]): r for r in read_csv(path)}


def largest_difference(a, b, keys):
    return max(math.dist([float(a[i][k]) for k in keys], [float(b[i][k]) for k in keys]) for i in a)


def servo_cell(exe, tmp):
    """The soft-disc servo Couette cell on 1 and 2 ranks: the same rows."""
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    with open(os.path.join(root, "cases", "campbell1982", "couette_rough.toml")) as f:
        case = os.path.join(tmp, "servo_cell.toml")
        with open(case, "w") as out:
            out.write(soft_disc_case(f.read(), 1.0e3))
    args = ["--set", "run.duration=300", "--set", "output.average_start=100", "--set", "output.interval=10",
            "--set", "output.checkpoint_interval=100"]
    rows, summaries = {}, {}
    for ranks in (1, 2):
        out = os.path.join(tmp, f"servo_{ranks}")
        status, err = run_ranks(exe, ranks, out, args, case=case)
        if not check(status == 0, f"servo cell, {ranks} ranks: exit {status}: {err[-2000:]}"):
            return
        rows[ranks] = read_csv(os.path.join(out, "timeseries.csv"))
        summaries[ranks] = json.load(open(os.path.join(out, "summary.json")))
    check(summaries[2].get("mpi_migrations", 0) > 0, f"servo cell: no disc crossed between the ranks ({summaries[2].get('mpi_grid')})")
    check(summaries[1]["servo_updates"] == summaries[2]["servo_updates"] and summaries[1]["servo_updates"] > 100,
          f"servo updates {summaries[1]['servo_updates']} on one rank, {summaries[2]['servo_updates']} on two")
    check(len(rows[1]) == len(rows[2]), f"servo cell: {len(rows[1])} and {len(rows[2])} rows")
    # A restart on another rank count would need the walls' servo state in the portable form: refused.
    status, err = run_ranks(exe, 2, os.path.join(tmp, "servo_restart"),
                            ["--restart", os.path.join(tmp, "servo_1", "checkpoint.h5")], case=case)
    check(status == 2 and "servo" in err and "restarts on as many MPI ranks" in err,
          f"servo cell restarted on 2 ranks from a 1-rank checkpoint: exit {status}, {err.strip()[-300:]}")
    for a, b in zip(rows[1], rows[2]):
        for key in ("gap", "wall_speed", "kinetic_energy"):
            check(abs(float(a[key]) - float(b[key])) <= 1e-9 * max(1.0, abs(float(a[key]))),
                  f"servo cell, t = {a['time']}: {key} {b[key]} on 2 ranks, {a[key]} on one")


def geometry_drum(exe, tmp, case="cases/geometry/rotating_drum.toml", drum="drum"):
    """A rotating drum (a [[geometry]] cylinder turning about its axis, or a mesh with lifters turning
    with it) on 1 and 2 ranks: the same state."""
    args = ["--set", "run.duration=0.3", "--set", "output.interval=0.05", "--set", "particles.expansion_time=0.05",
            "--set", "geometry.0.motion.angular_velocity=[0,0,0.3]"]
    out = {}
    for ranks in (1, 2):
        out[ranks] = os.path.join(tmp, f"{drum}_{ranks}")
        status, err = run_ranks(exe, ranks, out[ranks], args, case=case)
        if not check(status == 0, f"{drum}, {ranks} ranks: exit {status}: {err[-2000:]}"):
            return
    summary = json.load(open(os.path.join(out[2], "summary.json")))
    check(summary.get("mpi_migrations", 0) > 0, f"{drum}: no particle crossed between the ranks")
    serial, parallel = (states(os.path.join(out[r], "final_state.csv")) for r in (1, 2))
    # As the bed's: round-off amplified over 600 steps (measured 4e-12 d) against >= 1e-7 d for a
    # lost wall contact history (the drum's friction on the grains touching it).
    dx = largest_difference(serial, parallel, ("x", "y", "z"))
    check(dx <= 1e-9, f"{drum}, 2 ranks: positions differ by {dx:.3g} d from one rank's")
    rows = [read_csv(os.path.join(out[r], "timeseries.csv")) for r in (1, 2)]
    check(any(int(r["wall_contacts"]) > 0 for r in rows[0]), f"{drum}: no grain touched the drum")
    for a, b in zip(*rows):
        for key in ("wall_contacts", "wall_collisions", "contacts"):
            check(a[key] == b[key], f"{drum}, 2 ranks, t = {a['time']}: {key} {b[key]}, one rank {a[key]}")
        check(abs(float(a["energy_input"]) - float(b["energy_input"])) <= 1e-9 * max(1.0, abs(float(a["energy_input"]))),
              f"{drum}, 2 ranks, t = {a['time']}: energy input {b['energy_input']}, one rank {a['energy_input']}")


def main():
    exe = executable_from_argv("usage: test_mpi_dem.py PATH_TO_grainflow")
    if exe is None:
        return 2
    if not mpirun_found():
        return finish("test_mpi_dem")
    with tempfile.TemporaryDirectory() as tmp:
        # Short run: the same state on 1, 2 and 4 ranks.
        out = {}
        for ranks in (1, 2, 4):
            out[ranks] = os.path.join(tmp, f"short_{ranks}")
            status, err = run_ranks(exe, ranks, out[ranks], SHORT)
            check(status == 0, f"{ranks} ranks: exit {status}: {err[-2000:]}")
        serial = states(os.path.join(out[1], "final_state.csv"))
        rows_serial = read_csv(os.path.join(out[1], "timeseries.csv"))
        for ranks in (2, 4):
            summary = json.load(open(os.path.join(out[ranks], "summary.json")))
            check(summary.get("mpi_ranks") == ranks, f"{ranks} ranks: summary.json mpi_ranks {summary.get('mpi_ranks')}")
            check(summary.get("mpi_migrations", 0) > 0 and summary.get("mpi_ghosts", 0) > 0,
                  f"{ranks} ranks: nothing crossed between ranks ({summary.get('mpi_migrations')} migrations, "
                  f"{summary.get('mpi_ghosts')} ghosts): the comparison would not cover the exchange")
            parallel = states(os.path.join(out[ranks], "final_state.csv"))
            check(sorted(parallel) == sorted(serial), f"{ranks} ranks: final_state.csv has other particles")
            if sorted(parallel) != sorted(serial):
                continue
            dx = largest_difference(serial, parallel, ("x", "y", "z"))
            check(dx <= 1e-9 * DIAMETER, f"{ranks} ranks: positions differ by {dx / DIAMETER:.3g} d from one rank's")
            rows = read_csv(os.path.join(out[ranks], "timeseries.csv"))
            check(len(rows) == len(rows_serial), f"{ranks} ranks: {len(rows)} time-series rows, one rank {len(rows_serial)}")
            for a, b in zip(rows_serial, rows):
                for key in ("contacts", "wall_contacts", "collisions", "wall_collisions", "neighbor_rebuilds"):
                    check(a[key] == b[key], f"{ranks} ranks, t = {a['time']}: {key} {b[key]}, one rank {a[key]}")
            # The energy budget is summed over the ranks (each books its own particles' and contacts'
            # work): every part equals one rank's to the round-off the positions show (1e-9 of the
            # input), and the budget closes as tightly; a rank's share left out would miss ~1/N of it.
            serial_summary = json.load(open(os.path.join(out[1], "summary.json")))
            scale = abs(serial_summary["energy_input"])
            for key in ("energy_input", "energy_input_gravity", "energy_input_walls", "energy_input_growth",
                        "energy_change", "energy_dissipated"):
                check(abs(summary[key] - serial_summary[key]) <= 1e-9 * scale,
                      f"{ranks} ranks: {key} {summary[key]!r}, one rank {serial_summary[key]!r}")
            check(scale > 0 and abs(summary["energy_budget_residual"]) < 1e-3,
                  f"{ranks} ranks: energy budget residual {summary['energy_budget_residual']}")

        # Walls across the cut axis; walls on all four sides, where 4 ranks take a 2 x 2 grid of
        # columns (2 cut planes against 3 for slabs), so that particles cross edges and corners of
        # sub-domains; threads inside the ranks: the same state as one rank.
        walled = SHORT + ["--set", 'domain.boundary.x="wall"']
        boxed = SHORT + ["--set", 'domain.boundary.x="wall"', "--set", 'domain.boundary.z="wall"',  # a base 10 d
                         "--set", "domain.hi=[0.03,0.08,0.03]", "--set", "particles.region_hi=[0.03,0.05,0.03]"]  # square
        for ranks, threads, args, label in ((1, 1, walled, "walls_1"), (2, 1, walled, "walls_2"), (1, 1, boxed, "boxed_1"),
                                            (4, 1, boxed, "boxed_4"), (2, 2, SHORT, "threads")):
            out[label] = os.path.join(tmp, label)
            status, err = run_ranks(exe, ranks, out[label], args, threads=threads)
            check(status == 0, f"{label}: exit {status}: {err[-2000:]}")
        boxed_summary = json.load(open(os.path.join(out["boxed_4"], "summary.json")))
        check(boxed_summary.get("mpi_grid") == "2x1x2",
              f"4 ranks in a walled box: grid {boxed_summary.get('mpi_grid')}, expected 2x1x2 (columns)")
        check(boxed_summary.get("mpi_migrations", 0) > 0 and boxed_summary.get("mpi_ghosts", 0) > 0,
              f"4 ranks in a walled box: {boxed_summary.get('mpi_migrations')} migrations, "
              f"{boxed_summary.get('mpi_ghosts')} ghosts: the comparison would not cover the exchange")
        for reference, label in (("walls_1", "walls_2"), ("boxed_1", "boxed_4"), (1, "threads")):
            a = states(os.path.join(out[reference], "final_state.csv"))
            b = states(os.path.join(out[label], "final_state.csv"))
            if check(sorted(a) == sorted(b), f"{label}: other particles than one rank's"):
                dx = largest_difference(a, b, ("x", "y", "z"))
                check(dx <= 1e-9 * DIAMETER, f"{label}: positions differ by {dx / DIAMETER:.3g} d from one rank's")

        servo_cell(exe, tmp)
        geometry_drum(exe, tmp)
        geometry_drum(exe, tmp, "cases/geometry/mesh_drum.toml", "mesh_drum")

        # Long run: statistically identical profiles on 1 and 2 ranks.
        profiles = {}
        for ranks in (1, 2):
            path = os.path.join(tmp, f"long_{ranks}")
            status, err = run_ranks(exe, ranks, path, LONG)
            check(status == 0, f"long run, {ranks} ranks: exit {status}: {err[-2000:]}")
            profiles[ranks] = read_csv(os.path.join(path, "profiles.csv"))
        compared = 0
        for a, b in zip(profiles[1], profiles[2]):
            for value, error in (("solids_fraction", "solids_fraction_error"), ("temperature", "temperature_error")):
                ea, eb = float(a[error]), float(b[error])
                if not (math.isfinite(ea) and math.isfinite(eb)) or float(a["solids_fraction"]) < 0.05:
                    continue
                compared += 1
                gap = abs(float(a[value]) - float(b[value]))
                check(gap <= 4.0 * math.hypot(ea, eb),
                      f"zone {a['zone']}: {value} {a[value]} (1 rank) and {b[value]} (2 ranks) differ by "
                      f"{gap / math.hypot(ea, eb):.1f} combined standard errors")
        check(compared >= 10, f"only {compared} zone values had error bars to compare")

        # A fault every rank sees at an output time (here the overlap bound, the maximum over the
        # ranks) stops them all there, and rank 0 writes the outputs as a serial run does.
        halted = os.path.join(tmp, "halted")
        status, err = run_ranks(exe, 2, halted, ["--set", "particles.expansion_time=0.02", "--set", "drive.start=0.05",
                                                 "--set", "run.duration=0.3", "--set", "run.halt_overlap=0.0005"])
        check(status != 0, f"halted run on 2 ranks: exit {status}")
        summary_path = os.path.join(halted, "summary.json")
        if check(os.path.exists(summary_path), f"halted run on 2 ranks wrote no summary.json: {err[-1000:]}"):
            errors = json.load(open(summary_path))["errors"]
            check(any("halt_overlap" in e for e in errors), f"halted run on 2 ranks: errors {errors}")
            check(len(read_csv(os.path.join(halted, "final_state.csv"))) > 0, "halted run: final_state.csv empty")
    return finish("test_mpi_dem")


if __name__ == "__main__":
    sys.exit(main())
