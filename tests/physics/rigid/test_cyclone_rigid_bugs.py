"""Regression tests for Cyclone's rigid-body bugs (rigid-notes.md §1.8, R1–R11), one or more
each. R3 (aero on the surface point's velocity) and R4 (springs push both ends) are tested
with the rigid force generators in test_body_forces.py; R6 (sleeping) has more in
test_sleep.py, R11 (joints) in test_joints.py and test_joint_chains.py.
"""

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.shapes import Box, Sphere
from pointmass.rigid.step import MAX_ROTATION

#: The solver's tuning numbers as World() has them (``pm.SolverSettings``)
DEFAULTS = pm.SolverSettings()

DT = 1 / 60


def _free_world():
    return pm.World(gravity=(0.0, 0.0, 0.0))


def test_r1_a_free_spinning_body_keeps_its_angular_momentum_and_precesses():
    """R1: Cyclone's integrate has no gyroscopic term, so a tumbling body's L drifts. Here a
    box spun off its axes keeps |L| and its direction for 10 s."""
    world = _free_world()
    body = world.add_body(Box((0.1, 0.3, 0.6)), angular_velocity=(1.0, 4.0, 0.5), mass=2.0)
    before = world.bodies.angular_momentum(0)
    for _ in range(600):
        world.step(DT)
    after = world.bodies.angular_momentum(0)
    assert np.linalg.norm(after - before) / np.linalg.norm(before) < 1e-9
    assert not np.allclose(body.angular_velocity, (1.0, 4.0, 0.5))   # ω itself precesses


def test_r2_rotation_per_step_is_bounded_and_inertia_follows_the_pose():
    """R2: Cyclone uses last step's world inertia and lets ω·dt grow without bound. A huge
    torque here is capped where it is integrated: the first kick's spin is MAX_ROTATION / h
    along I⁻¹τ, h the body stage's integration step (dt/SUBSTEPS). The torque-free drifts
    after it keep the rotational energy and later kicks only slow a spin, so the energy after
    the step is at most that capped spin's; the box turns at most π/4 per drift (four drifts
    a step, whose sum the orientation alone cannot show). The world inverse inertia is
    that of the current orientation after the step."""
    from pointmass.rigid.bodies import world_rotation

    world = pm.World(gravity=(0.0, 0.0, 0.0))
    body = world.add_body(Box((0.2, 0.4, 0.8)), mass=1.0)
    torque = np.array((3e5, 1e6, 0.0))
    body.add_torque(torque)
    world.step(DT)
    b = world.bodies
    h = DT / DEFAULTS.soft_substeps
    spin = b.inv_inertia[0] * torque  # the identity pose: I⁻¹ is diagonal
    capped = MAX_ROTATION / h * spin / np.linalg.norm(spin)
    cap_energy = 0.5 * capped @ (capped / b.inv_inertia[0])
    w = b.angular_velocity[0]
    energy = 0.5 * w @ np.linalg.solve(b.inv_inertia_world[0], w)
    assert energy <= cap_energy * (1.0 + 1e-9)
    r = world_rotation(b.orientation[0])
    expected = r @ np.diag(b.inv_inertia[0]) @ r.T
    assert np.allclose(b.inv_inertia_world[0], expected, atol=1e-12)


def test_r5_mass_properties_come_from_the_shape():
    """R5: Cyclone's flightsim and sailboat build inertia for another mass. Here mass and
    inertia both follow from shape and density (or a given mass): m(b² + c²)/3 on half-extents."""
    world = _free_world()
    box = world.add_body(Box((0.5, 1.0, 1.5)), density=200.0)
    mass = 200.0 * 8 * 0.5 * 1.0 * 1.5
    assert box.mass == pytest.approx(mass)
    assert box.inertia == pytest.approx(mass / 3 * np.array([1.0 + 2.25, 0.25 + 2.25, 0.25 + 1.0]))
    ball = world.add_body(Sphere(0.5), mass=4.0)
    assert ball.inertia == pytest.approx([0.4 * 4.0 * 0.25] * 3)


