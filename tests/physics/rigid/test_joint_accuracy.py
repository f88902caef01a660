"""Issue 26, acceptance point 6: joints that hold and keep energy. Ball-joint and hinge
pendulums and a double pendulum of two boxes, no damping, ``World()`` defaults, dt = 1/60,
20 s each: the joint gap < 0.5 mm and the energy within ±0.5 % at every step.

The energy is measured as a fraction of the energy the swing moves (m·g·L for a pendulum
released level, whose total is 0 with the potential's zero at the pivot): a pendulum released
level has no other scale.

``World()`` (the soft step, leapfrog over 4 substeps) meets both: gap < 0.1 µm, energy
−0.0063 … 0 % (single pendulums), −0.027 … 0 % (double). Semi-implicit
Euler, its integrator before stop 42, swung it ±0.57 % (−0.89 … +0.77 % double): first order.

The impulses stage before the soft step (removed at stop 44) held the gap under 1e-9 m but
swung KE + PE by semi-implicit Euler's own first-order error at h = dt: −2.2 … +2.5 % (box),
−2.8 … +3.1 % (double); the issue's ±0.5 % took it 8 substeps.
"""

import functools
import math

import pytest

import pointmass as pm
from pointmass.rigid.joints import BallJoint, HingeJoint
from pointmass.rigid.shapes import Box, Sphere

DT = 1 / 60
G = 9.81
STEPS = 1200  # 20 s
#: The issue's targets.
GAP = 0.5e-3
ENERGY = 0.005


def _pendulum(joint: str, shape: str, substeps: int = 1):
    """1 kg on a 1 m arm from a world anchor at the origin, released level (along +x)."""
    world = pm.World(gravity=(0.0, -G, 0.0), substeps=substeps)
    body = world.add_body(Box((0.1, 0.1, 0.1)) if shape == "box" else Sphere(0.1),
                          (1.0, 0.0, 0.0), mass=1.0)
    if joint == "ball":
        world.add(BallJoint(body, (-1.0, 0.0, 0.0)))
    else:
        world.add(HingeJoint(body, (-1.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0)))
    return world, 1.0 * G * 1.0


def _double(substeps: int = 1):
    """Two 1 kg boxes 0.5 m long on ball joints: the upper one level from the world anchor at
    the origin, the lower one hanging from its tip bent 45° below it; the energy it moves is
    its height above both boxes hanging straight down."""
    world = pm.World(gravity=(0.0, -G, 0.0), substeps=substeps)
    upper = world.add_body(Box((0.25, 0.05, 0.05)), (0.25, 0.0, 0.0), mass=1.0)
    bend = math.radians(-45.0)
    lower = world.add_body(Box((0.25, 0.05, 0.05)),
                           (0.5 + 0.25 * math.cos(bend), 0.25 * math.sin(bend), 0.0),
                           (math.cos(bend / 2), 0.0, 0.0, math.sin(bend / 2)), mass=1.0)
    world.add(BallJoint(upper, (-0.25, 0.0, 0.0)))
    world.add(BallJoint(lower, (-0.25, 0.0, 0.0), upper))
    return world, world.potential_energy() - (-G * 0.25 - G * 0.75)


def _swing(world, scale):
    """20 s: the largest joint gap [m] and the energy's band as a fraction of ``scale`` (low,
    high)."""
    e0 = world.kinetic_energy() + world.potential_energy()
    gap, band = 0.0, [0.0, 0.0]
    for _ in range(STEPS):
        world.step(DT)
        gap = max(gap, float(world.joints.separations().max()))
        x = (world.kinetic_energy() + world.potential_energy() - e0) / scale
        band[0], band[1] = min(band[0], x), max(band[1], x)
    return gap, band


