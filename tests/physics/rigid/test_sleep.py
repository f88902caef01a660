"""Sleeping islands (issue 13, rigid-notes §1.1): islands fall asleep after 0.5 s below
0.05 m/s and wake, all of them, when touched or pushed."""

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid import islands
from pointmass.rigid.forces import Explosion
from pointmass.rigid.shapes import Box, Sphere

#: The solver's tuning numbers as World() has them (``pm.SolverSettings``)
DEFAULTS = pm.SolverSettings()

DT = 1 / 60
HALF = 0.5


def _world(**kwargs):
    world = pm.World(**kwargs)
    world.add(pm.Ground(friction=0.5, restitution=0.5))  # e = 0.5: the figures were measured so
    return world


def _stack(world, n=3, x=0.0, **kwargs):
    """n unit cubes (1 kg) stacked exactly on the ground at x."""
    return [world.add_body(Box((HALF,) * 3), (x, HALF + 2 * HALF * k, 0.0), mass=1.0, **kwargs)
            for k in range(n)]


def _fastest_point(world):
    """|v| + |ω|·extent of every body (the sleep test's speed) [m/s]."""
    b = world.bodies
    extent = np.empty(b.count)
    islands.extents(b.shape, b.size, b.inv_mass, b.inv_inertia, extent)
    return (np.linalg.norm(b.velocity, axis=1)
            + np.linalg.norm(b.angular_velocity, axis=1) * extent)


def _step_until_asleep(world, seconds=5.0):
    for k in range(int(seconds / DT)):
        world.step(DT)
        if not world.bodies.awake.any():
            return (k + 1) * DT
    raise AssertionError(f"still awake after {seconds} s")


def _corners(box):
    signs = np.array([[(k >> a & 1) * 2 - 1 for a in range(3)] for k in range(8)], float)
    return np.array([box.to_world(HALF * s) for s in signs])


def test_a_dropped_box_falls_asleep_soon_after_it_settles_and_stays_exactly_put():
    """It sleeps within 0.5 s of its last step above 0.05 m/s, once no corner has moved 2.5 cm
    (0.05 m/s × 0.5 s) in the last 0.5 s, and then does not move by a single bit."""
    world = _world()
    box = world.add_body(Box((HALF,) * 3), (0.0, 1.5, 0.0), (0.96, 0.2, 0.0, 0.2), mass=1.0)
    window = round(islands.TIME_TO_SLEEP / DT)
    corners = [_corners(box)]
    rest = None  # the start of the last stretch below the threshold before it slept
    for k in range(int(5.0 / DT)):
        stats = world.step(DT)
        if not box.awake:
            break
        corners.append(_corners(box))
        slow = _fastest_point(world)[0] <= islands.SLEEP_SPEED
        rest = (rest if rest is not None else (k + 1) * DT) if slow else None
    else:
        raise AssertionError("the box never fell asleep")
    slept = (k + 1) * DT
    assert rest is not None and slept - rest <= islands.TIME_TO_SLEEP + 2 * DT
    moved = np.linalg.norm(corners[-1] - corners[-1 - window], axis=1).max()
    assert moved < islands.SLEEP_SPEED * islands.TIME_TO_SLEEP
    assert stats.awake_bodies == 0
    pose = box.position.copy(), box.orientation.copy()
    assert abs(pose[0][1] - HALF) < 2e-3  # asleep on its face, not in mid-air
    for _ in range(300):
        stats = world.step(DT)
    assert np.array_equal(box.position, pose[0]) and np.array_equal(box.orientation, pose[1])
    assert not box.velocity.any() and not box.angular_velocity.any()
    assert stats.body_contacts == 0  # no rows for a sleeping body on the ground


def test_sleeping_bodies_are_neither_integrated_nor_solved():
    world = _world()
    boxes = _stack(world, 3)
    _step_until_asleep(world)
    stats = world.step(DT)
    assert stats.body_contacts == 0 and stats.velocity_passes == 0
    assert stats.awake_bodies == 0
    assert all(not b.velocity.any() for b in boxes)


