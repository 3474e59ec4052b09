"""Every output of a soft-sphere run on several MPI ranks (issue 8): the same files as one rank's,
and checkpoints that continue a run of several ranks exactly.

Lan's bed (poured, then shaken; the short run of test_mpi_dem.py) with [trajectory], [zone_series],
[field], [tracers] and VTU snapshots, on 1 and 2 ranks:
- The ranks evaluate every pair as one rank does (test_mpi_dem.py: the states agree to 1e-9 d, in
  practice bit for bit), so what differs is only how sums over particles are associated: each rank
  sums its own particles and the ranks' sums are added. That changes a sum of n terms by round-off,
  ~n 1e-16 of its magnitude. The bounds below are 1e-9 of each quantity's scale (a diameter, the
  floor's peak speed), far above that round-off and far below what a lost or doubled particle
  would change (a whole particle's share, >= 1e-4 of a zone's mean).
- trajectory.h5: the windowed velocities and positions of every particle.
- zone_series.h5: each zone's instantaneous mean velocity.
- convection.csv: the same visits in every cell (counts: exactly), the same mean velocities.
- tracers.csv: the same rows in the same order (time, then id).
- snapshots: the last one, read with VTK's parallel reader from its .pvtu pieces, holds every
  particle once (no ghost copies) at one rank's positions; `grainflow plot`'s reader joins the
  pieces too.
Checkpoints on 2 ranks: a run stopped at 0.015 s and continued to 0.03 s ends with the same
final_state.csv, timeseries.csv, tracers.csv and HDF5 datasets, byte for byte or bit for bit, as
the unsplit run (each rank restores its own particles, ghosts, contact histories and cuts). A
checkpoint of 2 ranks is refused on 1 rank (exit 2), naming the rank counts. SIGTERM sent to mpirun
stops both ranks at one step with a checkpoint, from which the run continues exactly.

Usage: /usr/bin/python3 tests/integration/test_mpi_outputs.py PATH_TO_grainflow
"""
import filecmp
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from grainflow_plots import snapshots  # noqa: E402
from gftest import check, executable_from_argv, finish, mpi_environment, mpirun_found, read_csv, write_text  # noqa: E402
from test_mpi_dem import BED, DIAMETER, SHORT, run_ranks  # noqa: E402

SAMPLED = """
[trajectory]
start = 0.005
samples = 40

[zone_series]
start = 0.005
samples = 40
interval = 0.0005

[field]
axis = "z"
start = 0.005

[tracers]
particles = [0, 7, 100, 150, 238]
interval = 0.001
"""
FLOOR_SPEED = 0.1  # m/s, the scale of the bed's velocities (the drive's peak speed is of this order)


def datasets(path):
    with h5py.File(path, "r") as f:
        return {name: numpy.array(f[name]) for name in f if isinstance(f[name], h5py.Dataset)}


def read_points(path, parallel):
    reader = vtkXMLPUnstructuredGridReader() if parallel else vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    ids = vtk_to_numpy(grid.GetPointData().GetArray("id"))
    points = vtk_to_numpy(grid.GetPoints().GetData())
    order = numpy.argsort(ids)
    return ids[order], points[order]


def last_snapshot(out):
    names = sorted(f for f in os.listdir(os.path.join(out, "snapshots")) if f.endswith((".vtu", ".pvtu")) and "rank" not in f)
    return os.path.join(out, "snapshots", names[-1])


