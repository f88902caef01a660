"""Long jointed chains at the World() defaults (issue 13): the exact tree solve of the joints'
point blocks (``solver/joint_direct.py``) against Gauss–Seidel's limits, and the solve itself
against the saddle-point system it factors."""

import itertools
import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.joints import BallJoint, HingeJoint
from pointmass.rigid.shapes import Box
from pointmass.solver import joint_soft, joint_solver, joint_tree

#: The solver's tuning numbers as World() has them (``pm.SolverSettings``)
DEFAULTS = pm.SolverSettings()

DT = 1 / 60
G = 9.81
HALF = (0.05, 0.1, 0.05)  # 0.1 × 0.2 × 0.1 m links, jointed end to end


def _chain(n: int, tilt_deg: float = 0.0) -> pm.World:
    """n 1 kg boxes hung end to end from a world anchor at the origin, straight, tilted by
    ``tilt_deg`` about z, at rest."""
    world = pm.World(gravity=(0.0, -G, 0.0))
    th = math.radians(tilt_deg)
    down = np.array([math.sin(th), -math.cos(th), 0.0])
    turn = (math.cos(th / 2), 0.0, 0.0, math.sin(th / 2))
    above = None
    for k in range(n):
        box = world.add_body(Box(HALF), tuple(down * (0.1 + 0.2 * k)), turn, mass=1.0)
        world.add(BallJoint(box, (0.0, 0.1, 0.0), above))
        above = box
    return world


def _energy(world) -> float:
    return world.kinetic_energy() + world.potential_energy()


def test_a_chain_of_fifty_hangs_closed_at_the_defaults():
    """50 links hanging 10 s (they fall asleep on the way): no blow-up, every joint closed to
    < 1 mm (the bottom one too), the bottom link where the exact chain puts it, and the energy
    never above where it started (to rounding). Before the tree solve the 50 Gauss–Seidel
    passes of the defaults left this chain's joints apart and the bias fed it: 18 kJ in 1 s."""
    world = _chain(50)
    start = _energy(world)
    for _ in range(600):
        world.step(DT)
        assert _energy(world) <= start + 1e-9 * abs(start)
    assert world.joints.separations()[-1] < 1e-2
    assert world.joints.separations().max() < 1e-3
    assert world.bodies.position[-1, 1] == pytest.approx(-0.1 - 0.2 * 49, abs=1e-3)


def test_a_swinging_chain_of_fifty_holds_and_does_not_gain_energy():
    """50 links released 5° off the vertical, 10 s at the defaults: every joint < 1 cm all
    along (measured 0.16 mm), and the energy never rises above the start by more than 2 % of
    the swing's energy m·g·h (measured +1 %: the drift bias's work; Gauss–Seidel alone: joints
    6.5 mm apart within 0.2 s, the links spinning at 30 rad/s)."""
    world = _chain(50, 5.0)
    start = _energy(world)
    swing = 50 * G * 5.0 * (1.0 - math.cos(math.radians(5.0)))  # the centre of mass 5 m down
    worst = 0.0
    for _ in range(600):
        world.step(DT)
        worst = max(worst, world.joints.separations().max())
        assert _energy(world) <= start + 0.02 * swing
    assert worst < 1e-2
    assert np.abs(world.bodies.angular_velocity).max() < 2.0  # no link spun up


