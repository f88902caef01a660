"""Joints (``pointmass.rigid.joints``) against physics: a compound pendulum's period, a hanging
chain at rest, momentum of a freely tumbling jointed pair, limits under gravity, and the API's
checks (bad input, removal, restore, collision filtering, determinism)."""

import itertools
import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.joints import BallJoint, HingeJoint
from pointmass.rigid.shapes import Box

DT = 1 / 60
G = 9.81


def _pendulum(theta0: float, half=(0.1, 0.3, 0.05), d: float = 0.5, mass: float = 2.0):
    """A box hung from the world origin by a ball joint at its top, its centre d below the
    pivot, turned by theta0 about z."""
    world = pm.World(gravity=(0.0, -G, 0.0))
    pos = (d * math.sin(theta0), -d * math.cos(theta0), 0.0)
    turn = (math.cos(theta0 / 2), 0.0, 0.0, math.sin(theta0 / 2))
    body = world.add_body(Box(half), pos, turn, mass=mass)
    joint = world.add(BallJoint(body, (0.0, d, 0.0)))
    return world, body, joint


def _upward_crossings(t, x):
    return np.array([t[i - 1] + (-x[i - 1]) / (x[i] - x[i - 1]) * (t[i] - t[i - 1])
                     for i in range(1, len(x)) if x[i - 1] < 0.0 <= x[i]])


def test_a_box_on_a_ball_joint_swings_with_the_compound_pendulum_period():
    """Small swings: T = 2π√(I_pivot/(m·g·d)), I_pivot = m(a² + b²)/3 + m·d², within 1 %;
    the joint's points stay within 1 mm."""
    half, d, m = (0.1, 0.3, 0.05), 0.5, 2.0
    world, body, joint = _pendulum(0.05, half, d, m)
    expected = 2 * math.pi * math.sqrt((m * (half[0] ** 2 + half[1] ** 2) / 3 + m * d * d)
                                       / (m * G * d))
    t, x, gap = [], [], 0.0
    for _ in range(600):
        world.step(DT)
        t.append(world.time)
        x.append(body.position[0])
        gap = max(gap, joint.separation())
    period = np.diff(_upward_crossings(np.array(t), np.array(x))).mean()
    assert period == pytest.approx(expected, rel=0.01)
    assert gap < 1e-3


def test_a_large_swing_keeps_its_energy():
    """A 60° swing for 10 s: semi-implicit Euler's energy wobbles within a period, but the
    mean over each period stays where it was (within 1e-4 of the swing's energy; measured
    4e-6: the joints aim at the end pose, ``solver/joint_predict``, and take nothing, where
    the drift bias used to take 0.7 % a period), no later moment has more energy than the
    first period's peak (+1e-4 of the swing), and the joint stays shut (< 1 µm; measured
    2e-10 m)."""
    world, body, joint = _pendulum(math.radians(60))
    swing = 2.0 * G * 0.5 * (1 - math.cos(math.radians(60)))
    energy, x = [], []
    for _ in range(600):
        world.step(DT)
        energy.append(world.kinetic_energy() + world.potential_energy())
        x.append(body.position[0])
    energy, x = np.array(energy), np.array(x)
    starts = [i for i in range(1, len(x)) if x[i - 1] < 0.0 <= x[i]]
    assert len(starts) >= 5
    means = np.array([energy[u:v].mean() for u, v in itertools.pairwise(starts)])
    assert np.abs(means - means[0]).max() < 1e-4 * swing
    assert energy[starts[1]:].max() <= energy[:starts[1]].max() + 1e-4 * swing
    assert joint.separation() < 1e-6


def test_a_chain_of_ten_boxes_hangs_still_and_closed():
    """Ten 1 kg boxes jointed end to end from a world anchor: after 10 s the bottom joint is
    closed to < 1 mm and nothing moves faster than 1 mm/s."""
    world = pm.World(gravity=(0.0, -G, 0.0))
    joints, above = [], None
    for k in range(10):
        box = world.add_body(Box((0.05, 0.1, 0.05)), (0.0, -0.1 - 0.2 * k, 0.0), mass=1.0)
        joints.append(world.add(BallJoint(box, (0.0, 0.1, 0.0), above)))
        above = box
    for _ in range(600):
        world.step(DT)
    assert joints[-1].separation() < 1e-3
    assert world.joints.separations().max() < 1e-3
    assert np.abs(world.bodies.velocity).max() < 1e-3
    assert above.position[1] == pytest.approx(-1.9, abs=1e-3)


def _momenta(world):
    b = world.bodies
    mass = 1.0 / b.inv_mass
    p = (b.velocity * mass[:, None]).sum(axis=0)
    spin = sum(np.cross(b.position[i], b.velocity[i] * mass[i]) + b.angular_momentum(i)
               for i in range(b.count))
    return p, spin


