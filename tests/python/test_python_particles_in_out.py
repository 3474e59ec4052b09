"""Particles added and removed from Python (DEM): the new particle moves as physics says from the
step it joins, the removed ones are gone, and the energy budget follows both."""
import numpy as np
import pytest

import grainflow
from conftest import gas_case


def test_an_added_particle_falls_freely_from_the_step_it_joins():
    # Gravity -1 along y; a particle added at rest in the open (3 d from every lattice site at
    # spacing 2 would overlap: the lattice runs every 2 d from 1 d, so (2, 2, 2) is clear of all).
    case = grainflow.Case.from_string(gas_case("dem", 3, gravity=[0.0, -1.0, 0.0], temperature=0.0, spacing=2.0,
                                               duration=1.0))
    sim = grainflow.Simulation(case)
    sim.step(10)
    n = len(sim.particles)
    (new,) = sim.add_particles([2.0, 2.0, 2.0])
    assert new == max(sim.particles.id) + 1
    sim.step(1)                              # it joins at this step's list rebuild, mid-step
    p = sim.particles
    assert len(p) == n + 1
    k = int(np.flatnonzero(p.id == new)[0])
    assert p.mass[k] == pytest.approx(np.pi / 6.0)          # the species' sphere, density 1
    # Put in after the drift, it gets the second half kick only: v = -g dt / 2 after the first
    # step, then -g dt per step (velocity Verlet under a constant force, to round-off).
    dt = sim.time_step
    np.testing.assert_allclose(p.velocity[k], [0.0, -0.5 * dt, 0.0], rtol=0, atol=1e-15)
    sim.step(99)
    p = sim.particles
    k = int(np.flatnonzero(p.id == new)[0])
    np.testing.assert_allclose(p.velocity[k], [0.0, -99.5 * dt, 0.0], rtol=0, atol=1e-13)
    summary = sim.summary()
    assert abs(summary["energy_budget_residual"]) < 1e-9   # the budget counted it in


def test_overlapping_or_misplaced_additions_are_refused():
    sim = grainflow.Simulation(grainflow.Case.from_string(gas_case("dem", 3, temperature=0.0, spacing=2.0)))
    x = sim.particles.position[0].copy()
    with pytest.raises(grainflow.InputError) as error:
        sim.add_particles(x + [0.5, 0.0, 0.0])
    assert "overlap" in error.value.reason
    with pytest.raises(grainflow.InputError):
        sim.add_particles([[2.0, 2.0, 2.0], [2.5, 2.0, 2.0]])     # the two new ones overlap
    with pytest.raises(grainflow.InputError) as error:
        sim.add_particles([2.0, 2.0, 2.0], species="sand")
    assert error.value.key == "species"


def test_removed_particles_are_gone_and_their_energy_leaves_the_budget():
    # An elastic gas: removing particles that touch nothing takes exactly their kinetic energy
    # out of the start value, so the budget still closes to the integrator's error.
    sim = grainflow.Simulation(grainflow.Case.from_string(gas_case("dem", 3, spacing=2.0, temperature=0.01,
                                                                   duration=0.5)))
    sim.step(100)
    ids = sim.particles.id[:10].copy()
    sim.remove_particles(ids)
    sim.step(1)
    p = sim.particles
    assert len(p) == 54 and not np.isin(ids, p.id).any()
    summary = sim.summary()
    assert abs(summary["energy_budget_residual"]) < 1e-6


def test_the_event_driven_engine_refuses_both():
    sim = grainflow.Simulation(grainflow.Case.from_string(gas_case("edmd", 2)))
    with pytest.raises(grainflow.InputError):
        sim.add_particles([4.0, 4.0, 0.5])
    with pytest.raises(grainflow.InputError):
        sim.remove_particles([0])


def test_two_dimensional_additions_lie_on_the_discs_plane():
    case = grainflow.Case.from_string(gas_case("dem", 2, gravity=[0.0, -1.0, 0.0], temperature=0.0, spacing=2.0))
    sim = grainflow.Simulation(case)
    (new,) = sim.add_particles([2.0, 2.0, 0.9], velocity=[0.1, 0.0, 0.3])
    sim.step(1)
    p = sim.particles
    k = int(np.flatnonzero(p.id == new)[0])
    assert p.position[k][2] == 0.5 and p.velocity[k][2] == 0.0
    assert p.mass[k] == pytest.approx(np.pi / 4.0)           # a disc of density 1 per area
