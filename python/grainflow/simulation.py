"""Runs driven from Python: advanced in pieces, inspected and changed between them."""
import os
import shutil
import sys
import tempfile

from . import _grainflow
from .case import Case
from .errors import InputError
from .outputs import load_run


def grainflow_input_error(file, key, reason):
    return InputError(f"{file}: key '{key}': {reason}", file, key, reason)


class Particles:
    """The engine's particle arrays, as numpy arrays that view its memory (no copy).

    Lifetime: a view is valid until the next ``advance``/``step``/``run`` of its simulation, which
    may re-sort the particles (index ``i`` is not a particle's name: ``id`` is); take the arrays
    afresh from ``sim.particles`` after each advance, and ``.copy()`` what must outlive it.

    Writable: ``velocity`` (both engines) and ``angular_velocity`` (DEM) at any time; ``position``
    (DEM) before the first advance. The rest are read-only. Particles are added and removed by the
    case's ``[[insertion]]`` and ``[[outlet]]`` tables, not by resizing these arrays.
    """

    _VECTORS = ("position", "velocity", "angular_velocity", "force", "torque")
    _SCALARS = ("radius", "mass", "id", "species", "motion")

    def __init__(self, sim):
        self._sim = sim

    def __len__(self):
        return self._sim._core.particle_count()

    def _array(self, name):
        sim = self._sim
        core = sim._core
        writable = False
        if name == "velocity":
            writable = True
        elif name == "angular_velocity":
            writable = not core.event_driven
        elif name == "position":
            writable = not core.event_driven and core.steps == 0 and not sim._begun
        view = core.array(name, writable)
        if writable and name not in sim._handed_out:
            # What it holds now, to tell at the next advance whether it was written: the engine then
            # takes the new values up (an untouched view must leave the run as it was).
            sim._handed_out[name] = (view, view.copy())
        return view

    def __getattr__(self, name):
        if name in self._VECTORS or name in self._SCALARS:
            return self._array(name)
        raise AttributeError(f"no particle array '{name}' (there are: {', '.join(self._VECTORS + self._SCALARS)})")

    def __dir__(self):
        return list(self._VECTORS + self._SCALARS)


