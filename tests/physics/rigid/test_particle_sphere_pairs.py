"""A particle with a radius touching a sphere body touches it along their centres, as two sphere
bodies do (``solver/body_soft.normals``, ``CENTRES``): in the soft step's packed view a
particle is a sphere of its radius (``rigid/particle_body.Packed``), so a frictionless push
passes through the body's centre and spins it not at all, and both momenta are kept exactly.

Before (stop 45's main), a particle row was not "round": its normal stayed as the collision
found it and its push acted between the two collision points carried along by the centres,
off the body's centre once the two had slid past each other within a step. Measured then, a
0.5 kg particle (r 0.1) passing a frictionless 1 kg sphere body (r 0.5) 0.4 m off its line in
zero gravity left it spinning at 0.0068 / 0.042 / 0.28 rad/s at 1 / 2 / 5 m/s, and a rain of
40 frictionless particles onto a frictionless sphere body spun it up to 0.59 rad/s."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.shapes import Sphere

DT = 1.0 / 60.0


def _momenta(world) -> tuple[np.ndarray, np.ndarray]:
    """Linear momentum and angular momentum about the origin of bodies and particles."""
    b, p = world.bodies, world.particles
    mb, mp = 1.0 / b.inv_mass, 1.0 / p.inv_mass
    linear = (mb[:, None] * b.velocity).sum(axis=0) + (mp[:, None] * p.velocity).sum(axis=0)
    spin = sum(np.linalg.solve(b.inv_inertia_world[i], b.angular_velocity[i])
               for i in range(b.count))
    orbit = (np.cross(b.position, mb[:, None] * b.velocity).sum(axis=0)
             + np.cross(p.position, mp[:, None] * p.velocity).sum(axis=0))
    return linear, orbit + spin


@pytest.mark.parametrize("speed", [1.0, 2.0, 5.0])
def test_a_particle_glancing_off_a_frictionless_sphere_body_spins_it_not(speed):
    """Zero gravity, e = 0.5: a 0.5 kg particle (r 0.1) at ``speed`` along x passes a 1 kg
    sphere body (r 0.5) at rest, 0.4 m off its line and 0.05 m off its plane. Afterwards the
    body has no spin, both momenta are as before, and the velocities are those of an
    instantaneous collision along the centres' line at first touch, within 1.5 % of the
    speed (measured 0.51 %, 0.37 %, 0.94 %; before, 0.62 %, 2.4 %, 5.6 % and a spin of 0,
    0.084 and 0.52 rad/s)."""
    e, mb, mp = 0.5, 1.0, 0.5
    xb, xp, vp = np.zeros(3), np.array([-2.0, 0.4, 0.05]), np.array([speed, 0.0, 0.0])
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.particle_friction = 0.0
    world.add_body(Sphere(0.5), tuple(xb), mass=mb, friction=0.0, restitution=e)
    world.add_particle(tuple(xp), velocity=tuple(vp), mass=mp, radius=0.1)
    p0, l0 = _momenta(world)
    for _ in range(round(4.0 / speed / DT)):
        world.step(DT)
    b, p = world.bodies, world.particles
    assert np.abs(b.angular_velocity).max() < 1e-12
    p1, l1 = _momenta(world)
    assert np.abs(p1 - p0).max() < 1e-12 * mp * speed
    assert np.abs(l1 - l0).max() < 1e-12 * np.abs(l0).max()
    d0 = xp - xb  # the ideal: an impulse along the centres' line where they first touch
    t = (-(d0 @ vp) - math.sqrt((d0 @ vp) ** 2 - (vp @ vp) * (d0 @ d0 - 0.6**2))) / (vp @ vp)
    n = (d0 + vp * t) / np.linalg.norm(d0 + vp * t)
    j = -(1.0 + e) * (vp @ n) / (1.0 / mb + 1.0 / mp)
    assert np.abs(b.velocity[0] - (-j * n / mb)).max() < 0.015 * speed
    assert np.abs(p.velocity[0] - (vp + j * n / mp)).max() < 0.015 * speed


def test_a_rain_of_frictionless_particles_on_a_sphere_body_does_not_spin_it():
    """40 frictionless particles (r 0.1, 0.1 kg) rained one after another onto a frictionless
    5 kg sphere body (r 0.5) on a frictionless ground, within 0.4 m of its top: every push
    passes through its centre, so it slides but never spins (before: up to 0.59 rad/s)."""
    rng = np.random.default_rng(3)
    world = pm.World()
    world.particle_friction = 0.0
    world.add(pm.Ground(friction=0.0))
    world.add_body(Sphere(0.5), (0.0, 0.5, 0.0), mass=5.0, friction=0.0, restitution=0.0)
    for k in range(40):
        x, z = rng.uniform(-0.4, 0.4, 2)
        world.add_particle((x, 1.3 + 0.25 * k, z), mass=0.1, radius=0.1)
    for _ in range(300):
        world.step(DT)
        assert np.abs(world.bodies.angular_velocity).max() < 1e-12
    # the particles pushed it: it slid off where it started
    assert np.linalg.norm(world.bodies.position[0, [0, 2]]) > 0.1


def test_a_particle_rests_in_the_groove_of_two_sphere_bodies_without_sinking():
    """A particle (r 0.3, 1 kg) set in the groove between two fixed 0.5 m sphere bodies 1.2 m
    apart comes to rest on both, its gap to each the centres' distance less the radii: within
    0.2 mm of touching, at rest."""
    world = pm.World(sleep=False)
    for x in (-0.6, 0.6):
        world.add_body(Sphere(0.5), (x, 0.5, 0.0), mass=math.inf, friction=0.5)
    y = 0.5 + math.sqrt(0.8**2 - 0.6**2)
    world.add_particle((0.0, y + 0.01, 0.0), mass=1.0, radius=0.3)
    for _ in range(120):
        world.step(DT)
    p = world.particles
    for i in (0, 1):
        gap = np.linalg.norm(p.position[0] - world.bodies.position[i]) - 0.8
        assert abs(gap) < 2e-4, gap
    assert np.linalg.norm(p.velocity[0]) < 1e-6
