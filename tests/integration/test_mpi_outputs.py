"""Every output of a soft-sphere run on several MPI ranks: the same files as one rank's,
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
- coarse_grained.vti: the same density, momentum and contact stress in every cell (each contact
  between particles of two ranks is listed on one of them: a doubled or lost contact would move
  the stress by a contact's share, ~1e-3 of the field's largest value).
- snapshots: the last one, read with VTK's parallel reader from its .pvtu pieces, holds every
  particle once (no ghost copies) at one rank's positions; `grainflow plot`'s reader joins the
  pieces too.
Checkpoints on 2 ranks: a run stopped at 0.015 s and continued to 0.03 s ends with the same
final_state.csv, timeseries.csv, tracers.csv and HDF5 datasets, byte for byte or bit for bit, as
the unsplit run (each rank restores its own particles, ghosts, contact histories and cuts). The
same checkpoint continues on 1 and on 4 ranks from its portable state, to round-off. SIGTERM sent to mpirun
stops both ranks at one step with a checkpoint, from which the run continues exactly.

Usage: /usr/bin/python3 tests/integration/test_mpi_outputs.py PATH_TO_grainflow
"""
import filecmp
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader

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

[coarse_grain]
start = 0.005
"""
FLOOR_SPEED = 0.1  # m/s, the scale of the bed's velocities (the drive's peak speed is of this order)


def read_vti_cells(path):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    cells = reader.GetOutput().GetCellData()
    return {cells.GetArrayName(k): vtk_to_numpy(cells.GetArray(k)) for k in range(cells.GetNumberOfArrays())}


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

    a, b = read_vti_cells(os.path.join(one, "coarse_grained.vti")), read_vti_cells(os.path.join(two, "coarse_grained.vti"))
    for name in ("density", "momentum_density", "contact_stress", "kinetic_stress"):
        scale = float(numpy.max(numpy.abs(a[name])))
        gap = float(numpy.max(numpy.abs(a[name] - b[name])))
        check(scale > 0.0 and gap <= 1e-9 * scale, f"coarse_grained.vti {name}: 1 and 2 ranks differ by {gap:.3g} (scale {scale:.3g})")

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


def unwrapped_gap(a, b, box=0.015):
    """Largest difference of two final_state.csv tables' positions, m, through the periodic x and z
    faces (positions are wrapped into the box at neighbour-list rebuilds, which a continued run
    does at other steps)."""
    gap = 0.0
    for i in a:
        for k in "xyz":
            d = float(a[i][k]) - float(b[i][k])
            if k in "xz":
                d -= box * round(d / box)
            gap = max(gap, abs(d))
    return gap


def portable_restarts(exe, case, tmp):
    """A checkpoint of 2 ranks, taken as the bed lands after pouring (t = 0.025 s, contacts loading
    and unloading, friction 0.5 so that tangential springs are stretched), continued on 1 and on 4
    ranks for 300 steps. Its portable state has every particle, contact history and accumulator;
    only the neighbour lists are built afresh, so forces add up in another order: the continued runs
    differ from the unsplit one by round-off, which 300 steps grow to ~1e-13 d (measured 7.6e-14 d
    after 1,000 steps of the frictionless bed). A contact history lost or a force not restored moves
    particles by >= 1e-7 d within a few steps (a tangential force mu k1 delta on a 3 mm glass sphere;
    measured: 3.4e-6 d without the forces), so the bound 1e-9 d lies between; counts of contacts
    begun must agree exactly. A checkpoint without the portable state (an older version's) is
    refused, exit 2."""
    rough = ["--set", "contact.friction=0.5", "--set", "walls.ylo.friction=0.5"]
    every = ["--set", "output.checkpoint_interval=0.025"]
    end = ["--set", f"run.duration={0.025 + 300 * 7.908014e-07 + 1e-12:.12f}"]
    kept = os.path.join(tmp, "kept")
    status, err = run_ranks(exe, 2, kept, case=case, args=SHORT + rough + every + ["--set", "run.duration=0.025"])
    check(status == 0, f"first part on 2 ranks: exit {status}: {err[-2000:]}")
    unsplit = os.path.join(tmp, "unsplit_300")
    status, err = run_ranks(exe, 2, unsplit, case=case, args=SHORT + rough + every + end)
    check(status == 0, f"unsplit run of 2 ranks: exit {status}: {err[-2000:]}")
    reference = read_csv(os.path.join(unsplit, "final_state.csv"))
    for ranks in (1, 4):
        folder = os.path.join(tmp, f"portable_{ranks}")
        shutil.copytree(kept, folder)
        status, err = run_ranks(exe, ranks, folder, case=case,
                                args=SHORT + rough + every + end + ["--restart", os.path.join(folder, "checkpoint.h5")])
        if not check(status == 0, f"2-rank checkpoint on {ranks} rank(s): exit {status}: {err[-2000:]}"):
            continue
        summary = json.load(open(os.path.join(folder, "summary.json")))
        check(any(f"continued on {ranks} MPI rank(s) from a checkpoint of 2" in w for w in summary["warnings"]),
              f"2-rank checkpoint on {ranks} rank(s): no warning that the bits differ: {summary['warnings']}")
        a = {r["id"]: r for r in reference}
        b = {r["id"]: r for r in read_csv(os.path.join(folder, "final_state.csv"))}
        check(sorted(a) == sorted(b), f"2-rank checkpoint on {ranks} rank(s): other particles")
        if sorted(a) == sorted(b):
            gap = unwrapped_gap(a, b)
            check(gap <= 1e-9 * DIAMETER, f"2-rank checkpoint on {ranks} rank(s): positions differ by {gap / DIAMETER:.3g} d")
        rows_a = read_csv(os.path.join(unsplit, "timeseries.csv"))
        rows_b = read_csv(os.path.join(folder, "timeseries.csv"))
        check(len(rows_a) == len(rows_b), f"2-rank checkpoint on {ranks} rank(s): {len(rows_b)} rows, unsplit {len(rows_a)}")
        for r, q in zip(rows_a, rows_b):
            for key in ("collisions", "wall_collisions", "contacts"):
                check(r[key] == q[key], f"2-rank checkpoint on {ranks} rank(s), t = {r['time']}: {key} {q[key]}, unsplit {r[key]}")
        t_a, t_b = read_csv(os.path.join(unsplit, "tracers.csv")), read_csv(os.path.join(folder, "tracers.csv"))
        check(len(t_a) == len(t_b) and [r["id"] for r in t_a] == [r["id"] for r in t_b],
              f"2-rank checkpoint on {ranks} rank(s): tracers.csv rows differ")
        v_a, v_b = read_csv(os.path.join(unsplit, "convection.csv")), read_csv(os.path.join(folder, "convection.csv"))
        check([r["visits"] for r in v_a] == [r["visits"] for r in v_b],
              f"2-rank checkpoint on {ranks} rank(s): convection.csv visits differ (a share counted twice or lost)")
        h_a, h_b = datasets(os.path.join(unsplit, "trajectory.h5")), datasets(os.path.join(folder, "trajectory.h5"))
        if check(h_a["position"].shape == h_b["position"].shape, f"2-rank checkpoint on {ranks} rank(s): trajectory shapes"):
            gap = float(numpy.max(numpy.abs(h_a["position"] - h_b["position"])))
            check(gap <= 1e-9 * DIAMETER, f"2-rank checkpoint on {ranks} rank(s): trajectory.h5 positions differ by {gap:.3g} m")
    # Without the portable state: refused on another rank count, before anything runs.
    older = os.path.join(tmp, "older")
    shutil.copytree(kept, older)
    with h5py.File(os.path.join(older, "checkpoint.h5"), "a") as f:
        del f["portable"]
    status, err = run_ranks(exe, 1, older, case=case, args=SHORT + ["--restart", os.path.join(older, "checkpoint.h5")])
    check(status == 2 and "without a portable state" in err and "continue on 2" in err,
          f"a 2-rank checkpoint without its portable state on 1 rank: exit {status}: {err[-500:]}")


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
            check("portable" in f, "checkpoint.h5 lacks the portable state")
        status, err = run_ranks(exe, 2, split, case=case, args=SHORT + every + ["--restart", checkpoint])
        check(status == 0, f"second half: exit {status}: {err[-2000:]}")
        same_files(whole, split, ["final_state.csv", "timeseries.csv", "profiles.csv", "tracers.csv",
                                  "convection.csv", "trajectory.h5", "zone_series.h5", "coarse_grained.vti"])

        # The 2-rank checkpoint continued on 1 and on 4 ranks from its portable state, against the
        # run that never stopped (2 ranks).
        portable_restarts(exe, case, tmp)

        # SIGTERM to mpirun (which passes it to the ranks): a checkpoint at the step the ranks agree
        # on, exit status 143 on each rank, and a hint naming mpirun; continued, it ends where the
        # unsplit run to the same time ends.
        stopped = os.path.join(tmp, "stopped")
        command = ["mpirun", "--oversubscribe", "-np", "2", exe, "run", case, "-o", stopped, "--quiet", *SHORT,
                   "--set", "run.duration=20"]
        process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=mpi_environment())
        # The signal goes once both ranks are stepping (each has written its piece of the second
        # snapshot), not after a guessed time: a rank still starting up would die of it.
        pieces = [os.path.join(stopped, "snapshots", f"particles_000001_rank{r}.vtu") for r in (0, 1)]
        deadline = time.monotonic() + 300.0
        while not all(os.path.exists(p) for p in pieces) and process.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        check(process.poll() is None, "SIGTERM on 2 ranks: the run ended before both ranks wrote a snapshot")
        process.send_signal(signal.SIGTERM)
        _, err = process.communicate()
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
