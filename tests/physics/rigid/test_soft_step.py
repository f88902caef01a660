"""Issue 26's acceptance scenes for the body stage (the soft step, ``solver/body_soft.py``), each
with ``World()`` defaults plus the scene's own materials; dt = 1/60, g = 9.81.

* point 1: towers of N unit boxes (1 kg, μ 0.5, e 0) stacked exactly on a ground of μ 0.5,
  sleep off: the top box's drift after 60 s. "Drift" is read two ways: sideways (the
  benchmark's "top drift xy", a tower that leans or walks) and in height (how far the soft
  contacts let the stack settle);
* point 2: the 210-box pyramid and the 1000-box pit of benchmarks/bench_rigid.py, sleep off;
* point 5: a 1 m box (face down) and a sphere dropped from 0.9–1.1 m with e = 0.5 on body and
  ground: the rebound height is e²·h. The drop height h is read as the gap under the body
  (its lowest point above the floor), and the rebound as the highest gap after the bounce;
* point 8: boxes colliding without gravity (e 0 and 0.5, μ 0 and 0.5): linear and angular
  momentum about the origin.

A target the soft step misses is a ratchet at its measured value with the issue's target named.
The impulses stage that ran before the soft step (removed at stop 44) missed points 1 (its 20-
and 30-box towers fell within 60 s), 2 (the pyramid's apex drifted 8.0 mm in 10 s; the pit
still moved at 0.090 m/s), 5 (it bounced off a speculative point above the floor: 0.272–0.310·h)
and 8 (its position projection turned the boxes: |ΔL|/|L| 3.5e-3 at e 0, μ 0).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.box_box import box_box
from pointmass.rigid.manifold import empty_outputs
from pointmass.rigid.shapes import Box, Sphere

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "benchmarks"))
import bench_rigid  # the benchmark's scenes, built the same way

G = 9.81
DT = 1.0 / 60.0
MU = 0.5


# --- point 1: towers ---------------------------------------------------------------------------

def tower(n: int, seconds: float = 60.0, **world) -> tuple[float, float]:
    """(sideways drift, height change) of the top box of an n-box tower after ``seconds``."""
    world = pm.World(gravity=(0.0, -G, 0.0), sleep=False, **world)
    world.add(pm.Ground(restitution=0.0, friction=MU))
    boxes = [world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.5 + k, 0.0), mass=1.0, friction=MU,
                            restitution=0.0) for k in range(n)]
    for _ in range(round(seconds / DT)):
        world.step(DT)
    top = boxes[-1].position
    return math.hypot(top[0], top[2]), float(top[1] - (n - 0.5))


@pytest.mark.parametrize("n", [5, 10, pytest.param(20, marks=pytest.mark.slow),
                               pytest.param(30, marks=pytest.mark.slow)])
def test_tower_stands_60_s_with_sleep_off(n):
    # measured, sideways: 0.06, 0.10, 1.3, 1.1 mm (down: up to 3.8 mm, the stack's sag)
    drift, sink = tower(n)
    assert drift < 0.01
    assert abs(sink) < 0.01


# --- point 2: pyramid and pit ------------------------------------------------------------------

def _pyramid_world(**world_args):
    """The benchmark's 210-box pyramid (bench_rigid.pyramid), apex last."""
    scene = bench_rigid.pyramid()
    world = pm.World(gravity=(0.0, -G, 0.0), sleep=False, **world_args)
    world.add(pm.Ground(restitution=0.0, friction=MU))
    bodies = [world.add_body(Box((scene.half,) * 3), x, mass=1.0, friction=MU, restitution=0.0)
              for x in scene.position]
    return world, bodies


def pyramid(seconds: float = 10.0, **world_args) -> tuple[float, float]:
    """(apex drift [m], max speed [m/s]) of the 210-box pyramid after ``seconds``."""
    world, bodies = _pyramid_world(**world_args)
    start = bodies[-1].position.copy()
    for _ in range(round(seconds / DT)):
        world.step(DT)
    drift = float(np.linalg.norm(bodies[-1].position - start))
    return drift, float(np.linalg.norm(world.bodies.velocity, axis=1).max())


