"""Gravity and drag on every particle are folded into the integration kernel
(``ForceGenerator.fused_terms``): the same physics as through the accumulator."""

import numpy as np
import pytest

import pointmass as pm

DT = 1 / 60


def _flying(n: int = 200, seed: int = 4) -> pm.World:
    rng = np.random.default_rng(seed)
    world = pm.World(gravity=(0, -9.81, 0))
    world.add_particles(rng.uniform(-5, 5, (n, 3)), rng.normal(0, 4, (n, 3)),
                        masses=rng.uniform(0.2, 3.0, n), damping=rng.uniform(0.5, 1.0, n))
    world.particles.pin(3)  # immovable: no gravity, no drag
    return world


def test_folding_leaves_the_trajectory_as_the_accumulator_gives_it():
    """Drag and a Gravity generator on all particles (folded) against the same generators on
    an explicit list of every particle (applied through the accumulator): 120 steps agree to
    rounding, immovable particles included."""
    folded, accumulated = _flying(), _flying()
    every = np.arange(folded.particles.count)
    folded.add(pm.Drag(0.3, 0.05))
    folded.add(pm.Gravity((0.5, 0.0, -1.0)))
    accumulated.add(pm.Drag(0.3, 0.05, particles=every))
    accumulated.add(pm.Gravity((0.5, 0.0, -1.0), particles=every))
    assert all(f.fused_terms() is not None for f in folded.forces)
    assert all(f.fused_terms() is None for f in accumulated.forces)
    for _ in range(120):
        e1 = folded.step(DT).kinetic_energy
        e2 = accumulated.step(DT).kinetic_energy
    a, b = folded.particles, accumulated.particles
    scale = np.abs(b.position).max()
    assert np.abs(a.position - b.position).max() < 1e-12 * scale
    assert np.abs(a.velocity - b.velocity).max() < 1e-12 * np.abs(b.velocity).max()
    assert e1 == pytest.approx(e2, rel=1e-12)
    assert np.array_equal(a.position[3], b.position[3])


def test_a_drag_subclass_that_overrides_apply_is_not_folded():
    """A subclass with its own ``apply`` keeps its own forces: folding it would skip them."""

    class Wind(pm.Drag):
        def apply(self, particles, dt):
            particles.force[:, 0] += 2.0

    world = pm.World(gravity=(0, 0, 0))
    p = world.add_particle()
    world.add(Wind(0.0, 0.0))
    world.step(0.5)
    assert world.particles.velocity[p, 0] == pytest.approx(1.0)


def test_a_force_added_by_hand_still_acts_with_folded_drag():
    """The accumulator still carries user forces alongside folded drag (from rest drag is
    zero: the push alone acts in the first step), and the step clears it."""
    world = pm.World(gravity=(0, 0, 0))
    p = world.add_particle(mass=2.0)
    world.add(pm.Drag(1.0, 1.0))
    world.particles[p].add_force((4.0, 0.0, 0.0))
    world.step(0.1)
    assert world.particles.velocity[p, 0] == pytest.approx(0.2)
    assert not world.particles.force.any()


def test_the_resting_contact_test_sees_folded_forces():
    """With a contact generator the integration stores the acceleration it used, folded drag
    and Gravity generators included: a = g + g_extra + F_drag/m."""
    world = pm.World(gravity=(0, -9.81, 0))
    p = world.add_particle((0, 5, 0), velocity=(2.0, 0.0, 0.0), mass=0.5, radius=0.1)
    world.add(pm.Drag(0.2, 0.0))
    world.add(pm.Gravity((0.0, -1.0, 0.0)))
    world.add(pm.Ground())
    world.step(DT)
    assert world.particles.acceleration[p] == pytest.approx((-0.2 * 2.0 / 0.5, -10.81, 0.0))


def test_a_copied_store_keeps_its_views_on_its_own_arrays():
    """The properties return views cached per count: a deep copy rebuilds them on the copy's
    arrays, so what is written through them survives growth and is not the original's."""
    import copy

    world = _flying(5)
    twin = copy.deepcopy(world)
    twin.particles.position[0] = (7.0, 8.0, 9.0)
    twin.add_particle()  # the arrays may grow; the views are rebuilt
    assert twin.particles.position[0].tolist() == [7.0, 8.0, 9.0]
    assert world.particles.position[0].tolist() != [7.0, 8.0, 9.0]
    assert twin.particles.count == 6 and world.particles.count == 5
