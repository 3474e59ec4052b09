"""grainflow.Simulation: runs of both engines in 2D and 3D from Python, against the command line
(byte-identical outputs), the particle arrays as views of the engine's memory, conservation laws
through them, and interruption."""
import json
import os
import signal
import threading

import numpy as np
import pytest

import grainflow
from conftest import ROOT, gas_case, run_cli

VIBRATED_BED = os.path.join(ROOT, "cases", "demo", "vibrated_bed.toml")
# What depends on the machine's clock, not on the run.
CLOCK_KEYS = ("wall_seconds", "particle_steps_per_second", "events_per_second", "collisions_per_second",
              "peak_memory_bytes")


def assert_same_outputs(a, b):
    names_a = sorted(os.listdir(a))
    assert names_a == sorted(os.listdir(b))
    for name in names_a:
        if name == "run_log.json" or os.path.isdir(os.path.join(a, name)):
            continue
        with open(os.path.join(a, name), "rb") as fa, open(os.path.join(b, name), "rb") as fb:
            da, db = fa.read(), fb.read()
        if name == "summary.json":
            ja, jb = json.loads(da), json.loads(db)
            for key in list(ja):
                if any(clock in key for clock in CLOCK_KEYS):
                    ja.pop(key), jb.pop(key, None)
            assert ja == jb
        else:
            assert da == db, f"{name} differs"