@pytest.mark.parametrize(("spin", "sleeps"), [(0.04, False), (0.02, True)])
def test_r6_sleep_speed_is_the_fastest_point_in_metres_per_second(spin, sleeps):
    """R6, units: Cyclone compares v·v + ω·ω (m²/s² + rad²/s²) with 0.3. Here how far the
    body's points go, |Δx| + extent·θ, is compared with 0.05 m/s × 0.5 s: a 2 m cube (extent
    √3 m) turning at 0.04 rad/s moves its corners at 0.069 m/s and stays awake; at 0.02 rad/s
    (0.035 m/s) it sleeps after 0.5 s. Cyclone would put both to sleep."""
    world = _free_world()
    body = world.add_body(Box((1.0, 1.0, 1.0)), angular_velocity=(0.0, spin, 0.0), mass=1.0)
    for _ in range(120):
        world.step(DT)
    assert body.awake is not sleeps
    assert spin * spin < 0.3  # below Cyclone's sleepEpsilon: it would sleep there


def test_r6_a_stack_sleeps_and_wakes_as_one_island_also_from_the_world():
    """R6: Cyclone sleeps each body alone (a stack's bottom sleeps under a moving top) and
    wakes only body–body partners. Here the three boxes fall asleep in the same step, and a
    moving immovable body (a kinematic pusher, part of the world) wakes all three by touching
    the bottom one."""
    world = pm.World()
    world.add(pm.Ground())
    boxes = [world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.5 + k, 0.0), mass=1.0)
             for k in range(3)]
    for _ in range(120):
        world.step(DT)
        awake = [b.awake for b in boxes]
        assert all(awake) or not any(awake)
    assert not any(awake)
    world.add_body(Box((0.1, 0.2, 1.0)), (-0.61, 0.2, 0.0), mass=math.inf,
                   velocity=(0.5, 0.0, 0.0))
    for _ in range(3):  # 1 cm to go at 0.5 m/s: it closes in during the second step
        world.step(DT)
    assert all(b.awake for b in boxes)


def test_r7_a_box_resting_on_a_box_gets_four_points_on_the_face():
    """R7: Cyclone's box–box takes the least-overlap axis with no face bias and one point, so a
    box on a box rocks. Here a resting stack has four contact points on the shared face.

    The soft step rests on springs (``body_soft``, as in R8/R9): the top box sinks by its rows'
    static sag, m·g / (4·m_n·ω²) = 8.6 µm (m_n = 1/8 kg a corner, ω = 2π·240 Hz); tilted by more
    than that sag over its half-width, 1.7e-5 rad, a corner would lift off, so below it all four
    corners keep pushing and it does not rock (measured 1.5e-6 rad in the first 30 steps: a period-2
    rock of the Gauss–Seidel order that dies out, 1e-10 rad by step 100), where one point (Cyclone)
    lets it rock by degrees; its step-end velocity is what the relax passes of its closing
    projection leave (``body_soft``, "Leapfrog"), which stop once no row changes a velocity by more
    than ``SolverSettings.soft_tolerance`` = 1e-5 m/s (measured 1.3e-5 m/s; 7.7e-6 before the
    leapfrog, from the substeps' own relax)."""
    world = pm.World()
    world.add(pm.Ground(friction=0.5))
    world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.5, 0.0), mass=1.0)
    world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 1.5, 0.0), mass=1.0)
    tilt = 0.0
    for _ in range(30):
        stats = world.step(DT)
        # a unit quaternion's vector part is sin(angle / 2): the angle off upright [rad]
        tilt = max(tilt, 2.0 * np.abs(world.bodies.orientation[:, 1:]).max())
    assert stats.body_contacts == 8          # four on the ground, four between the boxes
    h = DT / DEFAULTS.soft_substeps
    omega = 2.0 * math.pi * min(DEFAULTS.contact_hertz, DEFAULTS.contact_hertz_cap / h)
    sag = 9.81 / (4 * (1.0 / 8.0) * omega**2)
    assert tilt < sag / 0.5
    assert np.abs(world.bodies.velocity).max() < 2.0 * DEFAULTS.soft_tolerance


