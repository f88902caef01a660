"""Particles sleep in islands exactly as bodies do (``particle_sleep.py``): the same thresholds
(no point gone 2.5 cm in 0.5 s, none faster than 0.05 m/s now), one island graph over
particles and bodies, and the same wake rules — touched by a moving particle or body, a force
that pushes, the user moving it, a link to a moving particle."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid import islands
from pointmass.rigid.shapes import Box

DT = 1.0 / 60.0
R = 0.1


def _until_asleep(world, seconds=3.0):
    for _ in range(int(seconds / DT)):
        world.step(DT)
        p = world.particles
        if not (p.awake & (p.inv_mass > 0)).any():  # immovable particles never sleep
            return world.time
    raise AssertionError(f"still awake after {seconds} s: {world.particles.awake}")


def _resting(world, x=0.0, **kwargs):
    return world.add_particle((x, R, 0.0), radius=R, **kwargs)


def _ground_world(**kwargs):
    world = pm.World(**kwargs)
    world.add(pm.Ground())
    return world


def test_a_resting_particle_falls_asleep_after_the_time_to_sleep_and_stays_exactly_put():
    world = _ground_world()
    i = _resting(world)
    slept = _until_asleep(world)
    assert islands.TIME_TO_SLEEP - DT <= slept <= islands.TIME_TO_SLEEP + 3 * DT
    where = world.particles.position[i].copy()
    for _ in range(120):
        stats = world.step(DT)
        assert stats.contacts == 0  # nothing active: no contact is even looked for
    assert not world.particles.awake[i] and np.array_equal(world.particles.position[i], where)
    assert np.array_equal(world.particles.velocity[i], np.zeros(3))  # gravity wakes nothing


def test_a_falling_particle_is_not_put_to_sleep():
    world = _ground_world()
    i = world.add_particle((0.0, 10.0, 0.0), radius=R)
    for _ in range(60):
        world.step(DT)
        assert world.particles.awake[i]


def test_sleeping_particles_are_neither_integrated_nor_solved():
    world = _ground_world()
    world.add(pm.SphereCollisions())
    for k in range(5):
        _resting(world, x=3 * R * k)
    _until_asleep(world)
    stats = world.step(DT)
    assert stats.contacts == 0 and stats.velocity_passes == 0


def test_a_user_force_wakes_a_sleeper_and_a_tiny_one_does_not():
    world = _ground_world()
    i = _resting(world)
    _until_asleep(world)
    world.particles.force[i] = (0.05, 0.0, 0.0)  # 0.05 m/s² on 1 kg: below the sleep test
    world.step(DT)
    assert not world.particles.awake[i]
    world.particles.force[i] = (5.0, 0.0, 0.0)
    world.step(DT)
    assert world.particles.awake[i] and world.particles.velocity[i, 0] > 0.05


@pytest.mark.parametrize("what", ["position", "velocity"])
def test_the_user_moving_a_sleeper_wakes_it(what):
    world = _ground_world()
    i = _resting(world)
    _until_asleep(world)
    if what == "position":
        world.particles[i].position = (0.0, 1.0, 0.0)
    else:
        world.particles[i].velocity = (1.0, 0.0, 0.0)
    world.step(DT)
    assert world.particles.awake[i]
    if what == "position":
        assert world.particles.velocity[i, 1] < 0.0  # falling from where it was put
    else:
        assert world.particles.position[i, 0] > 0.01


def test_a_moving_particle_that_touches_a_sleeping_one_wakes_it_and_pushes_it():
    world = _ground_world()
    world.add(pm.SphereCollisions(restitution=0.5))
    still = _resting(world)
    _until_asleep(world)
    world.add_particle((-1.0, R, 0.0), (3.0, 0.0, 0.0), radius=R)
    for _ in range(30):
        world.step(DT)
    assert world.particles.position[still, 0] > 0.05  # knocked along, not passed through


def test_a_nearby_particle_that_passes_by_wakes_nothing():
    world = _ground_world()
    world.add(pm.SphereCollisions())
    still = _resting(world)
    _until_asleep(world)
    world.add_particle((-1.0, R, 3 * R), (3.0, 0.0, 0.0), radius=R)  # a lane beside it
    for _ in range(40):
        world.step(DT)
        assert not world.particles.awake[still]


def test_a_spring_whose_other_end_moves_wakes_the_sleeper_gravity_alone_does_not():
    world = _ground_world()
    a = _resting(world)
    b = _resting(world, x=1.0)
    world.add(pm.Spring(a, b, spring_constant=50.0, rest_length=1.0))
    _until_asleep(world)
    for _ in range(60):
        world.step(DT)
    assert not world.particles.awake.any()
    world.particles[b].position = (1.5, R, 0.0)  # the user pulls b: a feels the spring
    world.step(DT)
    assert world.particles.awake.all()


def test_a_hanging_damped_spring_falls_asleep_and_stays_asleep():
    world = pm.World()
    i = world.add_particle((0.0, -1.0, 0.0))
    world.add(pm.AnchoredSpring(i, (0.0, 0.0, 0.0), spring_constant=100.0, rest_length=1.0,
                                damping=8.0))
    _until_asleep(world, seconds=10.0)
    stretch = 9.81 / 100.0
    # asleep near the rest length: its last swing was under the sleep test's 2.5 cm (measured
    # 2.6 mm above the equilibrium, still rising slowly when it fell asleep)
    assert world.particles.position[i, 1] == pytest.approx(-1.0 - stretch, abs=5e-3)
    for _ in range(120):
        world.step(DT)
    assert not world.particles.awake[i]  # the spring still holds it: no change, no wake


def test_particles_linked_by_a_rod_share_an_island_and_a_link_to_a_mover_wakes():
    world = _ground_world()
    a = _resting(world)
    b = _resting(world, x=0.5)
    world.add(pm.Rod(a, b, 0.5))
    _until_asleep(world)
    assert world.particles.island[a] == world.particles.island[b]
    world.particles.force[b] = (20.0, 0.0, 0.0)
    world.step(DT)
    assert world.particles.awake.all()  # b's push woke its island, a with it

    # A moving immovable particle (kinematic) wakes a sleeper it is linked to by a cable.
    world = _ground_world()
    a = _resting(world)
    hook = world.add_particle((0.0, 2.0, 0.0), mass=np.inf)
    world.add(pm.Cable(a, hook, 3.0))
    _until_asleep(world)
    world.particles[hook].velocity = (0.0, 1.0, 0.0)
    world.step(DT)
    assert world.particles.awake[a]


def test_a_particle_on_a_box_sleeps_with_it_and_wakes_when_the_box_is_pushed():
    world = _ground_world()
    box = world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.5, 0.0), mass=1.0)
    i = world.add_particle((0.0, 1.0 + R, 0.0), radius=R)
    _until_asleep(world)
    assert not box.awake
    on = world.particles.position[i].copy()
    for _ in range(60):
        world.step(DT)
    assert np.array_equal(world.particles.position[i], on)
    box.add_force((0.0, 60.0, 0.0))  # lifts the box under it
    world.step(DT)
    world.step(DT)
    assert box.awake and world.particles.awake[i]
    assert world.particles.position[i, 1] > on[1]


def test_a_particle_coming_to_rest_on_a_sleeping_box_sleeps_and_the_box_wakes_it():
    world = _ground_world()
    box = world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.5, 0.0), mass=1.0)
    for _ in range(60):
        world.step(DT)
    assert not box.awake
    i = world.add_particle((0.0, 1.0 + R + 0.02, 0.0), radius=R, mass=0.1)
    _until_asleep(world)
    assert not box.awake  # a particle landing softly leaves it asleep
    box.velocity = (0.0, 2.0, 0.0)  # the user throws the box up: it carries the particle
    for _ in range(10):
        world.step(DT)
    assert world.particles.awake[i] and world.particles.position[i, 1] > 1.0 + R + 0.1


def test_sleep_off_never_sleeps_and_turning_it_off_wakes_every_particle():
    world = _ground_world(sleep=False)
    i = _resting(world)
    for _ in range(120):
        world.step(DT)
    assert world.particles.awake[i]
    world.sleep = True
    _until_asleep(world)
    world.sleep = False
    assert world.particles.awake.all()


def _pile_run(sleep, steps=150):
    world = pm.World(sleep=sleep)
    world.add(pm.BoxContainer((-0.6, 0.0, -0.6), (0.6, 5.0, 0.6), restitution=0.3))
    world.add(pm.SphereCollisions(restitution=0.3))
    rng = np.random.default_rng(3)
    world.add_particles(rng.uniform((-0.4, 0.2, -0.4), (0.4, 1.5, 0.4), (20, 3)), radii=R)
    states = []
    for _ in range(steps):
        world.step(DT)
        states.append(world.particles.snapshot())
    return states


def test_sleeping_changes_nothing_until_the_first_island_sleeps_and_reruns_are_identical():
    """World(sleep=False) is the engine without particle sleep: until something falls asleep,
    sleep on gives the same bits (the same kernels on the same rows), and each is
    deterministic. (Against the engine before particles slept: the same bits, checked when
    this landed on the 100- and 1000-sphere pits over 600 steps.)"""
    on, off, again = _pile_run(True), _pile_run(False), _pile_run(True)
    compared = 0
    for a, b, c in zip(on, off, again):
        for name in a:
            assert np.array_equal(a[name], c[name]), name
        assert b["awake"].all()
        if not a["awake"].all():
            break
        for name in ("position", "velocity"):
            assert np.array_equal(a[name], b[name]), name
        compared += 1
    assert compared >= 30


def test_snapshots_keep_the_sleep_state():
    world = _ground_world()
    i = _resting(world)
    _until_asleep(world)
    snap = world.particles.snapshot()
    world.particles.wake(i)
    assert world.particles.awake[i]
    world.particles.restore(snap)
    assert not world.particles.awake[i]
    old = {k: v for k, v in snap.items() if k in ("position", "velocity", "force",
                                                  "acceleration", "inv_mass", "radius",
                                                  "damping")}
    world.particles.restore(old)  # a snapshot from before particles slept: all awake
    assert world.particles.awake[i]


def test_a_particle_handle_puts_to_sleep_and_wakes():
    world = _ground_world()
    i = _resting(world)
    world.particles[i].awake = False
    assert not world.particles[i].awake
    world.step(DT)
    assert not world.particles[i].awake
    world.particles[i].awake = True
    assert world.particles.awake[i]
    pinned = world.add_particle((5.0, 5.0, 0.0), mass=np.inf)
    with pytest.raises(ValueError, match="immovable"):
        world.particles[pinned].awake = False
    with pytest.raises(TypeError, match="awake"):
        world.particles[i].awake = 1


def test_a_mass_written_to_a_sleeper_wakes_it():
    """The platform demo spreads its load over the truss as mass: a truss asleep must feel it."""
    world = _ground_world()
    i = _resting(world)
    _until_asleep(world)
    world.particles.inv_mass[i] = 0.5
    world.step(DT)
    assert world.particles.awake[i]