def test_a_free_jointed_pair_keeps_its_momentum_and_angular_momentum():
    """No gravity: two boxes on one joint, turning together and flying, for 10 s. Linear
    momentum to rounding. The soft step's joint impulses (``joint_soft``) are equal and
    opposite at one point and the drift is torque-free, so angular momentum (about the origin)
    is kept by construction, to rounding (1e-9; measured 6.5e-11), and the joint aimed at the
    end pose every substep stays shut (1e-6 m; measured 1.4e-10 m). No step gains energy
    (issue 30: 1e-9; ``soft_energy.limit_islands`` takes what a substep's joint stages leave
    beyond its start off the pair's motion relative to its rigid motion, which keeps both
    momenta): the energy only falls, by the lower half of the band the joints' aim swung it
    in (+3.3e-8 / −4.5e-8, 307 of 600 steps gaining, before), −3.7e-7 in 10 s (measured),
    bound 1e-6. (The impulses stage that ran before kept angular momentum to 0.17 % and the
    joint to 1 mm.)"""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    omega = np.array([0.3, 0.5, 2.0])
    centre = np.array([0.5 / 3, 0.0, 0.0])  # the pair's centre of mass
    flight = np.array([1.0, 0.0, 0.0])
    a = world.add_body(Box((0.2, 0.1, 0.1)), (0.0, 0.0, 0.0), mass=2.0,
                       velocity=np.cross(omega, -centre) + flight,
                       angular_velocity=omega)
    b = world.add_body(Box((0.1, 0.3, 0.1)), (0.5, 0.0, 0.0), mass=1.0,
                       velocity=np.cross(omega, (0.5, 0.0, 0.0) - centre) + flight,
                       angular_velocity=omega)
    joint = world.add(BallJoint(a, (0.25, 0.0, 0.0), b))
    p0, l0 = _momenta(world)
    e0 = world.kinetic_energy()
    before = e0
    for _ in range(600):
        world.step(DT)
        now = world.kinetic_energy()
        assert now <= before * (1 + 1e-9)
        assert now >= e0 * (1 - 1e-6)
        before = now
    p1, l1 = _momenta(world)
    assert np.abs(p1 - p0).max() < 1e-12
    assert np.linalg.norm(l1 - l0) / np.linalg.norm(l0) < 1e-9
    assert joint.separation() < 1e-6


def _hung_rod(make, steps: int = 300, torque=None):
    """A 1 m rod along x hinged at its left end (x = 0) to the world at height 1 m, let fall
    under gravity (and ``torque`` [N m] each step); returns the world, rod, joint and the
    largest limit excess seen [rad]."""
    world = pm.World(gravity=(0.0, -G, 0.0))
    rod = world.add_body(Box((0.5, 0.05, 0.05)), (0.5, 1.0, 0.0), mass=1.0)
    joint = world.add(make(rod))
    worst = 0.0
    for _ in range(steps):
        if torque is not None:
            rod.add_torque(torque)
        world.step(DT)
        worst = max(worst, float(world.joints.angular_errors(world.bodies).max()))
    return world, rod, joint, worst


def test_a_hinge_limit_stops_a_falling_rod_at_its_angle():
    """A rod hinged about z with limits (−0.3, 0.3) falls from horizontal: it rests at −0.3
    rad (0.1° or better), never beyond it by more than 2°, and stays in its plane."""
    _, rod, joint, worst = _hung_rod(
        lambda r: HingeJoint(r, (-0.5, 0.0, 0.0), axis=(0, 0, 1), limits=(-0.3, 0.3)))
    x_axis = world_rotation(rod.orientation)[:, 0]
    assert math.atan2(x_axis[1], x_axis[0]) == pytest.approx(-0.3, abs=math.radians(0.1))
    assert worst < math.radians(2.0)
    assert abs(world_rotation(rod.orientation)[2, 2]) == pytest.approx(1.0, abs=1e-6)
    assert joint.separation() < 1e-3


def test_a_cone_limit_holds_a_falling_rod_at_its_swing():
    """A rod on a ball joint with a 30° cone about its own axis falls from horizontal: it
    rests 30° below (0.1°), never beyond by more than 2°."""
    _, rod, _, worst = _hung_rod(
        lambda r: BallJoint(r, (-0.5, 0.0, 0.0), axis=(1, 0, 0), cone=math.radians(30)))
    x_axis = world_rotation(rod.orientation)[:, 0]
    assert math.degrees(math.acos(x_axis[0])) == pytest.approx(30.0, abs=0.1)
    assert worst < math.radians(2.0)


@pytest.mark.parametrize("torque,angle", [(2.0, 0.4), (-2.0, -0.2)])
def test_a_twist_limit_stops_a_torque_at_each_bound(torque, angle):
    """A slab hung by a ball joint with twist (−0.2, 0.4) about the vertical, twisted by a
    steady torque either way: it stops at that bound (0.1°); the angle is the body's own turn
    about the axis, right-handed."""
    world = pm.World(gravity=(0.0, -G, 0.0))
    slab = world.add_body(Box((0.05, 0.5, 0.2)), (0.0, 0.5, 0.0), mass=1.0)
    world.add(BallJoint(slab, (0.0, 0.5, 0.0), axis=(0, 1, 0), twist=(-0.2, 0.4)))
    for _ in range(300):
        slab.add_torque((0.0, torque, 0.0))
        world.step(DT)
    z_axis = world_rotation(slab.orientation)[:, 2]
    assert math.atan2(z_axis[0], z_axis[2]) == pytest.approx(angle, abs=math.radians(0.1))