def test_r8_r9_contacts_persist_and_a_stack_converges():
    """R8/R9: Cyclone keeps nothing between steps and resolves worst-first without accumulated
    impulses, so stacks jitter. Here the contacts' impulses are stored by key and warm start
    the next step, and a 10-box stack converges and stands still.

    The soft step rests on springs (``body_soft``: each row k = m_n·ω², ω = 2π·240 Hz between boxes
    at h = dt/4, twice that on the ground; a unit box's corner row has m_n = 1/8 kg on a box,
    1/4 on the ground), so the stack first settles by its static sag, Σ over the faces of
    (boxes above)·m·g / (4·m_n·ω²) = 0.3991 mm (measured 0.3990 mm, rel 5.7e-5: the rows'
    passes stop at 1e-5 m/s, 1.2e-4 of a row's share of m·g·h), sideways less than that
    (the Gauss–Seidel order during the settle: 0.12 mm), and then stands still to 1e-9 m."""
    world = pm.World()
    world.add(pm.Ground(friction=0.5))
    boxes = [world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.5 + k, 0.0), mass=1.0, friction=0.5)
             for k in range(10)]
    exact = boxes[-1].position.copy()
    world.step(DT)
    assert len(world.body_impulses) == 4 * 10    # one stored impulse per contact point
    settle = 60
    for _ in range(settle - 1):
        world.step(DT)
    top = boxes[-1].position.copy()
    for _ in range(600 - settle + 1):
        world.step(DT)
    assert np.linalg.norm(boxes[-1].position - top) < 1e-9
    h = DT / DEFAULTS.soft_substeps
    omega = 2.0 * math.pi * min(DEFAULTS.contact_hertz, DEFAULTS.contact_hertz_cap / h)
    g, box_row, ground_row = 9.81, 1.0 / 8.0, 1.0 / 4.0
    sag = (10 * g / (4 * ground_row * (2 * omega) ** 2)
           + sum(k * g / (4 * box_row * omega**2) for k in range(1, 10)))
    assert exact[1] - top[1] == pytest.approx(sag, rel=1e-3)
    assert math.hypot(top[0] - exact[0], top[2] - exact[2]) < sag


def test_r10_a_fast_small_body_does_not_tunnel_through_a_thin_wall():
    """R10: no CCD in Cyclone (bigballistic's laser moves 5 m a step). A 0.1 m ball at 300 m/s
    (5 m a step) meets a 0.1 m static wall and stops at its face (speculative contacts)."""
    world = _free_world()
    world.add_body(Box((0.05, 2.0, 2.0)), mass=math.inf)
    ball = world.add_body(Sphere(0.05), (-3.0, 0.0, 0.0), velocity=(300.0, 0.0, 0.0), mass=0.1)
    for _ in range(60):
        world.step(DT)
    assert ball.position[0] == pytest.approx(-0.1, abs=1e-6)
    assert abs(ball.velocity[0]) < 1e-9


def test_r11_a_joint_is_two_sided_and_not_slack():
    """R11: Cyclone's joint is a contact with friction 1 that acts only once its two points are
    0.15 m apart, and only pulls. Here a box hung by its top point hangs with that point on the
    anchor (no slack: < 1 mm, not 0.15 m), and a box standing on its bottom point, pushed down
    onto the anchor by gravity and by a shove, keeps its point there as it topples: the joint
    pushes too (its centre never comes closer to the anchor than d − 1 mm)."""
    from pointmass.rigid.joints import BallJoint

    world = pm.World(gravity=(0.0, -10.0, 0.0))
    hung = world.add_body(Box((0.1, 0.25, 0.1)), (0.0, 1.75, 0.0), mass=1.0)
    pulled = world.add(BallJoint(hung, (0.0, 0.25, 0.0)))  # the anchor at (0, 2, 0)
    d = 0.25
    standing = world.add_body(Box((0.1, d, 0.1)), (3.0, d, 0.0), (0.9999, 0.0, 0.0, 0.0141),
                              mass=1.0, velocity=(0.0, -2.0, 0.0))
    pushed = world.add(BallJoint(standing, (0.0, -d, 0.0)))
    anchor = pushed.anchors()[1]
    closest, gap, heights = [], [], []
    for _ in range(120):
        world.step(DT)
        closest.append(float(np.linalg.norm(standing.position - anchor)))
        gap.append(max(pulled.separation(), pushed.separation()))
        heights.append(float(standing.position[1]))
    assert max(gap[:30]) < 1e-3  # the shove onto the anchor, and the start of the fall
    assert min(closest[:30]) > d - 1e-3
    # toppling all the way round at up to 11 rad/s, the step's drift opens it by ~5 mm
    assert max(gap) < 0.01 and min(closest) > d - 0.01
    # it did topple, about its pinned point: through the bottom of the swing, its centre d
    # below the anchor (the soft step keeps its energy to 2 % and it swings back over the
    # top, as a frictionless pin would; the impulses stage before it lost a fifth of the
    # energy in one step of the swing and stayed down)
    assert min(heights) < -0.9 * d