def test_the_tree_solve_meets_every_joint_target_at_once():
    """One velocity pass of a branching tree (a trunk of 6 with two branches of 4, anchored
    at the top; random velocities) leaves every joint's point velocity at its target to
    rounding: the factorisation solves the saddle-point system exactly, not by sweeps."""
    world = pm.World(gravity=(0.0, -G, 0.0))
    rng = np.random.default_rng(3)
    trunk = [world.add_body(Box(HALF), (0.0, -0.1 - 0.2 * k, 0.0), mass=1.0 + k)
             for k in range(6)]
    world.add(BallJoint(trunk[0], (0.0, 0.1, 0.0)))
    for upper, lower in itertools.pairwise(trunk):
        world.add(BallJoint(lower, (0.0, 0.1, 0.0), upper))
    for side in (-1.0, 1.0):
        above = trunk[2]
        for k in range(4):
            box = world.add_body(Box(HALF), (side * (0.2 + 0.2 * k), -0.5, 0.0),
                                 (math.cos(0.785), 0.0, 0.0, side * math.sin(0.785)), mass=0.5)
            world.add(BallJoint(box, (0.0, 0.1, 0.0), above))
            above = box
    b = world.bodies
    b.velocity[:] = rng.normal(size=(b.count, 3))
    b.angular_velocity[:] = rng.normal(size=(b.count, 3))
    rows = joint_solver.prepare(b, world.joints, DT)
    assert (rows.mode == joint_tree.DIRECT).all()
    joint_solver.warm_start(b, world.joints, rows)
    joint_solver.velocity_pass(b, world.joints, rows)
    j = world.joints.arrays()
    for k in range(j.a.shape[0]):
        a, other = j.a[k], j.b[k]
        rate = -(b.velocity[a] + np.cross(b.angular_velocity[a], rows.ra[k]))
        if other >= 0:
            rate += b.velocity[other] + np.cross(b.angular_velocity[other], rows.rb[k])
        assert rate == pytest.approx(rows.bias[k], abs=1e-9)


def _rope_bridge(n: int, **world) -> pm.World:
    """n planks (0.2 m long, 2 kg) ball-jointed end to end on a circular arc that hangs
    between two world anchors 0.9 of the bridge's length apart (slack to sag); ``world``:
    ``World``'s keywords."""
    world = pm.World(gravity=(0.0, -G, 0.0), **world)
    half = 0.786  # sin(x)/x = 0.9: the chord is 0.9 of the arc
    radius = 0.2 * n / (2 * half)
    planks = []
    for k in range(n):
        th = -half + (k + 0.5) * 2 * half / n
        planks.append(world.add_body(
            Box((0.1, 0.02, 0.3)),
            (radius * math.sin(th), radius * (math.cos(half) - math.cos(th)), 0.0),
            (math.cos(th / 2), 0.0, 0.0, math.sin(th / 2)), mass=2.0))
    world.add(BallJoint(planks[0], (-0.1, 0.0, 0.0)))
    for left, right in itertools.pairwise(planks):
        world.add(BallJoint(right, (-0.1, 0.0, 0.0), left))
    world.add(BallJoint(planks[-1], (0.1, 0.0, 0.0)))
    return world


def test_a_rope_bridge_of_fifty_planks_holds_at_the_defaults():
    """Anchored at both ends, the second anchor closes a loop through the world: it is a rigid
    row through the tree (``joint_loops``) aimed at closing its gap within the substep, so every
    joint stays closed to < 1 µm all along (measured 3.5e-7 m; as a soft row it opened 0.085 mm
    sprung with the tree's mass, 2.749 mm with one plank's; swept by Gauss–Seidel, in the
    impulses stage before the soft step, that anchor stayed 3–5 mm open with the joints beside
    it), and the bridge swings into its sag keeping its energy: the soft step reports
    leapfrog's synchronised velocity, so KE + PE has no first-order term of the drift's step
    and stays within 0.02 J of the start (measured 3e-4 J against a largest kinetic energy of
    1.74 J)."""
    world = _rope_bridge(50)
    rows = joint_soft.prepare(world.bodies, world.joints, DT / DEFAULTS.soft_substeps).solve
    assert (rows.mode == joint_tree.LOOP).sum() == 1
    start = _energy(world)
    worst = rise = moving = drift = 0.0
    for _ in range(600):
        world.step(DT)
        worst = max(worst, world.joints.separations().max())
        energy = _energy(world)
        rise = max(rise, energy - start)
        moving = max(moving, world.kinetic_energy())
        drift = max(drift, abs(energy - start))
    assert worst < 1e-6
    assert rise <= 0.1 * moving
    assert drift < 0.02


