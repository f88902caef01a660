"""Boxes poured into a walled pit: rigid bodies tumbling, stacking and coming to rest.

Small boxes in random orientations drop in layers into a pit with four walls and settle into a
heap (rigid-notes §3's pit: the only engine of the three we measured whose 1000 boxes are at
rest after 10 s). Friction μ 0.5, no bounce.

Keys: R rebuilds.   Run: pointmass run box_pit --set count=1000
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import BoxVisual, CameraHint, Plane, Scene, World, tweak
from pointmass.rigid.quaternion import quat_from_axis_angle_numpy
from pointmass.rigid.shapes import Box

TITLE = "Box pit (rigid bodies)"
HALF = 0.25


@dataclass
class Params:
    count: int = tweak(300, 10, 1000, "Boxes", rebuild=True)
    friction: float = tweak(0.5, 0.0, 1.5, "Friction coefficient", rebuild=True)
    seed: int = tweak(1, 0, 99, "Random seed for the orientations", rebuild=True)


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    per = math.ceil(math.sqrt(p.count / 4))
    side = 0.9 * per + 0.4
    half_side = side / 2
    world.add(Plane((0.0, 1.0, 0.0), 0.0, friction=p.friction))
    for normal in ((1, 0, 0), (-1, 0, 0), (0, 0, 1), (0, 0, -1)):
        world.add(Plane(normal, -half_side, friction=p.friction))
    rng = np.random.default_rng(p.seed)
    k = np.arange(p.count)
    grid = np.column_stack([k % per, k // (per * per), (k // per) % per]).astype(float)
    positions = np.column_stack([-half_side + 0.2 + 0.45 + 0.9 * grid[:, 0], 0.6 + 0.9 * grid[:, 1],
                                 -half_side + 0.2 + 0.45 + 0.9 * grid[:, 2]])
    positions += rng.uniform(-0.05, 0.05, positions.shape)
    for pos in positions:
        axis = rng.normal(size=3)
        q = quat_from_axis_angle_numpy(axis / np.linalg.norm(axis), rng.uniform(0, math.pi))
        world.add_body(Box((HALF, HALF, HALF)), pos, q, mass=1.0, friction=p.friction)
    bodies = world.bodies
    # The walls are planes (no thickness): drawn as outlines about as tall as the heap.
    heap = p.count * (2 * HALF) ** 3 / (side * side) / 0.6  # loose packing, about 60 % full
    depth = max(1.0, 1.5 * heap)
    walls = [BoxVisual(center=(x, depth / 2, z), half_size=(hx, depth / 2, hz),
                       color=(0.55, 0.6, 0.7), wireframe=True)
             for x, z, hx, hz in ((-half_side, 0, 0.0, half_side), (half_side, 0, 0.0, half_side),
                                  (0, -half_side, half_side, 0.0), (0, half_side, half_side, 0.0))]
    return Scene(world, camera=CameraHint(target=(0.0, 0.8, 0.0), distance=1.5 * side + 3.0,
                                          yaw=30.0, pitch=35.0),
                 boxes=walls, dt=1.0 / 60.0, handles={"side": side},
                 plots={"fastest box [m/s]": lambda s: float(
                     np.linalg.norm(bodies.velocity, axis=1).max())})


def check(scene: Scene) -> None:
    """Every box is finite and inside the pit, above the floor."""
    b = scene.world.bodies
    assert np.isfinite(b.position).all()
    half_side = scene.handles["side"] / 2
    assert (np.abs(b.position[:, [0, 2]]) < half_side).all(), "a box left the pit"
    assert (b.position[:, 1] > 0.0).all(), "a box sank through the floor"
