"""Checkpoints and restarts: a run split in two by a checkpoint ends bitwise identical to
the unsplit run, for a DEM vibrated bed, a DEM drum whose wall is a turning STL mesh and an
event-driven chute; SIGINT and SIGTERM write a
checkpoint and every output and exit with 130 / 143; a run killed with SIGKILL at any moment
leaves readable outputs and a checkpoint it continues from exactly, HDF5 streams included (the
checkpoint's copies of trajectory.h5 and zone_series.h5 carry them across); bad checkpoints are refused
before anything runs (exit 2).

Bitwise means byte-identical output files: the CSV files print doubles with enough digits that
any difference in the state shows (final_state.csv prints 17), so equality here is the strongest
check there is, and no tolerance is needed.

Usage: /usr/bin/python3 tests/integration/test_checkpoint_restart.py PATH_TO_grainflow
"""
import filecmp
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ElementTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run  # noqa: E402

import h5py  # noqa: E402  (Debian's python3-h5py)
import numpy  # noqa: E402

# Lan's bed, small and short: pouring by radius expansion, then the floor shaking with friction on,
# with both HDF5 streams (trajectory.h5, zone_series.h5) and VTU snapshots.
BED = "cases/demo/vibrated_bed.toml"
BED_SETS = ["--set", "particles.expansion_time=0.02", "--set", "drive.start=0.05", "--set", "drive.ramp=0.05",
            "--set", "output.snapshot_interval=0.05", "--set", "trajectory.start=0.06", "--set", "trajectory.samples=200",
            "--set", "zone_series.start=0.06", "--set", "zone_series.samples=100"]
# Campbell's chute with its collision stresses, and a trajectory.h5 of instantaneous states.
CHUTE = "cases/campbell1982/chute_30deg.toml"
MESH_DRUM = "cases/geometry/mesh_drum.toml"
MESH_DRUM_SETS = ["--set", "output.snapshot_interval=1.0", "--set", "output.interval=0.5", "--set", "trajectory.start=1.0",
                  "--set", "trajectory.samples=20"]
CHUTE_SETS = ["--set", "output.average_start=100", "--set", "trajectory.samples=60", "--set", "trajectory.interval=2"]


def h5_equal(a, b):
    """The same datasets with exactly equal values and the same attributes (the files' bytes hold
    HDF5's own bookkeeping, which depends on how the datasets grew)."""
    with h5py.File(a, "r") as x, h5py.File(b, "r") as y:
        if set(x.keys()) != set(y.keys()) or dict(x.attrs).keys() != dict(y.attrs).keys():
            return False
        same_attrs = all(str(x.attrs[k]) == str(y.attrs[k]) for k in x.attrs if k != "case")
        return same_attrs and all(numpy.array_equal(x[k][()], y[k][()]) for k in x.keys())


def outputs_equal(a, b, label):
    """Every result file the unsplit run `a` wrote exists in `b` with the same bytes (HDF5 files:
    the same datasets and attributes). Left out: the records of how each process ran (summary.json
    and run_log.json hold wall-clock figures, resolved_case.toml each process's own duration and
    checkpoint settings) and the checkpoint files."""
    names = []
    for root, _, files in os.walk(a):
        for name in files:
            rel = os.path.relpath(os.path.join(root, name), a)
            if rel not in ("summary.json", "run_log.json", "resolved_case.toml") and not rel.startswith("checkpoint"):
                names.append(rel)
    check(len(names) >= 3, f"{label}: the unsplit run wrote only {names}")
    check(any(n.endswith(".h5") for n in names), f"{label}: no HDF5 stream to compare in {names}")
    for rel in sorted(names):
        other = os.path.join(b, rel)
        if not check(os.path.exists(other), f"{label}: {rel} missing after the restart"):
            continue
        same = h5_equal if rel.endswith(".h5") else lambda p, q: filecmp.cmp(p, q, shallow=False)
        check(same(os.path.join(a, rel), other), f"{label}: {rel} differs from the unsplit run's")