def compare_outputs(one, two):
    """The sampled outputs of the runs in folders `one` (1 rank) and `two` (2 ranks)."""
    a, b = datasets(os.path.join(one, "trajectory.h5")), datasets(os.path.join(two, "trajectory.h5"))
    for name, scale in (("position", DIAMETER), ("velocity", FLOOR_SPEED)):
        check(a[name].shape == b[name].shape and a[name].shape[0] == 40,
              f"trajectory.h5 /{name}: shapes {a[name].shape} (1 rank), {b[name].shape} (2 ranks)")
        if a[name].shape == b[name].shape:
            gap = float(numpy.max(numpy.abs(a[name] - b[name])))
            check(gap <= 1e-9 * scale, f"trajectory.h5 /{name}: 1 and 2 ranks differ by {gap:.3g}")
    check(numpy.array_equal(a["id"], b["id"]), "trajectory.h5 /id: other particles on 2 ranks")

    a, b = datasets(os.path.join(one, "zone_series.h5")), datasets(os.path.join(two, "zone_series.h5"))
    check(a["zone_velocity"].shape == b["zone_velocity"].shape, "zone_series.h5: other shapes on 2 ranks")
    if a["zone_velocity"].shape == b["zone_velocity"].shape:
        gap = float(numpy.max(numpy.abs(a["zone_velocity"] - b["zone_velocity"])))
        check(gap <= 1e-9 * FLOOR_SPEED, f"zone_series.h5 /zone_velocity: 1 and 2 ranks differ by {gap:.3g} m/s")
        check(float(numpy.max(numpy.abs(a["zone_velocity"]))) > 1e-3, "zone_series.h5: the bed never moved")

    a, b = read_csv(os.path.join(one, "convection.csv")), read_csv(os.path.join(two, "convection.csv"))
    check(len(a) == len(b) and sum(int(r["visits"]) for r in a) > 0, f"convection.csv: {len(a)} and {len(b)} cells")
    for r, s in zip(a, b):
        check(r["visits"] == s["visits"], f"convection.csv cell {r['column']},{r['row']}: visits {r['visits']} and {s['visits']}")
        for key in ("velocity_horizontal", "velocity_vertical"):
            gap = abs(float(r[key]) - float(s[key]))
            check(gap <= 1e-9 * FLOOR_SPEED, f"convection.csv cell {r['column']},{r['row']}: {key} differs by {gap:.3g}")

    a, b = read_csv(os.path.join(one, "tracers.csv")), read_csv(os.path.join(two, "tracers.csv"))
    check(len(a) == len(b) and len(a) >= 5 * 25, f"tracers.csv: {len(a)} rows (1 rank), {len(b)} (2 ranks)")
    for r, s in zip(a, b):
        check((r["time"], r["id"], r["coordination"], r["wall_contacts"]) == (s["time"], s["id"], s["coordination"], s["wall_contacts"]),
              f"tracers.csv: row {r} (1 rank) against {s} (2 ranks)")
        gap = max(abs(float(r[k]) - float(s[k])) for k in ("x", "y", "z"))
        check(gap <= 1e-9 * DIAMETER, f"tracers.csv t = {r['time']}, id {r['id']}: positions differ by {gap:.3g} m")

    ids_a, points_a = read_points(last_snapshot(one), parallel=False)
    path = last_snapshot(two)
    check(path.endswith(".pvtu"), f"2 ranks' snapshot is {path}, not a parallel index")
    ids_b, points_b = read_points(path, parallel=True)
    check(numpy.array_equal(ids_a, ids_b), f"last snapshot: {len(ids_b)} points on 2 ranks, {len(ids_a)} on 1 (ghosts or losses)")
    if numpy.array_equal(ids_a, ids_b):
        gap = float(numpy.max(numpy.abs(points_a - points_b)))
        check(gap <= 1e-9 * DIAMETER, f"last snapshot: positions differ by {gap:.3g} m")
    # `grainflow plot` reads the pieces too (snapshots_phases.png).
    joined = snapshots.read_vtu(path)
    check(joined["position"].shape == points_a.shape, f"the plot's reader joined {joined['position'].shape} points")


def same_files(first, second, names):
    for name in names:
        if name.endswith(".h5"):
            a, b = datasets(os.path.join(first, name)), datasets(os.path.join(second, name))
            equal = a.keys() == b.keys() and all(numpy.array_equal(a[k], b[k]) for k in a)
        else:
            equal = filecmp.cmp(os.path.join(first, name), os.path.join(second, name), shallow=False)
        check(equal, f"split run on 2 ranks: {name} differs from the unsplit run's")


