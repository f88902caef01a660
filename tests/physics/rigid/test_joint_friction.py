"""Joint friction (``Joint(friction=τ)``, ``solver/joint_friction.py``): a joint resists its
bodies' relative turning with at most τ [N·m]. Checked against Coulomb's
law (a spin slowed at τ/I to a stop), conservation (a couple keeps linear and angular
momentum; the energy only falls) and statics (a pendulum comes to rest where gravity's torque
about the pivot is no more than τ)."""

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.joints import BallJoint, HingeJoint
from pointmass.rigid.shapes import Box, Sphere

DT = 1 / 60


@pytest.mark.parametrize("kind", ["ball", "hinge"])
def test_a_spin_on_a_joint_slows_at_torque_over_inertia_to_a_stop(kind):
    """A 1 kg ball of radius 0.5 m (I = 0.1 kg·m²) held at its centre, no gravity, spinning
    at 2 rad/s about the hinge's axis: friction 0.05 N·m slows it at 0.5 rad/s², so it turns
    at 1 rad/s after 2 s and stops at 4 s, and stays stopped."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    ball = world.add_body(Sphere(0.5), (0.0, 1.0, 0.0), mass=1.0)
    axis = (0.0, 0.0, 1.0)
    joint = BallJoint(ball, (0.0, 0.0, 0.0), friction=0.05) if kind == "ball" else \
        HingeJoint(ball, (0.0, 0.0, 0.0), axis=axis, friction=0.05)
    world.add(joint)
    ball.angular_velocity = (0.0, 0.0, 2.0)
    for _ in range(120):
        world.step(DT)
    assert ball.angular_velocity[2] == pytest.approx(1.0, abs=1e-9)
    for _ in range(150):
        world.step(DT)
    assert np.abs(ball.angular_velocity).max() < 1e-12
    assert np.abs(ball.position - (0.0, 1.0, 0.0)).max() < 1e-9


def test_a_joint_s_friction_keeps_both_momenta_and_only_takes_energy():
    """Two boxes joined end to end by a ball joint, no gravity, spinning and tumbling against
    each other: the friction is a couple, so Σp and Σ(x × p + I·ω) about the origin are kept
    (to round-off), the kinetic energy never rises, and their relative turning all but stops. (The
    impulses stage before the soft step lost 3e-4 of this pair's angular momentum with no
    friction at all: its position projection moved jointed bodies without their momenta.)"""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    a = world.add_body(Box((0.3, 0.1, 0.1)), (-0.3, 0.5, 0.2), mass=1.0)
    b = world.add_body(Box((0.3, 0.05, 0.15)), (0.3, 0.5, 0.2), mass=2.0)
    world.add(BallJoint(a, (0.3, 0.0, 0.0), b, friction=0.2))
    a.velocity = (0.1, 0.4, -0.2)
    a.angular_velocity = (3.0, -1.0, 2.0)
    b.angular_velocity = (-1.0, 0.5, 0.0)
    bodies = world.bodies

    def momenta():
        p = (bodies.velocity / bodies.inv_mass[:, None]).sum(axis=0)
        ell = sum(np.cross(bodies.position[k], bodies.velocity[k] / bodies.inv_mass[k])
                  + bodies.angular_momentum(k) for k in range(2))
        return p, ell

    p0, l0 = momenta()
    energy = bodies.kinetic_energy()
    for _ in range(300):
        world.step(DT)
        now = bodies.kinetic_energy()
        assert now <= energy * (1 + 1e-9)
        energy = now
    p1, l1 = momenta()
    assert np.abs(p1 - p0).max() <= 1e-9 * np.abs(p0).max()
    assert np.abs(l1 - l0).max() <= 1e-9 * np.abs(l0).max()
    # (from 4 rad/s: what remains is the splitting of one friction pass before the joint's
    # own solve, whose point impulses turn the two apart again by ~3e-4 rad/s a substep)
    assert np.abs(a.angular_velocity - b.angular_velocity).max() < 1e-3


@pytest.mark.parametrize("friction", [0.3, 1.0])
def test_a_pendulum_with_joint_friction_comes_to_rest_where_friction_holds_it(
                                                                               friction):
    """A 1 kg box on a 0.5 m arm from a hinge to the world, released level: gravity's torque
    about the pivot is m·g·L·cos θ; it swings down, loses energy every swing and stops where
    that torque is no more than τ (within 1.5° of hanging for τ = 0.3 N·m, 12° for 1 N·m),
    never rising."""
    g = 9.81
    world = pm.World(gravity=(0.0, -g, 0.0))
    box = world.add_body(Box((0.05, 0.05, 0.05)), (0.5, 0.0, 0.0), mass=1.0)
    world.add(HingeJoint(box, (-0.5, 0.0, 0.0), axis=(0.0, 0.0, 1.0), friction=friction))
    bodies = world.bodies

    def energy():
        return bodies.kinetic_energy() + g * float(bodies.position[0, 1])

    last = energy()
    for _ in range(round(30 / DT)):
        world.step(DT)
        now = energy()
        assert now <= last + 1e-6  # (the integrator's own energy error is below this)
        last = now
    assert np.abs(box.angular_velocity).max() < 1e-3
    hang = math.degrees(math.atan2(float(box.position[0]), -float(box.position[1])))
    most = math.degrees(math.asin(min(1.0, friction / (1.0 * g * 0.5))))
    assert abs(hang) <= most + 0.5


@pytest.mark.parametrize("value", [-0.1, float("nan"), float("inf"), "x"])
def test_a_joint_s_friction_must_be_a_finite_torque_of_zero_or_more(value):
    world = pm.World()
    body = world.add_body(Sphere(0.1), (0.0, 1.0, 0.0))
    with pytest.raises(ValueError, match="friction"):
        HingeJoint(body, (0.0, 0.0, 0.0), friction=value)
