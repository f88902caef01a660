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
