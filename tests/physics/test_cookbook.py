"""The Physics Cook Book's own numbers, reproduced with pointmass."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm

DT = 1.0 / 60.0


def test_vector3_cases_as_numpy():
    """Reproduce the cookbook's Vector3 test cases with numpy arrays."""
    a = np.array([1.0, 2.0, 3.0])
    b = np.array([3.0, 2.0, 1.0])
    assert np.array_equal(a - b, [-2.0, 0.0, 2.0])
    b = b * 2
    assert np.array_equal(b, [6.0, 4.0, 2.0])
    assert a @ b == 20.0
    assert np.array_equal(np.cross([1.0, 2.0, 3.0], [1.0, 5.0, 7.0]), [-1.0, -4.0, 3.0])


def test_drag_magnitude_matches_cookbook():
    """Give DragGenerator(0.2, 0.001) at v = (10, 30, 100) a force of 31.976176963403034 N."""
    world = pm.World(gravity=(0, 0, 0))
    i = world.add_particle(velocity=(10.0, 30.0, 100.0))
    drag = world.add(pm.Drag(0.2, 0.001))
    world.particles.force[:] = 0.0
    drag.apply(world.particles, DT)
    force = world.particles.force[i]
    assert np.linalg.norm(force) == pytest.approx(31.976176963403034, rel=1e-14)
    # Opposite to the velocity.
    v = np.array([10.0, 30.0, 100.0])
    assert np.allclose(np.cross(force, v), 0.0, atol=1e-12) and force @ v < 0


def test_anchored_spring_pulls_one_newton_toward_anchor():
    """Pull a particle at the origin by (0, 1, 0) with the cookbook's anchored spring."""
    world = pm.World(gravity=(0, 0, 0))
    i = world.add_particle()
    spring = world.add(pm.AnchoredSpring(i, anchor=(0.0, 2.0, 0.0), spring_constant=1.0,
                                         rest_length=1.0))
    world.particles.force[:] = 0.0
    spring.apply(world.particles, DT)
    assert np.allclose(world.particles.force[i], [0.0, 1.0, 0.0], atol=1e-15)


def test_cat_pushed_point_mass_reaches_terminal_velocity():
    """Fall with gravity and drag (0.1, 0.1) for 5 s at 60 Hz to the cookbook's -9.42."""
    world = pm.World(gravity=(0, 0, 0))
    i = world.add_particle(position=(0, 100, 0), velocity=(0.1, 0, 0))
    world.add(pm.Gravity((0.0, -9.81, 0.0)))
    world.add(pm.Drag(0.1, 0.1))
    for _ in range(60 * 5):
        world.step(DT)
    vy = world.particles.velocity[i, 1]
    assert vy == pytest.approx(-9.42, abs=0.01)
    # And the exact terminal speed, where k1·v + k2·v² = m·g.
    terminal = (-0.1 + np.sqrt(0.1**2 + 4 * 0.1 * 9.81)) / (2 * 0.1)
    assert -vy == pytest.approx(terminal, rel=1e-3)


def _spring_pair(with_spring: bool) -> tuple[pm.World, int, int]:
    world = pm.World(gravity=(0, 0, 0))
    p1 = world.add_particle(position=(2, 2, 2), velocity=(0, 10, 30), mass=1.0)
    p2 = world.add_particle(position=(2, 2, 2), mass=20.0)
    if with_spring:
        world.add(pm.Spring(p1, p2, spring_constant=100.0, rest_length=2.0))
    world.add(pm.Gravity((0.0, -9.81, 0.0)))
    return world, p1, p2


def _run(world: pm.World, steps: int) -> np.ndarray:
    trajectory = []
    for _ in range(steps):
        world.step(DT)
        trajectory.append(world.particles.position.copy())
    return np.array(trajectory)


def test_spring_pair_starts_coincident_without_a_force():
    """Give no spring force while the ends coincide (no direction), as the cookbook does."""
    bound, _, _ = _spring_pair(True)
    free, _, _ = _spring_pair(False)
    bound.step(DT)
    free.step(DT)
    assert np.array_equal(bound.particles.position, free.particles.position)
    assert np.isfinite(bound.particles.velocity).all()


def test_spring_pair_heavier_particle_is_less_affected():
    """Deflect the 20 kg particle 20x less than the 1 kg one from its spring-free path."""
    bound, p1, p2 = _spring_pair(True)
    free, _, _ = _spring_pair(False)
    deflection = _run(bound, 60) - _run(free, 60)  # (steps, particle, xyz)
    d1 = np.linalg.norm(deflection[:, p1], axis=1)
    d2 = np.linalg.norm(deflection[:, p2], axis=1)
    assert d1[-1] > 0.5  # the spring really acted
    # Equal and opposite forces: m1·d1 + m2·d2 = 0 at every step.
    assert np.allclose(1.0 * deflection[:, p1] + 20.0 * deflection[:, p2], 0.0, atol=1e-9)
    assert np.all(d2[1:] < d1[1:] / 19.0)
    # Bound together: the spring keeps them within a few rest lengths.
    fresh, _, _ = _spring_pair(True)
    trajectory = _run(fresh, 240)
    lengths = np.linalg.norm(trajectory[:, p1] - trajectory[:, p2], axis=1)
    assert lengths.max() < 6.0


def test_spring_pair_gravity_accelerates_both_equally():
    """Make the pair's centre of mass fall exactly like a free point (gravity acts equally)."""
    bound, p1, p2 = _spring_pair(True)
    trajectory = _run(bound, 60)
    com = (1.0 * trajectory[:, p1] + 20.0 * trajectory[:, p2]) / 21.0
    n = np.arange(1, 61)
    v0 = np.array([0.0, 10.0, 30.0]) / 21.0
    expected_y = 2.0 + v0[1] * n * DT - 9.81 * DT**2 * n * (n + 1) / 2
    assert np.allclose(com[:, 1], expected_y, atol=1e-9)
    assert np.allclose(com[:, 2], 2.0 + v0[2] * n * DT, atol=1e-9)
    # Without the spring, both gain the same downward velocity.
    free, q1, q2 = _spring_pair(False)
    _run(free, 30)
    dv1 = free.particles.velocity[q1, 1] - 10.0
    dv2 = free.particles.velocity[q2, 1] - 0.0
    assert dv1 == pytest.approx(dv2, abs=1e-12) == pytest.approx(-9.81 * 30 * DT)


def test_a_force_added_before_a_step_acts_in_it_and_is_then_cleared():
    """As the book's addForce: the accumulator holds until the integration reads and clears it
    (a hook's add_force before world.step is not thrown away)."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    i = world.add_particle((0.0, 0.0, 0.0), mass=2.0)
    world.particles[i].add_force((4.0, 0.0, 0.0))
    world.step(0.5)
    assert world.particles.velocity[i, 0] == pytest.approx(4.0 / 2.0 * 0.5)
    assert not world.particles.force.any()
    world.step(0.5)                            # nothing added: no force this time
    assert world.particles.velocity[i, 0] == pytest.approx(1.0)
