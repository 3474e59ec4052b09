"""grainflow from Python: cases, runs of both engines, particle arrays and outputs.

    import grainflow
    case = grainflow.Case.from_file("cases/demo/vibrated_bed.toml", set={"run.duration": 0.1})
    sim = grainflow.Simulation(case)
    sim.step(100)
    v = sim.particles.velocity          # N x 3, the engine's own memory
    sim.run(); print(sim.summary()["kinetic_energy"])

docs/PYTHON.md has the whole interface, its units and the arrays' lifetime.
"""
from ._grainflow import __version__
from .case import Case
from .errors import InputError, RunError
from .outputs import RunOutputs, Table, load_run
from .simulation import Particles, Simulation

__all__ = ["Case", "Simulation", "Particles", "InputError", "RunError", "load_run", "RunOutputs", "Table",
           "__version__"]
