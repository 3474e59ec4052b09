"""Shared set-up of the Python interface's tests: the program beside the module (for runs from the
command line to compare with), and small cases of both engines in 2D and 3D."""
import os
import subprocess

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture(scope="session")
def grainflow_bin():
    path = os.environ.get("GRAINFLOW_BIN", os.path.join(ROOT, "build", "release", "grainflow"))
    if not os.path.exists(path):
        pytest.skip(f"no grainflow program at {path}")
    return path


def gas_case(engine, dimension, gravity=(0.0, 0.0, 0.0), temperature=1.0, duration=2.0, spacing=None):
    """An elastic gas in a periodic box of 8 d (8 x 8 d discs in 2D): lattice start, Gaussian
    velocities of granular temperature `temperature`, reduced units (d = 1, density = 1)."""
    count = 64 if dimension == 3 else (16 if spacing else 40)
    hi_z = 8.0 if dimension == 3 else 1.0
    lattice = f"lattice_spacing = {spacing}\n" if spacing else ""
    law = ('[contact]\nmodel = "linear_dashpot"\nkn = 1.0e5\ngamma_n = 0.0\nfriction = 0.0\n'
           if engine == "dem" else "[collision]\nrestitution = 1.0\n")
    step = "time_step = 1.0e-4\n" if engine == "dem" else ""
    return f"""
[engine]
kind = "{engine}"
dimension = {dimension}

[domain]
lo = [0.0, 0.0, 0.0]
hi = [8.0, 8.0, {hi_z}]
boundary = {{ x = "periodic", y = "periodic", z = "periodic" }}

[gravity]
vector = [{gravity[0]}, {gravity[1]}, {gravity[2]}]

[[species]]
name = "grain"
diameter = 1.0
density = 1.0
count = {count}

[particles]
init = "lattice"
{lattice}initial_temperature = {temperature}
seed = 3

{law}
[run]
duration = {duration}
{step}
[output]
interval = 0.1
"""


def run_cli(grainflow_bin, case_path, output, *sets):
    command = [grainflow_bin, "run", case_path, "-o", output, "--quiet"]
    for s in sets:
        command += ["--set", s]
    subprocess.run(command, check=True, capture_output=True, text=True)