class Simulation:
    """A run of a case, by either engine, driven from Python.

    ``sim = Simulation(case)`` builds the engine (``case``: a :class:`Case` or a case file's path).
    ``sim.step(n)`` (DEM) and ``sim.advance(dt)`` advance it, its observers sampling as in
    ``grainflow run``; ``sim.run()`` goes on to the case's ``run.duration`` and writes every output,
    exactly as ``grainflow run`` does. Outputs go into ``output`` (a temporary folder, removed with
    the simulation, when not given); ``sim.outputs()`` and ``sim.summary()`` finish the run first if
    it has not finished, then read them.

    The engine runs with the GIL released; Ctrl-C stops ``step``/``advance``/``run`` at the step it
    reached with ``KeyboardInterrupt``, and the simulation can go on from there.
    """

    def __init__(self, case, output=None, threads=1):
        if not isinstance(case, Case):
            case = Case.from_file(case)
        self.case = case
        self._threads = int(threads)
        self._temporary = None
        if output is None:
            self._temporary = tempfile.TemporaryDirectory(prefix="grainflow_")
            output = os.path.join(self._temporary.name, "run")
        self._core = self._open(os.fspath(output))
        self._begun = False
        self._handed_out = {}  # writable views since the last advance: {name: (view, values then)}
        self._outputs = None

    def _open(self, output):
        # run_log.json's command line: the Python program that ran the case
        command_line = [sys.executable] + list(getattr(sys, "argv", []))
        return _grainflow.SessionCore(self.case._core, output, self._threads, command_line)

    # -- state ------------------------------------------------------------------------------
    @property
    def time(self):
        """Simulated time now, s."""
        return self._core.time

    @property
    def steps(self):
        """DEM: time steps taken; event-driven: events processed."""
        return self._core.steps

    @property
    def time_step(self):
        """DEM: the time step, s (event-driven: 0)."""
        return self._core.time_step

    @property
    def duration(self):
        """The case's ``run.duration``: how far the run may go."""
        return self._core.end_time

    @property
    def engine(self):
        return "edmd" if self._core.event_driven else "dem"

    @property
    def dimension(self):
        return self._core.dimension

    @property
    def output(self):
        """The folder the run writes into."""
        return self._core.output_directory

    @property
    def finished(self):
        return self._core.finished

    @property
    def particles(self):
        """The particle arrays now (see :class:`Particles` for lifetime and writing)."""
        return Particles(self)

    # -- advancing ---------------------------------------------------------------------------
    def _before_advance(self):
        written = self._written_arrays()
        if written:
            self._core.particles_written("position" in written)
        self._begun = True

    def _written_arrays(self):
        """The names of the writable views handed out since the last advance whose values changed."""
        import numpy as np
        written = [name for name, (view, before) in self._handed_out.items() if not np.array_equal(view, before)]
        self._handed_out = {}
        return written

    def step(self, n=1):
        """DEM: ``n`` time steps."""
        self._before_advance()
        self._core.advance_steps(int(n))
        return self

    def advance(self, dt):
        """Simulated time ``dt`` further (DEM: the nearest whole number of steps; event-driven:
        every particle brought to the new time)."""
        self._before_advance()
        self._core.advance_time(float(dt))
        return self

    def run(self, output=None):
        """On to the case's end and every output written, as ``grainflow run -o output`` does;
        returns the exit status (0; 1 after a failure, whose message is in the summary's
        ``errors``). With ``output`` another folder than the simulation's: before anything ran,
        the run goes there; after, it ends in its own folder and the whole folder is copied there."""
        copy_to = None
        if output is not None and os.path.abspath(output) != os.path.abspath(self.output):
            if self._begun:
                copy_to = os.fspath(output)  # the run's folder is fixed once it began: copied at the end
            else:
                self._move(os.fspath(output))
        self._before_advance()
        status = self._core.run()
        self._outputs = None
        if copy_to is not None:
            shutil.copytree(self.output, copy_to, dirs_exist_ok=True)
        return status

    def _move(self, output):
        old = self._core
        new = self._open(output)
        written = self._written_arrays()
        for name in written:  # what was written into the arrays goes with them
            new.array(name, True)[:] = old.array(name, False)
        if written:
            new.particles_written("position" in written)
        self._core = new

    # -- particles in and out ----------------------------------------------------------------
    def add_particles(self, position, velocity=None, species=0):
        """DEM: particles put in at ``position`` (N x 3, or one 3-vector) with ``velocity`` (same
        shape, default at rest), of ``species`` (the case's species by name or index; one for all,
        or one per particle), sized and weighed as that species. They must lie clear of every
        particle and wall (``InputError`` naming the one that does not; nothing is added); they
        join the run at the next step, whose energy budget counts them from then on. In 2D they
        lie on the discs' plane. Returns their new ids (numpy uint32)."""
        import numpy as np
        x = np.atleast_2d(np.asarray(position, dtype=np.float64))
        v = np.zeros_like(x) if velocity is None else np.atleast_2d(np.asarray(velocity, dtype=np.float64))
        names = [s["name"] for s in self.case["species"]]
        def index(s):
            if isinstance(s, str):
                if s not in names:
                    raise grainflow_input_error(self.case.path, "species", f"no species '{s}' (the case has {names})")
                return names.index(s)
            return int(s)
        kinds = [index(s) for s in species] if isinstance(species, (list, tuple, np.ndarray)) else [index(species)] * len(x)
        return np.asarray(self._core.add_particles(kinds, x, v), dtype=np.uint32)

    def remove_particles(self, ids):
        """DEM: the particles with these ids taken out at the next step (their energy leaves the
        budget's starting value; ids not present are ignored)."""
        import numpy as np
        self._core.remove_particles([int(i) for i in np.atleast_1d(ids)])

    def finish(self):
        """Writes every output now (the run ends here); returns the exit status."""
        status = self._core.finish()
        self._outputs = None
        return status

    # -- outputs -----------------------------------------------------------------------------
    def outputs(self):
        """Every output of the run (:class:`grainflow.RunOutputs`), the run finished first."""
        if not self._core.finished:
            self.finish()
        if self._outputs is None:
            self._outputs = load_run(self.output)
        return self._outputs

    def summary(self):
        """``summary.json`` as a dict, the run finished first."""
        return self.outputs()["summary"]

    def __repr__(self):
        state = "finished" if self.finished else f"t = {self.time:.6g} s"
        return f"<grainflow.Simulation {self.case.path!r} ({self.engine}, {state})>"


__all__ = ["Simulation", "Particles"]
