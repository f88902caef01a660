"""Handles and joints belong to their world, and odd values get one line naming the parameter
(issue 31, item 4): each of these was accepted, or failed with an unrelated message, before."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.forces import BodySpring
from pointmass.rigid.joints import BallJoint
from pointmass.rigid.shapes import Box, Sphere

#: The solver's tuning numbers as World() has them (``pm.SolverSettings``)
DEFAULTS = pm.SolverSettings()

DT = 1 / 60


def _two_bodies(world: pm.World):
    return (world.add_body(Sphere(0.5), (0, 1, 0)), world.add_body(Sphere(0.5), (1.2, 1, 0)))


def test_a_body_handle_of_another_world_is_refused_even_where_its_index_exists():
    here, there = pm.World(), pm.World()
    mine = _two_bodies(here)
    foreign = _two_bodies(there)
    with pytest.raises(ValueError, match="body is a Body of another world"):
        here.bodies.add_force(foreign[0], (1, 0, 0))
    with pytest.raises(ValueError, match="body_a is a Body of another world"):
        here.add(BallJoint(foreign[0], (0.6, 0, 0), mine[1]))
    with pytest.raises(ValueError, match="body_b is a Body of another world"):
        here.add(BodySpring(mine[0], (0, 0, 0), foreign[1], (0, 0, 0), 10.0, 1.0))
    assert not here.joints and not here.body_forces
    assert np.array_equal(here.bodies.force, np.zeros((2, 3)))
    here.bodies.add_force(mine[0], (1, 0, 0))  # its own handle still works


def test_a_particle_handle_of_another_world_is_refused():
    here, there = pm.World(), pm.World()
    here.add_particle()
    there.add_particle()
    with pytest.raises(ValueError, match="particle is a Particle of another world"):
        here.particles.set_mass(there.particles[0], 2.0)
    assert here.particles[0].mass == 1.0


def test_a_joint_whose_body_a_restore_dropped_does_not_bind_to_the_next_body():
    """Body 1 is dropped by a restore and a box takes index 1: the joint used to hold the box
    instead; now the step is refused naming the joint, and so is the stale handle."""
    world = pm.World()
    a = world.add_body(Sphere(0.5), (0, 1, 0))
    snap = world.bodies.snapshot()
    b = world.add_body(Sphere(0.5), (1.2, 1, 0))
    world.add(BallJoint(a, (0.6, 0, 0), b))
    world.bodies.restore(snap)
    world.add_body(Box((0.2, 0.2, 0.2)), (3, 1, 0))
    with pytest.raises(IndexError, match=r"BallJoint 0 \(body_b = 1\) lost its body.*another "
                                         r"body has its index now"):
        world.step(DT)
    with pytest.raises(ValueError, match="stale Body handle: body 1 was dropped"):
        world.bodies.add_force(b, (1, 0, 0))


def test_one_joint_cannot_be_in_two_worlds_but_may_move_after_removal():
    first, second = pm.World(), pm.World()
    _two_bodies(first)
    _two_bodies(second)
    joint = first.add(BallJoint(0, (0.6, 0, 0), 1))
    with pytest.raises(ValueError, match="already in another world"):
        second.add(joint)
    first.remove(joint)
    second.add(joint)
    second.step(DT)
    assert joint.separation() < 1e-3


@pytest.mark.parametrize(("make", "message"), [
    (lambda: Sphere(1e300), r"radius must be in \[1e-09, 1e\+09\], got 1e\+300"),
    (lambda: Sphere(1e-300), r"radius must be in \[1e-09, 1e\+09\], got 1e-300"),
    (lambda: Box((1.0, 1e-300, 1.0)), r"half_extents must each be in \[1e-09, 1e\+09\] m"),
])
def test_shape_sizes_that_overflow_or_vanish_name_the_parameter(make, message):
    """Sphere(1e300) raised OverflowError (34, ...); Sphere(1e-300) said "inertia must be
    three principal moments" though none was given."""
    with pytest.raises(ValueError, match=message):
        make()


def test_the_soft_step_refuses_a_velocity_too_large_to_square():
    """The soft step checks what it leaves (``body_soft._refuse_blow_up``): the step itself
    raises, naming the body and its velocity, before anything reads the energy (the impulses
    stage left it to ``StepStats.kinetic_energy``, which raised numpy's "zero-size array to
    reduction operation maximum" in a world of bodies alone, then "kinetic energy
    overflowed")."""
    world = pm.World(gravity=(0, 0, 0))
    world.add_body(Sphere(1.0), velocity=(1e200, 0, 0))
    with pytest.raises(FloatingPointError, match=r"body 0 .*1e\+200"):
        world.step(DT)


def test_a_spin_past_the_bound_raises_instead_of_becoming_zero():
    """|ω| = 1e300 rad/s was scaled by cap/inf to exactly 0 with no word; now the step raises
    naming the body. A finite spin past the cap is still slowed to it: π/4 per integration
    step of the body stage (README's rigid section), h = dt/SUBSTEPS (188.5 rad/s at dt 1/60;
    a sphere spins torque-free, so its |ω| stays there)."""
    world = pm.World(gravity=(0, 0, 0))
    body = world.add_body(Box((0.1, 0.2, 0.3)), angular_velocity=(1e300, 0, 0))
    with pytest.raises(FloatingPointError, match=r"body 0 spins too fast.*1e\+300"):
        world.step(DT)
    assert body.angular_velocity[0] == 1e300
    world = pm.World(gravity=(0, 0, 0))
    body = world.add_body(Sphere(0.3), angular_velocity=(0, 1000.0, 0))
    world.step(DT)
    kicks = DEFAULTS.soft_substeps
    assert np.linalg.norm(body.angular_velocity) == pytest.approx(0.25 * math.pi * kicks / DT)
