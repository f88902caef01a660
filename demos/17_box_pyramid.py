"""A pyramid wall of boxes: 210 unit boxes, 20 at the base, that stands until you knock it.

One box deep, 2 cm gaps between neighbours: the solver has to hold a load path through every
row by friction and contact alone (rigid-notes §3: PyBullet's collapses at its defaults; here
the apex stays within a few centimetres over 10 s). Space or a click throws a heavy ball at it.

Keys: Space / click throw a ball.   Run: pointmass run box_pyramid --set base=12
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Ground, Scene, World, tweak
from pointmass.rigid.shapes import Box, Sphere

TITLE = "Box pyramid (rigid bodies)"
#: Shown over the scene until the first key or click.
HINT = "Click or press SPACE to throw a ball at the wall"
HALF = 0.5
GAP = 0.02


@dataclass
class Params:
    base: int = tweak(20, 2, 30, "Boxes in the bottom row", rebuild=True)
    friction: float = tweak(0.5, 0.1, 1.5, "Friction coefficient", rebuild=True)
    ball_speed: float = tweak(15.0, 1.0, 40.0, "Speed of a thrown ball [m/s]")


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    world.add(Ground(friction=p.friction))
    pitch = 2 * HALF + GAP
    boxes = []
    for row in range(p.base):
        count = p.base - row
        for k in range(count):
            x = (k - (count - 1) / 2) * pitch
            boxes.append(world.add_body(Box((HALF, HALF, HALF)), (x, HALF + 2 * HALF * row, 0.0),
                                        mass=1.0, friction=p.friction))
    height = 2 * HALF * p.base
    apex = boxes[-1]
    return Scene(world, camera=CameraHint(target=(0.0, height / 2.5, 0.0),
                                          distance=1.5 * p.base * pitch + 4.0, yaw=20.0,
                                          pitch=10.0),
                 dt=1.0 / 60.0,
                 handles={"boxes": boxes, "params": p, "thrown": 0,
                          "apex_start": apex.position.copy()},
                 plots={"apex height [m]": lambda s: float(apex.position[1])})


def apply(scene: Scene, p: Params) -> None:
    scene.handles["params"] = p


def throw(scene: Scene, p: Params) -> None:
    """A 20 kg ball at the wall's lower third, from the front."""
    h = scene.handles
    target = np.array([0.0, 2 * HALF * h["params"].base / 3, 0.0])
    start = target + np.array([0.0, 1.0, 12.0])
    velocity = p.ball_speed * (target - start) / np.linalg.norm(target - start)
    velocity[1] += 1.5  # a little lift against the drop over the throw
    scene.world.add_body(Sphere(0.5), start, velocity=velocity, mass=20.0, friction=0.3)
    h["thrown"] += 1


KEYS = {"SPACE": ("Throw a ball at the wall", throw), "CLICK": ("Throw a ball", throw)}


def check(scene: Scene) -> None:
    """Untouched, the wall stands: no box's height changed by 0.1 m, the apex within 5 cm."""
    h = scene.handles
    bodies = scene.world.bodies
    assert np.isfinite(bodies.position).all()
    if h["thrown"]:
        return
    drift = np.linalg.norm(h["boxes"][-1].position - h["apex_start"])
    assert drift < 0.05, f"the apex moved {drift * 100:.1f} cm"
    heights = np.array([b.position[1] for b in h["boxes"]])
    rows = np.round((heights - HALF) / (2 * HALF))
    assert np.abs(heights - (HALF + 2 * HALF * rows)).max() < 0.1, "a box dropped a row"
