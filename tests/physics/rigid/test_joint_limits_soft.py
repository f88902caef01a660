"""Joint limits and a hinge's locks in the soft step (``World()``'s body stage) under loads far
larger than their own bones' weight: the ragdoll demo, thrown down and left 4.5 s, must pass its own
check (limits within 0.5° of their stops at rest, 3° in the fall, at rest by 4 s; the impulses stage
before it failed it in 6 of seeds 0–19), and a light lever held at its stop (or on its hinge's axis)
by a heavy weight must not give.

The tree's angular rows are rigid rows solved through the tree (``solver/joint_soft.py``,
"Angular rows"). Before (main at a17b885: Box2D's soft rows, sprung with their own two bones'
inertia beside the tree), a row gave by its load over its spring: the ragdoll's seeds 1, 4, 5
rested 2.35°, 2.98°, 0.71° past their stops and fell to 4.35°, 4.11°, 3.32° (an elbow's lock
carrying 14 N·m from the torso lying on the arm, sprung at I·ω² = 347 N·m/rad, rested 2.35°
off its axis); the levers below rested 5.6° past the stop and 19.5° off the hinge's axis.
Measured now: seeds 0–19 rest within 0.08° and fall within 1.7°, at rest
by 4.5 s (< 0.018 m/s; seed 5's head, swinging on its neck's cone at 0.9 m/s at 2.6 s, is the
slowest to settle); main's soft step failed 10 of those 20 checks; the levers hold to
< 1e-12°."""

import math

import pytest

import pointmass as pm
from pointmass.demo import load_demo
from pointmass.rigid.joints import BallJoint, HingeJoint
from pointmass.rigid.shapes import Box, Sphere


#: Seed 7 landed (from stop 38 to 41) with its chest held 2–3 cm above the ground and its head
#: on the rim of its neck's 40° cone, where it swung along the rim, damped only by the joint's
#: 0.2 N·m friction (0.11 m/s at 4.5 s, asleep by 8.5 s): an xfail until the leapfrog's start
#: (stop 42: a body's first step opens with a half kick), since which it lands otherwise and
#: passes; the class (a head on a frictionless limit's rim) is not gone.
@pytest.mark.slow
@pytest.mark.parametrize("seed", range(10))
def test_the_ragdoll_rests_within_its_limits_in_the_soft_step(seed):
    demo = load_demo("ragdoll")
    sim = pm.Simulation(demo, overrides=[f"seed={seed}"])
    for _ in range(round(4.5 * 30)):
        sim.advance(1 / 30)
    sim.check()


def _lever(axis, limits) -> pm.World:
    """A 1 m, 0.2 kg lever hinged to the world at its end (level along +x), a 20 kg ball hung
    0.3 m below its tip by a ball joint: 196 N·m at the hinge, 100 times the lever's weight."""
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    arm = world.add_body(Box((0.5, 0.02, 0.02)), (0.5, 0.0, 0.0), mass=0.2)
    world.add(HingeJoint(arm, (-0.5, 0.0, 0.0), axis=axis, limits=limits))
    load = world.add_body(Sphere(0.1), (1.0, -0.3, 0.0), mass=20.0)
    world.add(BallJoint(load, (0.0, 0.3, 0.0), arm))
    return world


@pytest.mark.parametrize("axis, limits", [((0.0, 0.0, 1.0), (0.0, 1.0)),
                                          ((1.0, 0.0, 0.0), None)],
                         ids=["at its stop", "on its axis"])
def test_a_light_lever_holds_a_heavy_weight_without_giving(axis, limits):
    """At its stop (hinge about z, the stop level) the limit carries the weight's moment; on a
    hinge about the lever's own axis the two locks do. A rigid row gives nothing whatever the
    load (Soft rows gave 5.6° and 19.5° at rest, 6.4° and 45° at worst: a spring of the lever's
    own inertia)."""
    world = _lever(axis, limits)
    for _ in range(120):
        world.step(1 / 60)
        assert world.joints.angular_errors(world.bodies).max() < math.radians(0.01)
    assert abs(world.bodies.position[0, 1]) < 1e-6  # the lever is level
    assert world.joints.separations().max() < 1e-6
