"""Issue 13's acceptance scenes for rigid contacts (dt = 1/60, g = 9.81, unit boxes of 1 kg).

Measured when written (one substep unless named): resting box 2e-13 m off its height; slide
−0.82 % short of v0²/(2μg) (the semi-implicit step's −v0·dt/2; −0.20 % at 4 substeps); incline
9e-8 m of drift in 10 s; rolling 5/7·v0 to 1e-15; corner bounce −e to 1e-5; 10-box tower
2e-10 m.
"""

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.quaternion import quat_from_axis_angle, quat_mul
from pointmass.rigid.shapes import Box, Sphere

#: The solver's tuning numbers as World() has them (``pm.SolverSettings``)
DEFAULTS = pm.SolverSettings()

G = 9.81
DT = 1 / 60
HALF = (0.5, 0.5, 0.5)


def _world(mu=0.5, e=0.0, normal=(0.0, 1.0, 0.0), substeps=1):
    world = pm.World(gravity=(0.0, -G, 0.0), substeps=substeps)
    world.add(pm.Plane(normal, 0.0, restitution=e, friction=mu))
    return world


def test_box_dropped_flat_comes_to_rest_within_a_millimetre_for_10_s():
    world = _world()
    box = world.add_body(Box(HALF), (0.0, 0.8, 0.0), mass=1.0)
    for _ in range(60):
        world.step(DT)
    heights = []
    for _ in range(600):
        world.step(DT)
        heights.append(box.position[1])
    assert np.abs(np.array(heights) - 0.5).max() < 1e-3
    assert np.abs(box.velocity).max() < 1e-6


@pytest.mark.parametrize(("v0", "mu", "substeps"), [(10.0, 0.5, 1), (10.0, 0.3, 4)])
def test_sliding_box_stops_after_v0_squared_over_2_mu_g(v0, mu, substeps):
    world = _world(mu, substeps=substeps)
    box = world.add_body(Box(HALF), (0.0, 0.5, 0.0), mass=1.0, friction=mu,
                         velocity=(v0, 0.0, 0.0))
    for _ in range(round(1.5 * v0 / (mu * G) / DT)):
        world.step(DT)
    assert abs(box.velocity[0]) < 1e-4
    assert box.position[0] == pytest.approx(v0**2 / (2 * mu * G), rel=0.01)
    assert box.position[1] == pytest.approx(0.5, abs=1e-4)  # it did not tip


def _on_incline(theta, mu):
    normal = (-math.sin(theta), math.cos(theta), 0.0)
    world = _world(mu, normal=normal)
    start = 0.5 * np.array(normal)
    q = quat_from_axis_angle(np.array([0.0, 0.0, 1.0]), theta)
    return world, world.add_body(Box(HALF), start, q, mass=1.0, friction=mu), start


def test_box_holds_still_on_an_incline_below_the_friction_angle():
    theta, mu = math.radians(20.0), 0.5  # tan θ = 0.36 < μ
    world, box, start = _on_incline(theta, mu)
    for _ in range(600):
        world.step(DT)
    assert np.linalg.norm(box.position - start) < 1e-3


def test_box_slides_down_a_steep_incline_at_g_sin_minus_mu_cos():
    theta, mu = math.radians(35.0), 0.5  # tan θ = 0.70 > μ
    world, box, _ = _on_incline(theta, mu)
    for _ in range(60):
        world.step(DT)
    v1 = box.velocity.copy()
    for _ in range(60):
        world.step(DT)
    accel = np.linalg.norm(box.velocity - v1)
    assert accel == pytest.approx(G * (math.sin(theta) - mu * math.cos(theta)), rel=1e-3)


def test_sliding_sphere_ends_rolling_at_five_sevenths():
    v0, r = 5.0, 0.5
    world = _world(0.3)
    ball = world.add_body(Sphere(r), (0.0, r, 0.0), mass=1.0, friction=0.3,
                          velocity=(v0, 0.0, 0.0))
    for _ in range(300):
        world.step(DT)
    assert ball.velocity[0] == pytest.approx(5 / 7 * v0, rel=1e-6)
    assert -ball.angular_velocity[2] * r == pytest.approx(5 / 7 * v0, rel=1e-6)  # rolling


def _lowest_corner(box):
    rot = world_rotation(box.orientation)
    corners = [box.position + rot @ (0.5 * np.array([(k & 1) * 2 - 1, (k >> 1 & 1) * 2 - 1,
                                                     (k >> 2 & 1) * 2 - 1]))
               for k in range(8)]
    return min(corners, key=lambda c: c[1])


@pytest.mark.parametrize("mu", [0.0, 0.5])
def test_box_dropped_on_a_corner_bounces_with_minus_e(mu):
    """A box falls from rest onto one corner (e = 0.5) and leaves the floor with −e times the
    corner's speed: the soft step bounces the speed it touches with (``body_soft.restitution``),
    read from the substeps' half-step velocities: v₀² = v² + 2·g·gap from the velocity v a
    substep drifts with, which lags √(2gH) by g·h/2 at depth H (v² + g·h·v = 2·g·H, h = dt/4);
    and the step reports its velocity at its end, half a substep of gravity after the bounce
    (``body_soft``, "Leapfrog"): −e·v₀ − g·h/2 (measured within 6e-6 of it): to 1e-4."""
    e = 0.5
    world = pm.World(gravity=(0.0, -G, 0.0))
    world.add(pm.Plane((0.0, 1.0, 0.0), 0.0, restitution=e, friction=mu))
    q = quat_mul(quat_from_axis_angle(np.array([1.0, 0.0, 0.0]), math.atan(1 / math.sqrt(2))),
                 quat_from_axis_angle(np.array([0.0, 0.0, 1.0]), math.pi / 4))
    box = world.add_body(Box(HALF), (0.0, 2.0, 0.0), q, mass=1.0, friction=mu, restitution=e)
    fall = _lowest_corner(box)[1]  # the corner's height above the floor [m]
    for _ in range(200):
        before = box.point_velocity(_lowest_corner(box))[1]
        stats = world.step(DT)
        after = box.point_velocity(_lowest_corner(box))[1]
        if after > 0.0:
            break
    assert stats.body_contacts == 1  # on one corner
    assert before < -4.0
    gh = G * DT / DEFAULTS.soft_substeps
    touch = 0.5 * (-gh + math.sqrt(gh * gh + 8.0 * G * fall))
    assert after == pytest.approx(e * touch - gh / 2, rel=1e-4)


def _tower(n=10, sliding=False):
    world = _world(0.5)
    boxes = [world.add_body(Box(HALF), (0.0, 0.5 + k, 0.0), mass=1.0, friction=0.5)
             for k in range(n)]
    if sliding:
        world.add_body(Box(HALF), (3.0, 0.5, 0.0), mass=1.0, velocity=(-2.0, 0.0, 1.0))
    return world, boxes


def test_tower_of_ten_boxes_stands_with_the_top_within_a_millimetre():
    world, boxes = _tower()
    for _ in range(600):
        world.step(DT)
    assert np.linalg.norm(boxes[-1].position - (0.0, 9.5, 0.0)) < 1e-3
    assert np.abs(world.bodies.velocity).max() < 1e-3


def test_reruns_are_bit_identical():
    runs = []
    for _ in range(2):
        world, _ = _tower(5, sliding=True)
        for _ in range(120):
            world.step(DT)
        runs.append(np.concatenate([world.bodies.position.ravel(),
                                    world.bodies.orientation.ravel(),
                                    world.bodies.angular_velocity.ravel()]).tobytes())
    assert runs[0] == runs[1]