def test_jointed_bodies_do_not_collide_but_others_do():
    """Two overlapping boxes: no contact points between them once jointed; a third box
    overlapping both still meets both."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    a = world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.0, 0.0))
    b = world.add_body(Box((0.5, 0.5, 0.5)), (0.8, 0.0, 0.0))
    c = world.add_body(Box((0.5, 0.5, 0.5)), (0.4, 0.8, 0.0))
    world.step(DT)
    pairs = {tuple(sorted(p)) for p in zip(world.body_contacts.a, world.body_contacts.b,
                                           strict=True)}
    assert (0, 1) in pairs
    world.add(BallJoint(a, (0.4, 0.0, 0.0), b))
    world.step(DT)
    pairs = {tuple(sorted(p)) for p in zip(world.body_contacts.a, world.body_contacts.b,
                                           strict=True)}
    assert (0, 1) not in pairs and (0, 2) in pairs and (1, 2) in pairs
    assert c.index == 2


def _ragdollish(seed: int):
    world = pm.World(gravity=(0.0, -G, 0.0))
    world.add(pm.Ground())
    rng = np.random.default_rng(seed)
    above = None
    for k in range(5):
        box = world.add_body(Box((0.05, 0.2, 0.05)), (0.0, 2.3 - 0.45 * k, 0.0),
                             velocity=rng.normal(size=3))
        if above is not None:
            world.add(HingeJoint(box, (0.0, 0.22, 0.0), above, axis=(0, 0, 1),
                                 limits=(-1.5, 0.0)))
        above = box
    return world


def test_reruns_are_bit_identical():
    """Same inputs, same bits: a jointed chain thrown on the ground, twice."""
    runs = []
    for _ in range(2):
        world = _ragdollish(7)
        for _ in range(120):
            world.step(DT)
        runs.append((world.bodies.position.tobytes(), world.bodies.orientation.tobytes()))
    assert runs[0] == runs[1]


def test_a_restored_world_replays_bit_identically():
    """Simulation.rebuild restores the bodies and forgets the joints' warm start, so the
    replay matches the first run."""
    sim = pm.Simulation(pm.Scene(_ragdollish(3), dt=DT))
    sim.advance(1.0)
    first = sim.world.bodies.position.copy()
    sim.rebuild()
    assert len(sim.world.joints) == 4
    sim.advance(1.0)
    assert sim.world.bodies.position.tobytes() == first.tobytes()


def test_a_joint_can_be_removed():
    world, body, joint = _pendulum(0.0)
    world.remove(joint)
    assert len(world.joints) == 0
    world.step(DT)
    assert body.velocity[1] == pytest.approx(-G * DT)
    with pytest.raises(ValueError, match="not in this world"):
        world.remove(joint)


def test_bad_joints_are_refused_with_clear_errors():
    world = pm.World()
    a = world.add_body(Box((0.1, 0.1, 0.1)))
    with pytest.raises(ValueError, match="body_a and body_b must be different"):
        BallJoint(a, (0, 0, 0), a)
    with pytest.raises(TypeError, match="body_b must be a Body or a body index"):
        BallJoint(a, (0, 0, 0), "b")
    with pytest.raises(ValueError, match="local_a"):
        BallJoint(a, (0, 0))
    with pytest.raises(ValueError, match="axis must be a non-zero vector"):
        BallJoint(a, (0, 0, 0), axis=(0, 0, 0))
    with pytest.raises(ValueError, match=r"cone.*\[0, 3.14"):
        BallJoint(a, (0, 0, 0), cone=4.0)
    with pytest.raises(ValueError, match="twist must satisfy"):
        BallJoint(a, (0, 0, 0), twist=(0.2, 0.5))
    with pytest.raises(ValueError, match="limits must be a pair"):
        HingeJoint(a, (0, 0, 0), limits=3.0)
    with pytest.raises(IndexError, match=r"body_b: 5 is not a body; indices must be in \[0, 0\]"):
        world.add(BallJoint(a, (0, 0, 0), 5))
    joint = world.add(BallJoint(a, (0, 0, 0)))
    with pytest.raises(ValueError, match="already in this world"):
        world.add(joint)


def test_a_joint_to_a_body_that_a_restore_dropped_fails_naming_it():
    world = pm.World()
    saved = world.bodies.snapshot()
    a = world.add_body(Box((0.1, 0.1, 0.1)))
    world.add(BallJoint(a, (0, 0.1, 0)))
    world.bodies.restore(saved)
    with pytest.raises(IndexError, match="BallJoint refers to a body that no longer exists"):
        world.step(DT)