def test_a_stack_sleeps_as_one_island_never_the_bottom_alone():
    """R6 in the island form: the bottom boxes are still for seconds while the top slides on
    them (frictionless), so per-body sleep (Cyclone's) would have put them to sleep; as one
    island none sleeps until all are still.

    The frictionless slide keeps its velocity but for the tilt of the face it slides on. The
    soft step rests on springs (``body_soft``: rows
    of ω = 2π·240 Hz at h = dt/4, 480 Hz against the ground, each of stiffness m_n·ω²; a unit
    box's corner row has m_n = 1/8 kg on a box, 1/4 on the ground): a face of four corners
    0.5 m off its centre resists a turn with 4·m_n·ω²·0.5², so the top's weight moved x = 0.4 m
    off centre tilts the middle box by g·x·(8 + 1)/ω² quasi-statically (its face on the bottom
    box, and the bottom box's on the ground): 1.55e-5 rad (measured 1.54e-5 rad at the end).
    The slide's velocity then moves by at most about
    g·θ·t (θ at its largest all along: 3.0e-4 m/s in 2 s; measured 1.5e-4 m/s).
    """
    world = _world()
    boxes = _stack(world, 3)
    top = boxes[2]
    world.bodies.friction[top.index] = 0.0
    top.velocity = (0.2, 0.0, 0.0)
    seconds = 2.0
    for _ in range(int(seconds / DT)):  # 0.4 m of slide: still on the middle box
        world.step(DT)
        assert world.bodies.awake.all()
    assert world.bodies.sleep_time[0] > 1.0  # the bottom alone has long been still
    h = DT / DEFAULTS.soft_substeps
    omega = 2.0 * math.pi * min(DEFAULTS.contact_hertz, DEFAULTS.contact_hertz_cap / h)
    g = 9.81
    tilt = g * 0.2 * seconds * (8.0 + 1.0) / omega**2  # the slide's end, x = 0.4 m
    bound = g * tilt * seconds
    assert np.linalg.norm(top.velocity - (0.2, 0.0, 0.0)) < bound


def test_a_ball_thrown_at_a_sleeping_stack_wakes_it_and_knocks_the_top_box():
    world = _world()
    boxes = _stack(world, 3)
    _step_until_asleep(world)
    top_before = boxes[2].position.copy()
    ball = world.add_body(Sphere(0.2), (-3.0, 2.5, 0.0), velocity=(12.0, 1.0, 0.0), mass=5.0)
    for _ in range(30):
        world.step(DT)
    assert all(b.awake for b in boxes)
    assert boxes[2].position[0] - top_before[0] > 0.2  # pushed along the throw
    assert ball.velocity[0] < 12.0


def test_an_awake_box_landing_on_a_sleeping_one_wakes_it_through_speculative_points():
    """The falling box's row with the sleeper exists before they touch (speculative), so the
    sleeper is awake when the solver meets the impact: the momentum goes into both."""
    world = _world()
    low = world.add_body(Box((HALF,) * 3), (0.0, HALF, 0.0), mass=1.0)
    _step_until_asleep(world)
    world.add_body(Box((HALF,) * 3), (0.0, 3.5, 0.0), mass=1.0, restitution=1.0)
    woke = None
    for k in range(60):
        world.step(DT)
        if low.awake and woke is None:
            woke = k
    assert woke is not None