def test_the_soft_step_leaves_a_redundant_pair_of_joints_to_soft_rows():
    """Two joints on one pair of bodies (a redundant pair: the second point cannot move along
    the line to the first, so its mass through the tree is singular there) close a loop the
    soft step leaves to soft Gauss–Seidel rows (``joint_tree.unpair``), while a loop through
    other bodies (the bridge's second anchor) still goes through the tree."""
    world = _rope_bridge(5)
    pair = [world.add_body(Box(HALF), (5.0, 2.0 + 0.2 * k, 0.0), mass=1.0) for k in range(2)]
    world.add(BallJoint(pair[1], (0.0, -0.1, 0.0), pair[0]))
    world.add(HingeJoint(pair[1], (0.05, -0.1, 0.0), pair[0], axis=(1.0, 0.0, 0.0)))
    soft = joint_soft.prepare(world.bodies, world.joints, DT / 4).solve.mode
    assert soft.tolist() == [joint_tree.DIRECT] * 5 + [joint_tree.LOOP] \
        + [joint_tree.DIRECT, joint_tree.ITERATIVE]
    assert joint_solver.prepare(world.bodies, world.joints, DT).mode.tolist() \
        == [joint_tree.DIRECT] * 5 + [joint_tree.ITERATIVE] \
        + [joint_tree.DIRECT, joint_tree.ITERATIVE]


def test_a_loop_and_a_second_anchor_are_solved_through_the_tree():
    """A rope bridge (anchored at both ends) and a closed ring: the forest takes all but one
    joint of each loop; the joint that closes it is a LOOP joint (``joint_loops``). A loop
    the tree cannot move along (a straight, taut bridge: first-order rigid along its length)
    is left to Gauss–Seidel."""
    world = _rope_bridge(5)
    corners = [np.array((0.3 * math.cos(a), 2.0 + 0.3 * math.sin(a), 0.0))
               for a in (0.0, 2.1, 4.2)]
    ring = [world.add_body(Box(HALF), tuple(c), mass=1.0) for c in corners]
    for k in range(3):  # a triangle, jointed at the middle of each side
        middle = 0.5 * (corners[k] + corners[(k + 1) % 3])
        world.add(BallJoint(ring[k], tuple(middle - corners[k]), ring[(k + 1) % 3]))
    rows = joint_solver.prepare(world.bodies, world.joints, DT)
    assert rows.mode.tolist() == [joint_tree.DIRECT] * 5 + [joint_tree.LOOP] \
        + [joint_tree.DIRECT] * 2 + [joint_tree.LOOP]
    taut = pm.World(gravity=(0.0, -G, 0.0))
    planks = [taut.add_body(Box(HALF), (0.2 * k, 0.0, 0.0), mass=1.0) for k in range(3)]
    taut.add(BallJoint(planks[0], (-0.1, 0.0, 0.0)))
    for left, right in itertools.pairwise(planks):
        taut.add(BallJoint(right, (-0.1, 0.0, 0.0), left))
    taut.add(BallJoint(planks[-1], (0.1, 0.0, 0.0)))
    rows = joint_solver.prepare(taut.bodies, taut.joints, DT)
    assert rows.mode.tolist() == [joint_tree.DIRECT] * 3 + [joint_tree.ITERATIVE]


def test_a_chain_from_an_immovable_body_hangs_as_from_the_world():
    """An immovable box as the anchor (inv_mass 0: not a node of the tree) holds a 20-box
    chain as the world does: the same bottom position to 1e-9 m after 2 s."""
    ends = []
    for fixed in (False, True):
        world = pm.World(gravity=(0.0, -G, 0.0))
        above = world.add_body(Box(HALF), (0.0, 0.1, 0.0), mass=math.inf) if fixed else None
        for k in range(20):
            box = world.add_body(Box(HALF), (0.05, -0.1 - 0.2 * k, 0.0), mass=1.0)
            world.add(BallJoint(box, (-0.05, 0.1, 0.0), above))
            above = box
        for _ in range(120):
            world.step(DT)
        ends.append(world.bodies.position[-1].copy())
    assert ends[0] == pytest.approx(ends[1], abs=1e-9)
