"""Two spheres touch along their centres (``solver/body_soft.normals``, ``CENTRES``): the soft
step finds their normal again from the centres each substep, their gap as the centres'
distance less the radii, and pushes both at one point on that line. A frictionless push
passes through both centres, so it spins neither sphere, and it keeps linear and angular
momentum exactly.

Before (stop 44's main), the normal stayed as the collision found it and the push acted
between the two collision points carried along by the centres: two spheres sliding past
each other within a step were pushed off their centres. Measured then: two frictionless
spheres meeting at 1 m/s in a glancing collision came away spinning at 0.015 rad/s each
(0.05 rad/s at 2 m/s), a frictionless sphere sliding off another on the ground spun at 0.16
rad/s, and a frictionless pit of 1 000 sphere bodies spun up to 3.0 rad/s (1.6 now: the pour's
fast impacts, below).

Not a row a sweep found at a fast glancing pair's time of impact (its normal is the centres'
line then): that push still acts at one point, and a 10 m/s glancing collision still spins
two frictionless spheres at 0.76 rad/s (the module docstring of ``body_soft.normals``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.shapes import Sphere

DT = 1.0 / 60.0


def _momenta(bodies) -> tuple[np.ndarray, np.ndarray]:
    """Linear momentum and angular momentum about the origin (orbit and spin)."""
    m = 1.0 / bodies.inv_mass
    p = (m[:, None] * bodies.velocity).sum(axis=0)
    orbit = np.cross(bodies.position, m[:, None] * bodies.velocity).sum(axis=0)
    spin = sum(np.linalg.solve(bodies.inv_inertia_world[i], bodies.angular_velocity[i])
               for i in range(bodies.count))
    return p, orbit + spin


@pytest.mark.parametrize("speed", [0.3, 1.0, 2.0])
def test_a_glancing_collision_of_frictionless_spheres_spins_neither(speed):
    """Zero gravity, e = 0.5: a 2 kg sphere at ``speed`` along x passes a 1 kg one at rest,
    0.6 m off its line (radii 0.5): a glancing hit. Afterwards: no spin, both momenta as
    before, and the velocities those of the instantaneous collision along the centres' line
    at first touch (measured 0.10 %, 0.24 %, 0.73 % of the speed off it: the soft step's push
    follows the centres' line through the step of the hit; 0.07 %, 0.36 %, 0.34 % and
    0.0012, 0.015, 0.048 rad/s of spin before)."""
    e, ma, mb = 0.5, 1.0, 2.0
    pa, pb, vb = np.zeros(3), np.array([-3.0, 0.6, 0.1]), np.array([speed, 0.0, 0.0])
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.add_body(Sphere(0.5), tuple(pa), mass=ma, friction=0.0, restitution=e)
    world.add_body(Sphere(0.5), tuple(pb), mass=mb, friction=0.0, restitution=e,
                   velocity=tuple(vb))
    p0, l0 = _momenta(world.bodies)
    for _ in range(round(4.0 / speed / DT)):
        world.step(DT)
    b = world.bodies
    assert np.abs(b.angular_velocity).max() < 1e-12
    p1, l1 = _momenta(b)
    assert np.abs(p1 - p0).max() < 1e-12 * mb * speed
    assert np.abs(l1 - l0).max() < 1e-12 * np.abs(l0).max()
    # the ideal: an impulse along the centres' line where they first touch
    d0 = pb - pa
    t = (-(d0 @ vb) - math.sqrt((d0 @ vb) ** 2 - (vb @ vb) * (d0 @ d0 - 1.0))) / (vb @ vb)
    n = (d0 + vb * t) / np.linalg.norm(d0 + vb * t)
    j = -(1.0 + e) * (vb @ n) / (1.0 / ma + 1.0 / mb)
    assert np.abs(b.velocity[0] - (-j * n / ma)).max() < 0.015 * speed
    assert np.abs(b.velocity[1] - (vb + j * n / mb)).max() < 0.015 * speed


def test_a_frictionless_sphere_sliding_off_another_does_not_spin():
    """Two 1 m frictionless spheres, one on a frictionless ground and one set on top of it
    0.1 m off centre: the top one slides off, the two part. Neither spins (before: 0.16
    rad/s)."""
    world = pm.World()
    world.add(pm.Ground(friction=0.0))
    world.add_body(Sphere(0.5), (0.0, 0.5, 0.0), mass=1.0, friction=0.0, restitution=0.0)
    world.add_body(Sphere(0.5), (0.1, 1.5, 0.03), mass=1.0, friction=0.0, restitution=0.0)
    for _ in range(120):
        world.step(DT)
        assert np.abs(world.bodies.angular_velocity).max() < 1e-12
    # they slid apart, each its own way
    assert world.bodies.velocity[1, 0] > 0.5 > -0.5 > world.bodies.velocity[0, 0]


def test_a_sphere_rests_in_the_groove_of_two_without_sinking():
    """A 0.3 m sphere set in the groove between two fixed 0.5 m spheres 1.2 m apart comes to
    rest on both, its gap to each the centres' distance less the radii: within 0.2 mm of
    touching (the contacts' give under its weight), at rest."""
    world = pm.World(sleep=False)
    for x in (-0.6, 0.6):
        world.add_body(Sphere(0.5), (x, 0.5, 0.0), mass=math.inf, friction=0.5)
    y = 0.5 + math.sqrt(0.8**2 - 0.6**2)
    ball = world.add_body(Sphere(0.3), (0.0, y + 0.01, 0.0), mass=1.0, friction=0.5,
                          restitution=0.0)
    for _ in range(120):
        world.step(DT)
    b = world.bodies
    for i in (0, 1):
        gap = np.linalg.norm(b.position[ball.index] - b.position[i]) - 0.8
        assert abs(gap) < 2e-4, gap
    assert np.linalg.norm(b.velocity[ball.index]) < 1e-6
    assert np.abs(b.angular_velocity[ball.index]).max() < 1e-6