def test_forces_wake_a_sleeping_body_and_a_pushed_body_does_not_fall_asleep():
    world = _world()
    box = world.add_body(Box((HALF,) * 3), (0.0, HALF, 0.0), mass=1.0)
    _step_until_asleep(world)
    box.add_force((0.0, 30.0, 0.0))  # > mg: lifts off
    assert box.awake
    world.step(DT)
    assert box.velocity[1] > 0.0
    _step_until_asleep(world)
    box.add_torque((0.0, 5.0, 0.0))
    assert box.awake
    _step_until_asleep(world)
    box.add_force_at_point((0.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    assert box.awake
    # a force every step keeps it awake, however small its effect
    for _ in range(120):
        box.add_force((1e-3, 0.0, 0.0))
        world.step(DT)
        assert box.awake


def test_setting_pose_or_velocity_through_body_wakes_it():
    world = _world()
    box = world.add_body(Box((HALF,) * 3), (0.0, HALF, 0.0), mass=1.0)
    for name, value in (("position", (0.0, 2.0, 0.0)), ("velocity", (1.0, 0.0, 0.0)),
                        ("angular_velocity", (0.0, 1.0, 0.0)),
                        ("orientation", (0.0, 0.0, 1.0, 0.0))):
        _step_until_asleep(world)
        setattr(box, name, value)
        assert box.awake, name


def test_a_ground_contact_alone_does_not_keep_a_body_awake_but_a_moving_platform_wakes_it():
    """R6: Cyclone wakes only body–body partners, never for a contact with the world. Here the
    scenery is immovable and wakes nothing, and an immovable body that moves (a kinematic
    platform) wakes what it reaches."""
    world = _world()
    box = world.add_body(Box((HALF,) * 3), (0.0, HALF, 0.0), mass=1.0)
    _step_until_asleep(world)
    wall = world.add_body(Box((0.1, 1.0, 1.0)), (-1.0, 1.0, 0.0), mass=float("inf"),
                          velocity=(1.0, 0.0, 0.0))
    for _ in range(30):
        world.step(DT)
    assert box.awake
    assert box.position[0] > 0.05  # pushed
    assert wall.awake


def test_an_explosion_wakes_what_it_reaches_and_nothing_else():
    world = _world()
    near = world.add_body(Box((HALF,) * 3), (2.0, HALF, 0.0), mass=1.0)
    far = world.add_body(Box((HALF,) * 3), (10.0, HALF, 0.0), mass=1.0)
    _step_until_asleep(world)
    still = far.position.copy()
    world.add(Explosion((0.0, 0.5, 0.0), strength=10.0, radius=4.0))
    world.step(DT)
    assert near.awake and not far.awake
    for _ in range(10):
        world.step(DT)
    assert near.position[0] > 2.1
    assert np.array_equal(far.position, still)


def test_a_particle_hitting_a_sleeping_box_wakes_it_one_resting_on_it_does_not():
    world = _world()
    box = world.add_body(Box((HALF,) * 3), (0.0, HALF, 0.0), mass=1.0)
    _step_until_asleep(world)
    p = world.add_particle((0.0, 2 * HALF + 0.05, 0.0), radius=0.05, mass=0.1)
    for _ in range(60):
        world.step(DT)
    assert not box.awake
    assert abs(world.particles.position[p, 1] - (2 * HALF + 0.05)) < 2e-3  # held up by it
    world.add_particle((-3.0, 0.5, 0.0), (10.0, 0.0, 0.0), radius=0.05, mass=0.5)
    for _ in range(30):
        world.step(DT)
    assert box.awake and box.position[0] > 1e-3


def _pile(world):
    """4 stacks of 5 boxes: 80 points."""
    return [b for x in range(4) for b in _stack(world, 5, x=1.5 * x)]


def _largest_move(world, boxes):
    before = np.array([b.position.copy() for b in boxes])
    world.step(DT)
    return np.abs(np.array([b.position for b in boxes]) - before).max()


def _woken_sag(cold, **kwargs):
    """The pile put to sleep and woken; how far a box moves in the first step after, the keys
    kept, and the steps it took to fall asleep."""
    world = _world(**kwargs)
    boxes = _pile(world)
    steps = round(_step_until_asleep(world) / DT)
    world.step(DT)  # a step with every body asleep: no rows, the history is empty
    held = world.sleeping_impulses.kept.keys.copy()
    assert len(world.body_impulses) == 0
    if cold:
        world.sleeping_impulses.clear()
    for b in boxes:
        b.awake = True
    return _largest_move(world, boxes), held, world, steps


def test_a_woken_pile_starts_from_the_impulses_it_slept_with():
    """The first step after waking is that of the same pile never put to sleep, its
    velocities zeroed (what sleeping does), to the bit: the warm start kept nothing less.
    Without it (cold) a box moves further. Measured: 5.1e-7 m warm and 1.3e-5 m cold.

    The wake step finds the points the twin finds. The soft step collides once a step, at the
    step's start, and its pile still rocks at
    ~1e-6 rad with a period of two steps when it falls asleep: the incident corners that lie
    on a reference face's edge (equal boxes stacked exactly) are clipped on one side or the
    other of it, so the four points of 4 of the 16 box–box faces change their ids every step
    (measured: 16 keys, until about step 50 without sleep), and 64 of the 80 are found again."""
    warm, held, world, steps = _woken_sag(cold=False)
    cold, _, _, _ = _woken_sag(cold=True)
    assert len(held) == 80
    twin = _world(sleep=False)
    boxes = _pile(twin)
    for _ in range(steps):
        twin.step(DT)
    twin.bodies.velocity[:] = 0.0
    twin.bodies.angular_velocity[:] = 0.0
    assert warm == _largest_move(twin, boxes)
    assert np.array_equal(world.body_impulses.keys, twin.body_impulses.keys)
    found = np.isin(held, world.body_impulses.keys).sum()
    assert found >= 64  # the same points, found again
    assert cold > 1.5 * warm


def test_sleeping_changes_nothing_before_the_first_island_sleeps():
    """Until something falls asleep, a world with sleeping on is bit for bit the world with it
    off (the same kernels on the same rows), and each is deterministic."""
    def run(sleep):
        world = _world(sleep=sleep)
        _stack(world, 4)
        world.add_body(Sphere(0.3), (-2.0, 0.3, 0.0), velocity=(3.0, 0.0, 0.0), mass=2.0)
        states = []
        for _ in range(40):
            world.step(DT)
            states.append(world.bodies.snapshot())
        return states

    on, off, again = run(True), run(False), run(True)
    compared = 0
    for a, b, c in zip(on, off, again):
        for name in ("position", "orientation", "velocity", "angular_velocity"):
            assert np.array_equal(a[name], c[name])
        if not a["awake"].all():
            break  # the stack (at rest from the start) fell asleep
        for name in ("position", "orientation", "velocity", "angular_velocity"):
            assert np.array_equal(a[name], b[name])
        compared += 1
    assert compared >= int(islands.TIME_TO_SLEEP / DT) - 1


def test_reruns_with_sleep_are_bit_identical_and_sleep_off_never_sleeps():
    def run(sleep):
        world = _world(sleep=sleep)
        _stack(world, 3)
        _stack(world, 2, x=3.0)
        ball = world.add_body(Sphere(0.2), (-3.0, 0.2, 0.0), mass=5.0)
        fewest = world.bodies.count
        for k in range(240):
            if k == 120:
                ball.velocity = (12.0, 0.0, 0.0)
            fewest = min(fewest, world.step(DT).awake_bodies)
        return world.bodies.snapshot(), fewest

    (a, slept), (b, _) = run(True), run(True)
    for name in a:
        assert np.array_equal(a[name], b[name]), name
    off, awake = run(False)
    assert slept == 0 and awake == off["awake"].size


def test_snapshots_keep_the_sleep_state():
    world = _world()
    _stack(world, 2)
    _step_until_asleep(world)
    snap = world.bodies.snapshot()
    world.bodies[0].awake = True
    assert world.bodies.awake.all()
    world.bodies.restore(snap)
    assert not world.bodies.awake.any() and (world.bodies.island == 0).all()


def test_linked_bodies_share_an_island():
    """The (K, 2) pairs of ``island_links`` (joints) join islands like a touching contact:
    a box at rest linked to one still falling does not sleep before it."""
    def first_sleep(linked):
        world = _world()
        rest = world.add_body(Box((HALF,) * 3), (0.0, HALF, 0.0), mass=1.0)
        world.add_body(Box((HALF,) * 3), (5.0, 8.0, 0.0), mass=1.0)
        if linked:
            world.island_links = np.array([[0, 1]])
        for k in range(300):
            world.step(DT)
            if not rest.awake:
                return k
        return None

    alone, linked = first_sleep(False), first_sleep(True)
    assert alone is not None and linked is not None
    assert linked > alone + 20  # waited for the falling box to land and settle


def test_a_link_to_a_moving_body_wakes_a_sleeper():
    world = _world()
    rest = world.add_body(Box((HALF,) * 3), (0.0, HALF, 0.0), mass=1.0)
    other = world.add_body(Box((HALF,) * 3), (5.0, HALF, 0.0), mass=1.0)
    anchor = world.add_body(Box((HALF,) * 3), (9.0, 5.0, 0.0), mass=float("inf"))
    world.island_links = np.array([[0, 1], [1, 2]])  # a static anchor wakes nothing
    for _ in range(60):
        world.step(DT)
    assert anchor.awake and not rest.awake and not other.awake
    other.velocity = (1.0, 0.0, 0.0)
    world.step(DT)
    assert rest.awake


def test_turning_sleep_off_wakes_everyone():
    world = _world()
    _stack(world, 2)
    _step_until_asleep(world)
    world.sleep = False
    assert world.bodies.awake.all()
    for _ in range(60):
        world.step(DT)
    assert world.bodies.awake.all()


@pytest.mark.parametrize(("setting", "error"), [("yes", TypeError), (1, TypeError)])
def test_bad_settings_name_the_parameter(setting, error):
    with pytest.raises(error, match="sleep"):
        pm.World(sleep=setting)
    world = _world()
    box = world.add_body(Box((HALF,) * 3), mass=1.0)
    with pytest.raises(TypeError, match="awake"):
        box.awake = setting
    wall = world.add_body(Box((HALF,) * 3), mass=float("inf"))
    with pytest.raises(ValueError, match="immovable"):
        wall.awake = False
    world.island_links = np.array([[0, 5]])
    with pytest.raises(IndexError, match="island_links"):
        world.step(DT)


def test_a_box_tipping_off_its_edge_is_not_frozen_on_the_way_down():
    """Balanced 0.5° past its edge, the box starts to turn so slowly that it moves less than
    2.5 cm in its first 0.5 s; it must still fall flat before it sleeps."""
    world = _world()
    tilt = np.radians(45.5)
    height = HALF * np.sqrt(2.0) * np.cos(np.radians(0.5))
    box = world.add_body(Box((HALF,) * 3), (0.0, height + 1e-4, 0.0),
                         (np.cos(tilt / 2), 0.0, 0.0, np.sin(tilt / 2)), mass=1.0, friction=1.0)
    _step_until_asleep(world)
    turned = 2.0 * np.degrees(np.arccos(min(1.0, abs(box.orientation[0]))))
    assert abs(turned - 90.0) < 0.1 and abs(box.position[1] - HALF) < 1e-3


def test_sleep_with_substeps_is_deterministic_and_still_sleeps():
    def run():
        world = _world(substeps=3)
        _stack(world, 3)
        ball = world.add_body(Sphere(0.2), (-3.0, 0.2, 0.0), mass=5.0)
        slept = False
        for k in range(150):
            if k == 90:
                ball.velocity = (12.0, 1.0, 0.0)
            slept |= world.step(DT).awake_bodies == 0
        return world.bodies.snapshot(), slept

    (a, slept), (b, _) = run(), run()
    assert slept
    for name in a:
        assert np.array_equal(a[name], b[name]), name


def test_a_world_all_asleep_steps_without_changing_a_bit_and_wakes_as_before():
    """With every body asleep the soft stage only keeps its books (``body_stage._stay_asleep``: no
    rows, nothing solved): 200 such steps leave every body's state, the kept impulses and the
    contacts bit for bit as the first left them; then a particle thrown at the pile and a
    push by hand wake it, as with the whole stage (the particle's rows, the force). A static
    body (which never sleeps) in the world does not keep the stage working."""
    world = _world()
    boxes = _stack(world, 3) + _stack(world, 2, x=3.0)
    wall = world.add_body(Box((0.1, 1.0, 1.0)), (-6.0, 1.0, 0.0), (0.99, 0.0, 0.14, 0.0),
                          mass=math.inf)
    _until_movable_asleep(world)
    world.step(DT)
    before = world.bodies.snapshot()
    held = world.sleeping_impulses.kept.keys.copy()
    for _ in range(200):
        stats = world.step(DT)
    after = world.bodies.snapshot()
    for name in before:
        assert np.array_equal(before[name], after[name]), name
    assert np.array_equal(world.sleeping_impulses.kept.keys, held)
    assert stats.body_contacts == 0 and stats.awake_bodies == 0 and stats.velocity_passes == 0
    assert len(world.body_impulses) == 0 and wall.awake
    world.add_particle((-3.0, 0.5, 0.0), (10.0, 0.0, 0.0), radius=0.05, mass=0.5)
    for _ in range(30):
        world.step(DT)
    assert all(b.awake for b in boxes[:3]) and not any(b.awake for b in boxes[3:])
    _until_movable_asleep(world)
    boxes[4].add_force((0.0, 0.0, 50.0))
    world.step(DT)
    assert boxes[3].awake and boxes[4].awake and boxes[4].velocity[2] > 0.0


def _until_movable_asleep(world, seconds=5.0):
    """Step until every body of finite mass sleeps (a static one never does)."""
    for _ in range(int(seconds / DT)):
        world.step(DT)
        if world.bodies.awake_movable() == 0:
            return
    raise AssertionError(f"still awake after {seconds} s")