def split_run(exe, tmp, case, sets, full, half, label):
    whole, split = os.path.join(tmp, label + "_whole"), os.path.join(tmp, label + "_split")
    status, _, err = run(exe, "run", case, "-o", whole, "--quiet", "--set", f"run.duration={full}", *sets)
    check(status == 0, f"{label}: unsplit run failed: {err}")
    status, _, err = run(exe, "run", case, "-o", split, "--quiet", "--set", f"run.duration={half}",
                         "--set", f"output.checkpoint_interval={half}", *sets)
    check(status == 0 and os.path.exists(os.path.join(split, "checkpoint.h5")), f"{label}: first half: {err}")
    # Only the case and the file: the checkpoint brings its own --set assignments; the new duration wins.
    status, _, err = run(exe, "run", case, "--quiet", "--restart", os.path.join(split, "checkpoint.h5"),
                         "--set", f"run.duration={full}")
    check(status == 0, f"{label}: restart failed: {err}")
    summary = json.load(open(os.path.join(split, "summary.json")))
    check(summary.get("restarted_from", "").endswith("checkpoint.h5"), f"{label}: summary.json lacks restarted_from")
    outputs_equal(whole, split, label)
    return whole


def checkpoint_time(path):
    with h5py.File(path, "r") as f:
        check(f["particles/position"].shape[1] == 3, f"{path}: particles/position is not N x 3")
        check(f.attrs["format"] in ("grainflow checkpoint 1", b"grainflow checkpoint 1"), f"{path}: format attribute")
        return float(f.attrs["time"])


def checkpoint_reached(path, reached):
    """Whether the checkpoint at `path` exists and holds a time >= `reached` (it is replaced by a
    rename, so a reader sees a whole file or none)."""
    try:
        with h5py.File(path, "r") as f:
            return float(f.attrs["time"]) >= reached
    except (OSError, KeyError):
        return False


def wait_until(proc, condition):
    """Polls `condition` while `proc` runs; True once it holds, False if the process ended first."""
    while proc.poll() is None:
        if condition():
            return True
        time.sleep(0.02)
    return condition()


def interrupted(exe, tmp, case, sets, sig, expected_status, label, wait_for):
    """Starts a long run, sends `sig` once `wait_for` exists in its folder, and checks the exit."""
    out = os.path.join(tmp, label)
    proc = subprocess.Popen([exe, "run", case, "-o", out, "--quiet", *sets], stderr=subprocess.PIPE, text=True)
    # The handlers are installed before the output folder is made; an event-driven run writes nothing
    # else before its end. No deadline: ctest's TIMEOUT bounds a run that never gets there.
    wait_until(proc, lambda: os.path.exists(os.path.join(out, wait_for or "")))
    proc.send_signal(sig)
    _, err = proc.communicate()
    check(proc.returncode == expected_status, f"{label}: exit status {proc.returncode}, expected {expected_status}: {err}")
    check(os.path.exists(os.path.join(out, "checkpoint.h5")), f"{label}: no checkpoint after the signal")
    summary = json.load(open(os.path.join(out, "summary.json")))
    check(any("interrupted by" in e for e in summary["errors"]), f"{label}: summary.json errors: {summary['errors']}")
    check(len(read_csv(os.path.join(out, "timeseries.csv"))) > 0, f"{label}: timeseries.csv empty")
    check(len(read_csv(os.path.join(out, "final_state.csv"))) > 0, f"{label}: final_state.csv empty")
    return out


def continue_and_compare(exe, tmp, case, sets, out, end, label):
    status, _, err = run(exe, "run", case, "--quiet", "--restart", os.path.join(out, "checkpoint.h5"),
                         "--set", f"run.duration={end}")
    check(status == 0, f"{label}: restart failed: {err}")
    reference = os.path.join(tmp, label + "_reference")
    status, _, err = run(exe, "run", case, "-o", reference, "--quiet", *sets, "--set", f"run.duration={end}")
    check(status == 0, f"{label}: reference run failed: {err}")
    outputs_equal(reference, out, label)


def readable_after_kill(out, label):
    """Every file a killed run left under its real name parses; temporaries may lie beside them."""
    for root, _, files in os.walk(out):
        for name in files:
            path = os.path.join(root, name)
            if ".tmp" in name:
                continue
            if name.endswith(".csv"):
                check(len(read_csv(path)) > 0, f"{label}: {path} unreadable")
            elif name.endswith((".vtu", ".pvd")):
                try:
                    ElementTree.parse(path)
                except ElementTree.ParseError as e:
                    check(False, f"{label}: {path} is not whole XML: {e}")
            elif name.endswith(".json"):
                json.load(open(path))