def write_case(tmp_path, text, name="case.toml"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_dem_run_from_python_is_byte_identical_to_the_command_line(tmp_path, grainflow_bin):
    run_cli(grainflow_bin, VIBRATED_BED, str(tmp_path / "cli"), "run.duration=0.02", "output.snapshot_interval=0.01")
    case = grainflow.Case.from_file(VIBRATED_BED, set={"run.duration": 0.02, "output.snapshot_interval": 0.01})
    assert grainflow.Simulation(case).run(output=str(tmp_path / "py")) == 0
    assert_same_outputs(str(tmp_path / "cli"), str(tmp_path / "py"))
    assert sorted(os.listdir(tmp_path / "cli" / "snapshots")) == sorted(os.listdir(tmp_path / "py" / "snapshots"))


def test_dem_run_stepped_in_pieces_is_byte_identical(tmp_path, grainflow_bin):
    # Stepping is the run's own loop cut into pieces: the same steps, samples and rows.
    run_cli(grainflow_bin, VIBRATED_BED, str(tmp_path / "cli"), "run.duration=0.02")
    case = grainflow.Case.from_file(VIBRATED_BED, set={"run.duration": 0.02})
    sim = grainflow.Simulation(case, output=str(tmp_path / "py"))
    for _ in range(5):
        sim.step(1237)
    sim.advance(0.001)
    assert sim.run() == 0
    assert_same_outputs(str(tmp_path / "cli"), str(tmp_path / "py"))


@pytest.mark.parametrize("dimension", [2, 3])
def test_edmd_run_from_python_is_byte_identical(tmp_path, grainflow_bin, dimension):
    path = write_case(tmp_path, gas_case("edmd", dimension, duration=1.0))
    run_cli(grainflow_bin, path, str(tmp_path / "cli"))
    sim = grainflow.Simulation(grainflow.Case.from_file(path))
    assert sim.run(output=str(tmp_path / "py")) == 0
    assert_same_outputs(str(tmp_path / "cli"), str(tmp_path / "py"))


@pytest.mark.parametrize("engine,dimension", [("dem", 2), ("dem", 3), ("edmd", 2), ("edmd", 3)])
def test_zero_velocity_through_the_view_stops_the_particle(engine, dimension):
    # Particles 2 d apart at a low temperature under gravity: none touches within the steps below,
    # so each falls freely. The particle whose velocity is set to zero through the view then moves
    # as one released from rest: v = g t and x - x0 = g t^2 / 2 (velocity Verlet and the
    # event-driven parabola are both exact for a constant force; round-off bound 1e-12).
    g = [0.0, -1.0, 0.0]
    case = grainflow.Case.from_string(gas_case(engine, dimension, gravity=g, temperature=1e-4, spacing=2.0))
    sim = grainflow.Simulation(case)
    sim.advance(0.05)
    p = sim.particles
    k = int(np.flatnonzero(p.id == 7)[0])
    p.velocity[k] = 0.0                       # the engine's own memory
    assert np.all(sim.particles.velocity[k] == 0.0)
    x0 = p.position[k].copy()
    dt = 0.01 if engine == "edmd" else 100 * sim.time_step
    sim.advance(dt)
    p = sim.particles
    k = int(np.flatnonzero(p.id == 7)[0])
    np.testing.assert_allclose(p.velocity[k], np.array(g) * dt, rtol=0, atol=1e-12)
    moved = p.position[k] - x0
    np.testing.assert_allclose(moved, 0.5 * np.array(g) * dt * dt, rtol=0, atol=1e-12)


@pytest.mark.parametrize("engine,dimension", [("dem", 2), ("dem", 3), ("edmd", 2), ("edmd", 3)])
def test_energy_and_momentum_of_an_elastic_run_match_the_summary(engine, dimension):
    # An elastic gas in a periodic box: momentum is conserved to round-off (every pair force or
    # collision impulse is equal and opposite); the kinetic energy the arrays give at the end is
    # the summary's (which prints 10 digits: 1e-9); the event-driven gas keeps its kinetic energy
    # to round-off, the soft one to the integrator's O((dt / t_c)^2) error, t_c / dt = 28 here (5e-3).
    sim = grainflow.Simulation(grainflow.Case.from_string(gas_case(engine, dimension, duration=0.5)))
    p = sim.particles
    m, v0 = p.mass.copy(), p.velocity.copy()
    momentum0 = (m[:, None] * v0).sum(axis=0)
    energy0 = 0.5 * np.sum(m[:, None] * v0 ** 2)
    sim.run()
    p = sim.particles
    m, v = p.mass, p.velocity
    momentum = (m[:, None] * v).sum(axis=0)
    energy = 0.5 * np.sum(m[:, None] * v ** 2)
    np.testing.assert_allclose(momentum, momentum0, rtol=0, atol=1e-12 * np.sqrt(energy0 * m.sum()))
    summary = sim.summary()
    assert summary["kinetic_energy"] == pytest.approx(energy, rel=1e-9)
    if engine == "edmd":
        assert energy == pytest.approx(energy0, rel=1e-12)
    else:
        # energy_change counts the springs too: the budget closes to the integrator's error.
        assert abs(summary["energy_change"]) < 5e-3 * energy0
        assert summary["kinetic_energy"] + summary["rotational_energy"] == pytest.approx(energy0, rel=5e-2)


def test_positions_are_writable_before_the_first_step_only():
    sim = grainflow.Simulation(grainflow.Case.from_string(gas_case("dem", 3, temperature=0.0, duration=0.5)))
    p = sim.particles
    assert p.position.flags.writeable and p.velocity.flags.writeable
    assert not p.radius.flags.writeable and not p.mass.flags.writeable and not p.id.flags.writeable
    # Two particles moved to overlap by 0.1 d: the first step feels their contact, kn * 0.1 apart.
    a, b = 0, 1
    pos = p.position
    pos[b] = pos[a] + np.array([0.9, 0.0, 0.0])
    ids = p.id[[a, b]].copy()
    sim.step(1)
    p = sim.particles
    ia, ib = (int(np.flatnonzero(p.id == i)[0]) for i in ids)
    assert p.velocity[ia][0] < 0.0 < p.velocity[ib][0]
    assert not p.position.flags.writeable


def test_advancing_past_the_duration_names_the_key():
    sim = grainflow.Simulation(grainflow.Case.from_string(gas_case("dem", 3, duration=0.01)))
    with pytest.raises(grainflow.InputError) as error:
        sim.step(1000)
    assert error.value.key == "run.duration"
    edmd = grainflow.Simulation(grainflow.Case.from_string(gas_case("edmd", 2, duration=0.01)))
    with pytest.raises(grainflow.InputError) as error:
        edmd.advance(1.0)
    assert error.value.key == "run.duration"
    with pytest.raises(grainflow.InputError):
        edmd.step(1)   # no time step in the event-driven engine


def test_ctrl_c_raises_keyboard_interrupt_and_the_run_goes_on():
    case = grainflow.Case.from_string(gas_case("dem", 3, duration=1000.0))
    sim = grainflow.Simulation(case)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sim.step(sim.duration / sim.time_step)
    timer.join()
    stopped = sim.steps
    assert 0 < stopped < round(sim.duration / sim.time_step)
    sim.step(10)                                     # it goes on from the step it stopped at
    assert sim.steps == stopped + 10
    # Python's own handler is back: a SIGINT now is Python's KeyboardInterrupt as usual.
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        for _ in range(1000):
            pass


def test_outputs_in_memory_are_the_files(tmp_path, grainflow_bin):
    sim = grainflow.Simulation(grainflow.Case.from_file(VIBRATED_BED, set={"run.duration": 0.02}),
                               output=str(tmp_path / "py"))
    sim.step(100)
    out = sim.outputs()                              # finishes the run here
    assert sim.finished
    assert out.summary["steps"] == 100 and out.summary["simulated_time"] == pytest.approx(100 * sim.time_step)
    table = out.timeseries
    assert table.columns[0] == "time" and table["time"][0] == 0.0
    assert "units" not in table and "kinetic_energy" in table.units
    loaded = grainflow.load_run(str(tmp_path / "py"))
    np.testing.assert_array_equal(loaded["final_state"]["x"], out.final_state["x"])
    with pytest.raises(grainflow.RunError):
        sim.step(1)                                  # finished: its outputs are written


def test_the_gil_is_released_while_the_engine_runs():
    # A Python thread notes the time as it counts while the main thread is inside step(): had the
    # engine held the GIL, none of its notes could fall inside the call, away from its two ends.
    import time
    sim = grainflow.Simulation(grainflow.Case.from_string(gas_case("dem", 3, duration=1000.0)))
    stamps, running = [], [True]

    def count():
        n = 0
        while running[0]:
            n += 1
            if n % 1000 == 0:
                stamps.append(time.perf_counter())

    worker = threading.Thread(target=count)
    worker.start()
    try:
        start = time.perf_counter()
        sim.step(100000)
        end = time.perf_counter()
    finally:
        running[0] = False
        worker.join()
    margin = 0.1 * (end - start)
    inside = [t for t in stamps if start + margin < t < end - margin]
    assert len(inside) > 10, (end - start, len(stamps))


def test_run_into_another_folder_after_stepping(tmp_path):
    # The run's folder is fixed once it began; run(output=...) then ends it there and copies it.
    sim = grainflow.Simulation(grainflow.Case.from_string(gas_case("dem", 3, duration=0.2)))
    sim.step(40)
    assert sim.run(output=str(tmp_path / "moved")) == 0
    out = grainflow.load_run(str(tmp_path / "moved"))
    assert out.summary["steps"] == 2000 and out.summary["simulated_time"] == pytest.approx(0.2)
    np.testing.assert_allclose(out.timeseries["time"], [0.0, 0.1, 0.2])


@pytest.mark.parametrize("engine", ["dem", "edmd"])
def test_reading_the_arrays_leaves_the_run_as_it_was(tmp_path, engine):
    # Taking views between advances without writing them must not change a bit of the run (the
    # event-driven engine would otherwise predict every event anew from the views' values).
    finals = []
    for read in (False, True):
        case = grainflow.Case.from_string(gas_case(engine, 3, gravity=[0.0, -1.0, 0.0], duration=1.0))
        sim = grainflow.Simulation(case, output=str(tmp_path / f"read_{read}"))
        if read:
            sim.particles.position.sum()
        for _ in range(10):
            sim.advance(0.05)
            if read:
                sim.particles.velocity.sum()
                sim.particles.angular_velocity.sum()
        sim.run()
        finals.append((tmp_path / f"read_{read}" / "final_state.csv").read_bytes())
    assert finals[0] == finals[1]
