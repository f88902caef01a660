"""Materials at their defaults: a box on a default ``pm.Ground()`` grips and settles (the
ground leaves a body its own μ = 0.5 and e = 0), while particles keep the book's frictionless,
e = 0.5 ground; a material given to the ground combines with the body's (√(μa·μb), max e)."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm

DT = 1 / 60


def _box_on(ground, velocity=(2.0, 0.0, 0.0), height=0.505):
    world = pm.World()
    world.add(ground)
    body = world.add_body(pm.Box((0.5, 0.5, 0.5)), (0.0, height, 0.0), velocity=velocity,
                          mass=1.0)
    return world, body


def test_a_box_dropped_on_the_default_ground_comes_to_rest_by_3_s():
    """Drop a box from 0.5 m above a default Ground: it lands without bouncing and is at rest
    (speed < 1 mm/s, spin < 1 mrad/s) by 3 s, its centre 0.5 m up."""
    world, box = _box_on(pm.Ground(), velocity=(0.0, 0.0, 0.0), height=1.0)
    heights = []
    for _ in range(round(3.0 / DT)):
        world.step(DT)
        heights.append(box.position[1])
    assert np.linalg.norm(box.velocity) < 1e-3
    assert np.linalg.norm(box.angular_velocity) < 1e-3
    assert abs(box.position[1] - 0.5) < 0.01
    first = int(np.argmax(np.asarray(heights) < 0.51))
    assert max(heights[first:]) < 0.511  # e = 0: no bounce above a millimetre


def test_a_box_sliding_on_the_default_ground_stops_by_3_s():
    """Set a box on a default Ground moving 2 m/s sideways: it stops (speed < 1 mm/s) by 3 s,
    after sliding about v²/(2μg) = 0.41 m (the body's μ = 0.5), and stays on the ground."""
    world, box = _box_on(pm.Ground())
    heights = []
    for _ in range(round(3.0 / DT)):
        world.step(DT)
        heights.append(box.position[1])
    assert np.linalg.norm(box.velocity) < 1e-3
    assert np.linalg.norm(box.angular_velocity) < 1e-3
    assert abs(box.position[1] - 0.5) < 0.01
    assert 0.35 < box.position[0] < 0.47
    assert max(heights) < 0.506


def test_a_ground_given_no_friction_leaves_a_box_sliding():
    """Give the ground μ = 0 explicitly: it combines as √(0.5·0) = 0, so the box keeps its
    2 m/s (the old default's behaviour, now asked for by name)."""
    world, box = _box_on(pm.Ground(friction=0.0), velocity=(2.0, -1e-9, 0.0))
    for _ in range(round(2.0 / DT)):
        world.step(DT)
    assert abs(box.velocity[0] - 2.0) < 1e-6


def test_a_ground_given_restitution_bounces_a_body_by_the_larger_e():
    """A sphere body (e = 0) dropped 1 m onto Ground(restitution=0.5) leaves at half its
    closing speed √(2gh) = 4.43 m/s (max(0, 0.5)); on a default Ground it does not bounce
    (its own e = 0)."""
    closing = np.sqrt(2 * 9.81 * 1.0)
    rebound = {}
    for name, ground in (("given", pm.Ground(restitution=0.5)), ("default", pm.Ground())):
        world = pm.World(sleep=False)
        world.add(ground)
        ball = world.add_body(pm.Sphere(0.25), (0.0, 1.25, 0.0), mass=1.0)
        rising = []
        for _ in range(round(1.5 / DT)):
            world.step(DT)
            rising.append(ball.velocity[1])
        rebound[name] = max(rising)
    assert abs(rebound["given"] / closing - 0.5) < 0.05
    assert rebound["default"] < 0.05


def test_particles_on_the_default_ground_keep_the_books_material():
    """A particle dropped on a default Ground bounces at e = 0.5 and slides frictionlessly
    (the cookbook's numbers); its Ground reads μ = 0, e = 0.5."""
    ground = pm.Ground()
    assert (ground.friction, ground.restitution) == (0.0, 0.5)
    assert (ground.body_friction, ground.body_restitution) == (None, None)
    world = pm.World()
    world.add(ground)
    p = world.add_particle((0.0, 1.0, 0.0), velocity=(1.0, 0.0, 0.0), radius=0.1)
    closing = rebound = 0.0
    for _ in range(round(1.0 / DT)):
        before = world.particles.velocity[p, 1]
        world.step(DT)
        if not closing and before < -1.0 and world.particles.velocity[p, 1] > 0.0:
            closing, rebound = -before, world.particles.velocity[p, 1]
    assert closing > 3.0 and abs(rebound / closing - 0.5) < 0.02
    assert world.particles.velocity[p, 0] == 1.0


def test_setting_a_ground_material_later_applies_to_bodies_and_none_resets_it():
    """``ground.friction = 0.8`` makes it explicit for bodies too; ``= None`` leaves bodies
    their own again and particles the book's 0."""
    ground = pm.Ground()
    ground.friction = 0.8
    ground.restitution = 0.2
    assert (ground.body_friction, ground.body_restitution) == (0.8, 0.2)
    assert (ground.friction, ground.restitution) == (0.8, 0.2)
    ground.friction = None
    ground.restitution = None
    assert (ground.friction, ground.restitution) == (0.0, 0.5)
    assert (ground.body_friction, ground.body_restitution) == (None, None)


def test_adding_a_rigid_shape_as_a_generator_says_what_to_do():
    """``world.add(pm.Box(...))`` (the old name of the particle container) names add_body and
    pm.BoxContainer."""
    with pytest.raises(TypeError, match=r"add_body.*pm\.BoxContainer"):
        pm.World().add(pm.Box((1.0, 1.0, 1.0)))