def main():
    exe = executable_from_argv("usage: test_checkpoint_restart.py PATH_TO_grainflow")
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        # Split against unsplit, both engines.
        split_run(exe, tmp, BED, BED_SETS, 0.2, 0.1, "dem_bed")
        split_run(exe, tmp, CHUTE, CHUTE_SETS, 300, 150, "edmd_chute")
        # A turning STL mesh (the drum with lifters): its contacts' slots, their last normals and
        # each particle's listed triangles are in the checkpoint.
        split_run(exe, tmp, MESH_DRUM, MESH_DRUM_SETS, 4.0, 2.0, "dem_mesh_drum")

        # SIGINT on a DEM run, SIGTERM on an event-driven one: checkpoint, outputs, 130 / 143; the
        # continued run then matches one that never stopped, up to a common end on the output grid.
        long_bed = BED_SETS + ["--set", "run.duration=5", "--set", "output.checkpoint_interval=0"]
        out = interrupted(exe, tmp, BED, long_bed, signal.SIGINT, 130, "dem_sigint", "snapshots/particles_000001.vtu")
        end = round(checkpoint_time(os.path.join(out, "checkpoint.h5")) + 0.05, 2)
        continue_and_compare(exe, tmp, BED, BED_SETS, out, end, "dem_sigint")

        long_chute = CHUTE_SETS + ["--set", "run.duration=1000000"]
        out = interrupted(exe, tmp, CHUTE, long_chute, signal.SIGTERM, 143, "edmd_sigterm", None)
        end = float(int(checkpoint_time(os.path.join(out, "checkpoint.h5"))) + 20)
        continue_and_compare(exe, tmp, CHUTE, CHUTE_SETS, out, end, "edmd_sigterm")

        # SIGKILL at three moments of a run that checkpoints and snapshots often (once its checkpoint
        # has reached 0.02, 0.05 and 0.1 s, whatever the machine's speed): what is left reads, and the
        # last checkpoint continues to the same end as the unsplit run.
        kill_sets = BED_SETS + ["--set", "output.checkpoint_interval=0.01", "--set", "run.duration=5"]
        for k, reached in enumerate((0.02, 0.05, 0.1)):
            label = f"dem_sigkill_{k}"
            out = os.path.join(tmp, label)
            checkpoint = os.path.join(out, "checkpoint.h5")
            proc = subprocess.Popen([exe, "run", BED, "-o", out, "--quiet", *kill_sets], stderr=subprocess.DEVNULL)
            running = wait_until(proc, lambda: checkpoint_reached(checkpoint, reached))
            proc.kill()
            proc.wait()
            check(running, f"{label}: the run ended before its checkpoint reached {reached} s")
            readable_after_kill(out, label)
            if not check(os.path.exists(checkpoint), f"{label}: no checkpoint after it reached {reached} s"):
                continue
            end = round(checkpoint_time(checkpoint) + 0.03, 2)
            continue_and_compare(exe, tmp, BED, BED_SETS, out, end, label)

        # Refusals, before anything runs.
        chute_checkpoint = os.path.join(tmp, "edmd_chute_split", "checkpoint.h5")
        status, _, err = run(exe, "run", BED, "-o", os.path.join(tmp, "wrong"), "--restart", chute_checkpoint)
        check(status == 2 and "cannot continue" in err, f"a DEM case on an edmd checkpoint: {status} {err}")
        check(not os.path.exists(os.path.join(tmp, "wrong")), "a refused restart wrote its output folder")
        garbage = os.path.join(tmp, "garbage.h5")
        with open(garbage, "wb") as f:
            f.write(b"not hdf5 at all" * 10)
        status, _, err = run(exe, "run", BED, "-o", os.path.join(tmp, "g"), "--restart", garbage)
        check(status == 2 and "garbage.h5" in err, f"a garbage checkpoint: {status} {err}")
        truncated = os.path.join(tmp, "truncated.h5")
        with open(chute_checkpoint, "rb") as f:
            data = f.read()
        with open(truncated, "wb") as f:
            f.write(data[: len(data) // 2])
        status, _, err = run(exe, "run", CHUTE, "-o", os.path.join(tmp, "t"), "--restart", truncated)
        check(status == 2 and "truncated.h5" in err, f"a truncated checkpoint: {status} {err}")
        status, _, err = run(exe, "run", BED, "-o", os.path.join(tmp, "n"), "--restart", os.path.join(tmp, "none.h5"))
        check(status == 2 and "no such checkpoint" in err, f"a missing checkpoint: {status} {err}")
    return finish("test_checkpoint_restart")


if __name__ == "__main__":
    sys.exit(main())
