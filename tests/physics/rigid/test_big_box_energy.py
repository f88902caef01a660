"""A big box dropped on another (the fracture demo's parts: 4 m side, 12.5 kg, μ 0.9, e 0.2)
never gains energy and comes to rest.

Contacts only take energy out (restitution e < 1, friction, the projection moves no
velocities), and a semi-implicit step of free fall loses ½·m·g²·dt² a step, so kinetic plus
potential energy may never rise above its start. The flat drop over the lower box's corner,
spinning about the vertical, is the case that broke: the box lands on a face (a manifold of
four points with twist friction), then tips over the corner onto one point. Each point kept a
share of the face's twist for its warm start; the one point left has no twist row to revise
it, so the share was applied and kept again every step and spun the box up (before the fix,
``body_manifolds.gather_friction``: +593 J on 1.06 kJ from this 0.5 m drop, +18.6 kJ when set
down on the lower box without a gap).
"""

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.shapes import Box
from pointmass.solver.body_manifolds import gather_friction

G = 9.81
HALF = 2.0
MASS = 12.5
SURFACE = {"friction": 0.9, "restitution": 0.2}
DT = 1 / 60
#: Energy may rise by float noise only [J] (the boxes hold ~1 kJ).
NOISE = 1e-6


def _energy(bodies) -> float:
    """Kinetic (linear and rotational) plus potential energy of all bodies [J]."""
    total = 0.0
    for i in range(bodies.count):
        m = 1.0 / bodies.inv_mass[i]
        turn = world_rotation(bodies.orientation[i])
        inertia = turn @ np.diag(1.0 / bodies.inv_inertia[i]) @ turn.T
        v, w = bodies.velocity[i], bodies.angular_velocity[i]
        total += 0.5 * m * v @ v + 0.5 * w @ inertia @ w + m * G * bodies.position[i, 1]
    return total


def _drop(offset, tilt, spin, gap, sleep):
    """Box B (turned by ``tilt`` [rad] about (1, 0, −1), spinning at ``spin`` [rad/s] about the
    vertical) with its lowest corner ``gap`` [m] above box A, its centre at (offset, ·, offset)."""
    world = pm.World(gravity=(0.0, -G, 0.0), sleep=sleep)
    world.add(pm.Ground(**SURFACE))
    world.add_body(Box((HALF,) * 3), (0.0, HALF, 0.0), mass=MASS, **SURFACE)
    axis = np.array([1.0, 0.0, -1.0]) / math.sqrt(2.0)
    quat = np.array([math.cos(tilt / 2), *(math.sin(tilt / 2) * axis)])
    low = np.abs(world_rotation(quat)[1]) @ np.full(3, HALF)
    world.add_body(Box((HALF,) * 3), (offset, 2 * HALF + gap + low, offset), quat, mass=MASS,
                   angular_velocity=(0.0, spin, 0.0), **SURFACE)
    return world


@pytest.mark.parametrize("offset, tilt, spin, sleep", [
    (2.2, 0.0, 1.0, True),   # flat, spinning, over the corner: tips onto one point
    (2.2, 0.0, 1.0, False),
    (0.8, 0.4, 0.0, True),   # tilted, lands on an edge of the lower box's top
    (1.5, 0.8, 2.0, True),
])
def test_a_big_box_dropped_on_another_never_gains_energy_and_rests(offset, tilt, spin, sleep):
    world = _drop(offset, tilt, spin, gap=0.5, sleep=sleep)
    bodies = world.bodies
    start = _energy(bodies)
    worst = -math.inf
    for _ in range(600):  # 10 s
        world.step(DT)
        worst = max(worst, _energy(bodies) - start)
    assert worst <= NOISE, f"energy rose {worst:.3f} J above its start ({start:.1f} J)"
    assert _energy(bodies) < start - 10.0  # it did fall and lose something
    speed = np.hypot(np.linalg.norm(bodies.velocity, axis=1),
                     HALF * np.linalg.norm(bodies.angular_velocity, axis=1)).max()
    assert speed < 1e-3, f"still moving at {speed:.4f} m/s after 10 s"
    bottoms = [bodies.position[i, 1] - np.abs(world_rotation(bodies.orientation[i])[1])
               @ bodies.size[i] for i in range(bodies.count)]
    assert min(bottoms) > -0.01


def test_warm_start_carries_no_twist_or_friction_that_no_row_revises():
    """Three manifolds: one point (no twist row), four points with μ > 0 and four with μ = 0;
    each point kept (1, 2, 3): tangents and twist are gathered only where a row solves them."""
    n = np.tile([0.0, 1.0, 0.0], (9, 1))
    start = np.array([0, 1, 5, 9])
    t1 = np.tile([1.0, 0.0, 0.0], (3, 1))
    t2 = np.tile([0.0, 0.0, 1.0], (3, 1))
    kept = np.tile([1.0, 2.0, 3.0], (9, 1))
    mu = np.array([0.9, 0.9, 0.0])
    radius = np.array([0.0, 2.8, 2.8])
    mass_tw = np.full(3, 10.0)
    jt1, jt2, jtw = np.empty(3), np.empty(3), np.empty(3)
    gather_friction(start, n, t1, t2, mu, radius, mass_tw, kept, jt1, jt2, jtw)
    assert list(jt1) == [1.0, 4.0, 0.0]
    assert list(jt2) == [3.0, 12.0, 0.0]
    assert list(jtw) == [0.0, 8.0, 0.0]
