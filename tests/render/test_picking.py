"""Picking particles with a ray, without GL."""

from __future__ import annotations

import numpy as np

import pointmass as pm
from pointmass.render.picking import pick_particle


def _scene():
    world = pm.World()
    world.add_particle((0.0, 0.0, 0.0), radius=0.5)
    world.add_particle((0.0, 0.0, -5.0), radius=1.0)
    world.add_particle((3.0, 0.0, 0.0))            # radius 0: picked with point_radius
    return pm.Scene(world, point_radius=0.2)


def test_nearest_hit_wins():
    """Of two spheres on the ray, the nearer one is picked."""
    assert pick_particle(_scene(), (0, 0, 10), (0, 0, -1)) == 0


def test_miss_returns_none():
    assert pick_particle(_scene(), (0, 5, 10), (0, 0, -1)) is None


def test_point_particle_uses_drawn_radius():
    """A radius-0 particle is hit within point_radius of its centre, not outside it."""
    scene = _scene()
    assert pick_particle(scene, (3.15, 0, 10), (0, 0, -1)) == 2
    assert pick_particle(scene, (3.25, 0, 10), (0, 0, -1)) is None


def test_hidden_particles_are_not_picked_and_behind_is_ignored():
    scene = _scene()
    scene.hidden = np.array([True, False, False])
    assert pick_particle(scene, (0, 0, 10), (0, 0, -1)) == 1
    assert pick_particle(scene, (0, 0, 10), (0, 0, 1)) is None     # all behind the origin


def test_empty_world():
    assert pick_particle(pm.Scene(pm.World()), (0, 0, 0), (0, 0, 1)) is None


def test_pick_body_hits_the_nearest_box_or_sphere_at_its_surface():
    """Ray against rigid bodies: a turned box by its faces, a sphere by its surface; the
    nearer one wins; a miss is None."""
    import math

    import pytest

    import pointmass as pm
    from pointmass.render.picking import pick_body
    from pointmass.rigid.quaternion import quat_from_axis_angle
    from pointmass.rigid.shapes import Box, Sphere

    world = pm.World()
    turned = quat_from_axis_angle(np.array([0.0, 1.0, 0.0]), math.pi / 4)
    world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 1.0, 0.0), turned)
    world.add_body(Sphere(0.5), (0.0, 1.0, -3.0))
    index, point, _ = pick_body(world, (0.0, 1.0, 5.0), (0.0, 0.0, -1.0))
    assert index == 0                                   # the box is in front of the sphere
    assert point[2] == pytest.approx(0.5 * math.sqrt(2.0))   # its front edge, turned 45°
    index, point, _ = pick_body(world, (0.0, 1.0, -10.0), (0.0, 0.0, 1.0))
    assert index == 1 and point[2] == pytest.approx(-3.5)
    assert pick_body(world, (5.0, 5.0, 5.0), (0.0, 1.0, 0.0)) is None
