"""Joints and sleeping islands (rigid/sleep.py): jointed bodies share one island, so a ragdoll
falls asleep as one and wakes as one; a sleeping joint's rows are left out of the solve."""

import numpy as np

from pointmass.demo import load_demo
from pointmass.rigid.shapes import Sphere

DT = 1 / 60


def _ragdoll(seed: int = 1):
    demo = load_demo("ragdoll")
    params = demo.default_params()
    params.seed = seed
    return demo.build(params).world


def _until_asleep(world, seconds: float = 12.0) -> int:
    """Step until every body sleeps; returns the steps taken (fails after ``seconds``)."""
    for step in range(int(seconds / DT)):
        world.step(DT)
        if not world.bodies.awake.any():
            return step
    raise AssertionError(f"still awake after {seconds} s: {world.bodies.awake.tolist()}")


def test_a_ragdoll_at_rest_falls_asleep_as_one_island():
    """Thrown down, it comes to rest and all 12 bones fall asleep in the same step, in one
    island (jointed bones touch only through their joints: without the joints' links, the
    bones that lie apart would be islands of their own)."""
    world = _ragdoll()
    b = world.bodies
    woke = b.awake.copy()
    for _ in range(int(12.0 / DT)):
        world.step(DT)
        if not b.awake.any():
            break
        assert b.awake.all() or not b.awake.any(), "part of the ragdoll fell asleep alone"
        woke = b.awake.copy()
    assert woke.all() and not b.awake.any()
    assert np.unique(b.island).size == 1
    assert world.joints.separations().max() < 2e-3


def test_asleep_the_joints_leave_the_bodies_exactly_where_they_are():
    """While the island sleeps, the joints' rows (and their projection) are skipped: 2 s more
    change no bit of a pose, and the joints keep their warm start for the wake."""
    world = _ragdoll()
    _until_asleep(world)
    b = world.bodies
    pose = b.position.tobytes(), b.orientation.tobytes()
    kept = world.joints.point.copy()
    for _ in range(120):
        world.step(DT)
    assert (b.position.tobytes(), b.orientation.tobytes()) == pose
    assert np.array_equal(world.joints.point, kept)


def test_a_ball_on_one_bone_wakes_the_whole_ragdoll():
    """A ball dropped on the highest bone wakes that bone's island: every bone, at once."""
    world = _ragdoll()
    _until_asleep(world)
    b = world.bodies
    high = int(np.argmax(b.position[:, 1]))
    top = b.position[high] + np.array([0.0, 0.4, 0.0])
    ball = world.add_body(Sphere(0.08), tuple(top), velocity=(0.0, -3.0, 0.0), mass=2.0)
    for _ in range(30):
        world.step(DT)
        if b.awake[:ball].any():
            break
    assert b.awake[:ball].all()


def test_reruns_with_sleep_are_bit_identical():
    """Same inputs, same bits, through a fall, the sleep and a wake by a push."""
    runs = []
    for _ in range(2):
        world = _ragdoll(4)
        _until_asleep(world)
        world.bodies.add_force(3, (0.0, 0.0, 400.0))
        for _ in range(60):
            world.step(DT)
        b = world.bodies
        runs.append((b.position.tobytes(), b.orientation.tobytes(), b.awake.tobytes(),
                     world.joints.point.tobytes()))
    assert runs[0] == runs[1]