def _overlap(pos, quat, half):
    """Deepest box–box overlap [m] of equal cubes (the benchmark's SAT check, margin 0)."""
    size = np.full(3, half)
    normal, points, depth, ids = empty_outputs()
    deepest = 0.0
    for i in range(len(pos)):
        near = np.flatnonzero(np.linalg.norm(pos[i + 1:] - pos[i], axis=1)
                              < 2 * math.sqrt(3) * half) + i + 1
        for j in near:
            got = box_box(pos[i], quat[i], size, pos[j], quat[j], size, 0.0, normal, points,
                          depth, ids)
            if got:
                deepest = max(deepest, float(depth[:got].max()))
    return deepest


def pit(n: int = 1000, seconds: float = 10.0, seed: int = 0,
        **world_args) -> tuple[float, float]:
    """(max speed [m/s], deepest box overlap [m]) of the benchmark's box pit after ``seconds``."""
    scene = bench_rigid.pit(n, seed)  # the benchmark's layout
    pos, q, side = scene.position, scene.orientation, 2 * scene.pit
    world = pm.World(gravity=(0.0, -G, 0.0), sleep=False, **world_args)
    world.add(pm.Ground(restitution=0.0, friction=MU))
    for normal in ((1, 0, 0), (-1, 0, 0), (0, 0, 1), (0, 0, -1)):
        world.add(pm.Plane(normal, -side / 2, restitution=0.0, friction=MU))
    for x, qq in zip(pos, q):
        world.add_body(Box((0.25, 0.25, 0.25)), x, qq, mass=1.0, friction=MU, restitution=0.0)
    for _ in range(round(seconds / DT)):
        world.step(DT)
    b = world.bodies
    speed = float(np.linalg.norm(b.velocity, axis=1).max())
    return speed, _overlap(b.position, b.orientation, 0.25)


@pytest.mark.slow
def test_pyramid_stands_still_with_sleep_off():
    # measured: apex 0.2 mm, max speed 0.28 mm/s (with the soft rows over-relaxed)
    drift, speed = pyramid()
    assert drift < 0.005
    assert speed < 0.01


@pytest.mark.slow
def test_box_pit_comes_to_rest_with_sleep_off():
    # measured before the soft rows were over-relaxed: max speed 0.44 mm/s, overlap 0.17 mm
    speed, overlap = pit()
    assert speed < 0.05
    assert overlap < 0.005


# --- point 5: drops ----------------------------------------------------------------------------

def drop(shape: str, height: float, e: float = 0.5, **world) -> float:
    """Rebound height over drop height of a body whose lowest point starts ``height`` above a
    ground of restitution ``e`` (the body's too)."""
    world = pm.World(gravity=(0.0, -G, 0.0), **world)
    world.add(pm.Ground(restitution=e, friction=MU))
    if shape == "box":
        half = 0.5
        body = world.add_body(Box((half, half, half)), (0.0, half + height, 0.0), mass=1.0,
                              friction=MU, restitution=e)
    else:
        half = 0.5
        body = world.add_body(Sphere(half), (0.0, half + height, 0.0), mass=1.0, friction=MU,
                              restitution=e)
    went_up = False
    peak = 0.0
    for _ in range(round(3.0 / DT)):
        world.step(DT)
        if body.velocity[1] > 0.0:
            went_up = True
        if went_up:  # the step after the last rising one may be the highest
            peak = max(peak, body.position[1] - half)
            if body.velocity[1] <= 0.0:
                break
    return peak / height


@pytest.mark.parametrize("shape", ["box", "sphere"])
@pytest.mark.parametrize("height", [0.9, 0.95, 1.0, 1.05, 1.1])
def test_drop_rebounds_to_e_squared_of_its_height(shape, height):
    # measured (leapfrog, stop 42): box and sphere 0.2426 / 0.2430 / 0.2474 / 0.2432 / 0.2435,
    # within the 3 % (before, with semi-implicit Euler's flight losing h·v/2 of height
    # down and up: box 0.2480 / 0.2497 / 0.2416 / 0.2454 / 0.2499, a ratchet at 4 %)
    assert drop(shape, height) == pytest.approx(0.25, rel=0.03)


# --- point 8: momentum -------------------------------------------------------------------------

def _momenta(world):
    b = world.bodies
    m = 1.0 / b.inv_mass
    p = (m[:, None] * b.velocity).sum(axis=0)
    ang = np.cross(b.position, m[:, None] * b.velocity).sum(axis=0)
    for i in range(b.count):
        ang += b.angular_momentum(i)
    return p, ang