def main():
    exe = executable_from_argv("usage: test_mpi_outputs.py PATH_TO_grainflow")
    if exe is None:
        return 2
    if not mpirun_found():
        return finish("test_mpi_outputs")
    with tempfile.TemporaryDirectory() as tmp:
        case = os.path.join(tmp, "bed.toml")
        with open(BED) as f:
            write_text(case, f.read() + SAMPLED)
        snapshots = ["--set", "output.snapshot_interval=0.01"]
        out = {}
        for ranks in (1, 2):
            out[ranks] = os.path.join(tmp, f"sampled_{ranks}")
            status, err = run_ranks(exe, ranks, out[ranks], SHORT + snapshots, case=case)
            check(status == 0, f"{ranks} rank(s): exit {status}: {err[-2000:]}")
        if status == 0:
            compare_outputs(out[1], out[2])

        # Checkpoints on 2 ranks: unsplit, and stopped at half time then continued.
        every = ["--set", "output.checkpoint_interval=0.015"]
        whole, split = os.path.join(tmp, "whole"), os.path.join(tmp, "split")
        status, err = run_ranks(exe, 2, whole, case=case, args=SHORT + every)
        check(status == 0, f"unsplit run with checkpoints: exit {status}: {err[-2000:]}")
        status, err = run_ranks(exe, 2, split, case=case, args=SHORT + every + ["--set", "run.duration=0.015"])
        check(status == 0, f"first half: exit {status}: {err[-2000:]}")
        checkpoint = os.path.join(split, "checkpoint.h5")
        if not check(os.path.exists(checkpoint), "the first half on 2 ranks wrote no checkpoint.h5"):
            return finish("test_mpi_outputs")
        with h5py.File(checkpoint, "r") as f:
            check(int(f.attrs["mpi_ranks"]) == 2 and "state_rank_1" in f, "checkpoint.h5 lacks rank 1's state")
            check(len(f["particles/id"]) == len(read_csv(os.path.join(whole, "final_state.csv"))),
                  "checkpoint.h5 /particles: not every particle")
        refused = os.path.join(tmp, "refused")
        status, err = run_ranks(exe, 1, refused, case=case, args=SHORT + ["--restart", checkpoint])
        check(status == 2 and "written by 2 MPI rank(s), this run has 1" in err,
              f"a 2-rank checkpoint on 1 rank: exit {status}: {err[-500:]}")
        status, err = run_ranks(exe, 2, split, case=case, args=SHORT + every + ["--restart", checkpoint])
        check(status == 0, f"second half: exit {status}: {err[-2000:]}")
        same_files(whole, split, ["final_state.csv", "timeseries.csv", "profiles.csv", "tracers.csv",
                                  "convection.csv", "trajectory.h5", "zone_series.h5"])

        # SIGTERM to mpirun (which passes it to the ranks): a checkpoint at the step the ranks agree
        # on, exit status 143 on each rank, and a hint naming mpirun; continued, it ends where the
        # unsplit run to the same time ends.
        stopped = os.path.join(tmp, "stopped")
        command = ["mpirun", "--oversubscribe", "-np", "2", exe, "run", case, "-o", stopped, "--quiet", *SHORT,
                   "--set", "run.duration=20"]
        process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=mpi_environment())
        time.sleep(3.0)
        process.send_signal(signal.SIGTERM)
        _, err = process.communicate(timeout=120)
        summary_path = os.path.join(stopped, "summary.json")
        if check(os.path.exists(summary_path), f"SIGTERM on 2 ranks: no summary.json: {err[-1000:]}"):
            summary = json.load(open(summary_path))
            message = " ".join(summary["errors"])
            check("interrupted by SIGTERM" in message and "continue with: mpirun -np 2 grainflow run" in message,
                  f"SIGTERM on 2 ranks: errors {summary['errors']}")
            check(summary["simulated_time"] < 20, "SIGTERM on 2 ranks: the run was not stopped")
            end = f"{summary['simulated_time'] + 0.005:.6f}"
            status, err = run_ranks(exe, 2, stopped, case=case, args=SHORT + ["--restart", os.path.join(stopped, "checkpoint.h5"),
                                                                   "--set", f"run.duration={end}"])
            check(status == 0, f"continued after SIGTERM: exit {status}: {err[-2000:]}")
            unsplit = os.path.join(tmp, "unsplit")
            status, err = run_ranks(exe, 2, unsplit, case=case, args=SHORT + ["--set", f"run.duration={end}"])
            check(status == 0, f"unsplit run to {end} s: exit {status}: {err[-2000:]}")
            same_files(unsplit, stopped, ["final_state.csv", "tracers.csv", "trajectory.h5"])
    return finish("test_mpi_outputs")


if __name__ == "__main__":
    sys.exit(main())
