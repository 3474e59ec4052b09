"""`mpirun -np N grainflow sweep ...`: the runs of a sweep are shared out over the MPI ranks,
each rank running every N-th as a plain one-rank process, and rank 0 writes the one sweep.csv and
sweep.json for all of them, with the same results as a sweep without MPI.

Usage: /usr/bin/python3 tests/integration/test_mpi_sweep.py PATH_TO_grainflow
"""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, mpi_environment, mpirun_found, read_csv, run  # noqa: E402

CHUTE = "cases/campbell1982/chute_30deg.toml"
VALUES = ["0.5", "0.6", "0.7", "0.8", "0.9"]


def main():
    exe = executable_from_argv("usage: test_mpi_sweep.py PATH_TO_grainflow")
    if exe is None:
        return 2
    if not mpirun_found():
        return finish("test_mpi_sweep")
    with tempfile.TemporaryDirectory() as tmp:
        args = ["sweep", CHUTE, "--set", "run.duration=5", "--vary", "collision.restitution=" + ",".join(VALUES)]
        plain = os.path.join(tmp, "plain")
        status, _, err = run(exe, *args, "-o", plain, "--jobs", "1")
        check(status == 0, f"sweep without MPI: {status}: {err}")
        spread = os.path.join(tmp, "mpi")
        result = subprocess.run(["mpirun", "--oversubscribe", "-np", "2", exe, *args, "-o", spread], capture_output=True,
                                text=True, env=mpi_environment())
        check(result.returncode == 0, f"sweep on 2 ranks: {result.returncode}: {result.stderr}")
        # Each rank ran its share: both ranks reported runs.
        for rank in (0, 1):
            check(f"rank {rank} [" in result.stderr, f"rank {rank} ran none of the sweep's runs:\n{result.stderr}")
        a, b = read_csv(os.path.join(plain, "sweep.csv")), read_csv(os.path.join(spread, "sweep.csv"))
        check(len(b) == len(VALUES), f"sweep.csv on 2 ranks has {len(b)} rows")
        for x, y in zip(a, b):
            # One process per run either way, so each run is the same computation: equal to the last digit.
            for key in ("run", "status", "collisions", "kinetic_energy", "granular_temperature"):
                check(x.get(key) == y.get(key), f"run {x.get('run')}: {key} {y.get(key)} on 2 ranks, {x.get(key)} without")
    return finish("test_mpi_sweep")


if __name__ == "__main__":
    sys.exit(main())