def collide(e: float, mu: float, steps: int = 240, **world) -> tuple[float, float]:
    """Largest relative drift of linear and angular momentum about the origin when two
    spinning boxes meet off-centre without gravity."""
    world = pm.World(gravity=(0.0, 0.0, 0.0), sleep=False, **world)
    world.add_body(Box((0.5, 0.3, 0.4)), (-2.0, 0.2, 0.1), (0.9, 0.1, 0.3, 0.2), mass=2.0,
                   friction=mu, restitution=e, velocity=(3.0, 0.0, 0.2),
                   angular_velocity=(0.5, 2.0, -1.0))
    world.add_body(Box((0.4, 0.4, 0.2)), (1.0, -0.1, 0.0), (0.8, -0.2, 0.1, 0.4), mass=1.0,
                   friction=mu, restitution=e, velocity=(-2.0, 0.3, 0.0),
                   angular_velocity=(-1.0, 0.5, 3.0))
    p0, l0 = _momenta(world)
    scale_p = np.linalg.norm(p0)
    scale_l = np.linalg.norm(l0)
    worst_p = worst_l = 0.0
    touched = 0
    for _ in range(steps):
        touched += world.step(DT).body_contacts > 0
        p, ang = _momenta(world)
        worst_p = max(worst_p, float(np.linalg.norm(p - p0)) / scale_p)
        worst_l = max(worst_l, float(np.linalg.norm(ang - l0)) / scale_l)
    assert touched > 0  # they met
    return worst_p, worst_l


@pytest.mark.parametrize("e", [0.0, 0.5])
@pytest.mark.parametrize("mu", [0.0, 0.5])
def test_zero_gravity_collision_keeps_momentum_by_construction(e, mu):
    # measured: linear ≤ 4.5e-16, angular ≤ 1.4e-13 (equal and opposite impulses at one point)
    linear, angular = collide(e, mu)
    assert linear < 1e-9
    assert angular < 1e-9


# --- joints (``solver/joint_soft.py``) -----------------------------------------------------------

def test_holds_a_body_on_two_joints_that_cannot_both_hold():
    """Issue 30's hang under the soft step: a 55 g box held by a ball joint and a hinge to two
    world points 105 cm apart (its joint points 16 cm apart: the joints cannot all hold), hit
    from below by a 2.3 kg box at 16 m/s. Every step returns and the kinetic energy never
    passes what the blow and a 20 m fall could give (the contradiction is soft: the tree
    takes one joint exactly, the other is a soft Gauss–Seidel row whose bias closes a gap at
    3 m/s at most)."""
    world = pm.World()
    box = world.add_body(Box((0.1, 0.05, 0.08)), (0.0, 1.0, 0.0), mass=0.055)
    world.add(pm.BallJoint(box, (0.08, 0.0, 0.0), None, (0.5, 1.5, 0.5)))
    world.add(pm.HingeJoint(box, (-0.08, 0.0, 0.0), None, (-0.2, 0.6, 0.4),
                            axis=(0.6, 0.0, 0.8)))
    world.add_body(Box((0.2, 0.1, 0.2)), (0.02, 0.5, 0.01), mass=2.3, velocity=(0.0, 16.0, 0.0))
    limit = world.kinetic_energy() + 2.355 * G * 20.0
    for _ in range(120):
        world.step(DT)
        assert world.kinetic_energy() < limit
    assert np.isfinite(world.bodies.position).all()


def test_hangs_a_chain_of_ten_boxes_still_and_closed():
    """Ten 1 kg boxes jointed end to end from a world anchor (a tree: solved exactly each
    substep): after 10 s every joint is shut to < 0.5 mm and nothing moves faster than
    1 mm/s."""
    world = pm.World(gravity=(0.0, -G, 0.0))
    above = None
    for k in range(10):
        box = world.add_body(Box((0.05, 0.1, 0.05)), (0.0, -0.1 - 0.2 * k, 0.0), mass=1.0)
        world.add(pm.BallJoint(box, (0.0, 0.1, 0.0), above))
        above = box
    for _ in range(600):
        world.step(DT)
    assert world.joints.separations().max() < 0.5e-3
    assert np.abs(world.bodies.velocity).max() < 1e-3