SCENES = {
    "ball box": lambda s=1: _pendulum("ball", "box", s),
    "ball sphere": lambda s=1: _pendulum("ball", "sphere", s),
    "hinge box": lambda s=1: _pendulum("hinge", "box", s),
    "double": _double,
}
@functools.cache
def _result(name: str, substeps: int = 1):
    """Each scene is run once per substep count, shared by the tests that read it."""
    return _swing(*SCENES[name](substeps))


def _leapfrog_band(inertia: float, substeps: int = 4) -> tuple[float, float]:
    """The energy band (low, high; fractions of m·g·L) that leapfrog at h = dt/``substeps``
    (the soft step's integrator: half kick, drift, half kick) gives the exact pendulum of
    these scenes in its angle (1 kg, L = 1 m, ``inertia`` [kg·m²] about the centre, released
    level), over the same 20 s, read at every step: what the integrator itself swings by,
    whatever the joints do (semi-implicit Euler's at the same h: ±0.57 %)."""
    h = DT / substeps
    moment = inertia + 1.0
    theta = omega = 0.0
    low = high = 0.0
    for n in range(STEPS * substeps):
        omega += 0.5 * h * G * math.cos(theta) / moment
        theta += h * omega
        omega += 0.5 * h * G * math.cos(theta) / moment
        if (n + 1) % substeps == 0:
            e = (0.5 * moment * omega * omega - G * math.sin(theta)) / G
            low, high = min(low, e), max(high, e)
    return low, high


#: The bodies' inertia about their centre [kg·m²]: a 0.2 m cube and a 0.1 m sphere of 1 kg.
INERTIA = {"ball box": 0.08 / 12, "ball sphere": 0.4 * 0.01, "hinge box": 0.08 / 12}
#: The double pendulum's energy band with the soft step (measured; a ratchet: the issue's
#: target is ±0.5 %; semi-implicit Euler, before the leapfrog, swung it −0.89 … +0.77 %).
SOFT_DOUBLE = (-0.00028, 0.0)


@pytest.mark.parametrize("name", list(SCENES))
def test_the_joints_stay_shut_and_the_energy_is_the_integrators(name):
    """The soft step (4 substeps of leapfrog; the tree's joints aim at the pose each substep
    ends in and are relaxed in it): gap < 0.5 mm (measured < 0.1 µm); the single pendulums'
    energy swings as leapfrog at h = dt/4 swings the exact pendulum in its angle (measured
    −0.0063 … 0 % against its −0.0035 … 0 %): the joints add next to nothing to the
    integrator's error, and lose nothing over 20 s."""
    gap, band = _result(name)
    assert gap < GAP
    if name == "double":
        low, high = SOFT_DOUBLE
        assert band[0] >= low - 0.0001
        assert band[1] <= high + 0.0001
        return
    low, high = _leapfrog_band(INERTIA[name])
    assert band[0] == pytest.approx(low, abs=0.0001)
    assert band[1] == pytest.approx(high, abs=0.0001)


@pytest.mark.parametrize("name", list(SCENES))
def test_issue_26_point_6_energy_at_the_defaults(name):
    """Issue 26 point 6 at ``World()``'s defaults: gap < 0.5 mm, energy within ±0.5 % at every
    step over 20 s (measured: −0.0063 % … 0 single, −0.027 % … 0 double; semi-implicit Euler
    before the leapfrog: ±0.57 %, double −0.89 … +0.77 %)."""
    gap, band = _result(name)
    assert gap < GAP
    assert -ENERGY <= band[0] and band[1] <= ENERGY


@pytest.mark.slow
@pytest.mark.parametrize("name", list(SCENES))
def test_with_eight_substeps_the_energy_is_within_half_a_percent(name):
    """The issue's target with the soft step once the integrator's own error allows it:
    ``World(substeps=2)``, 8 soft substeps of dt/8. Gap < 0.5 mm, energy within ±0.5 %."""
    gap, band = _result(name, 2)
    assert gap < GAP
    assert -ENERGY <= band[0] and band[1] <= ENERGY
