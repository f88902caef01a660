"""A tower of boxes: rigid bodies (the book's second half) standing still, until you throw a ball.

Ten 1 kg unit boxes stacked on the ground (μ 0.5, no bounce) stand with the top box still to
a millimetre: the solver's warm-started contact manifolds and friction with angular terms hold
them (rigid-notes §3: PyBullet's tower drifts 0.26 m in 10 s). Space or a click throws a heavy
ball at the tower; R builds it again.

Keys: Space / click throw a ball, R rebuild.   Run: pointmass run box_tower --set count=14
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Ground, Scene, World, tweak
from pointmass.rigid.shapes import Box, Sphere

TITLE = "Box tower (rigid bodies)"
#: Shown over the scene until the first key or click.
HINT = "Click or press SPACE to throw a ball at the tower"
HALF = 0.5


@dataclass
class Params:
    count: int = tweak(10, 1, 30, "Boxes in the tower", rebuild=True)
    friction: float = tweak(0.5, 0.0, 1.5, "Friction coefficient of boxes and ground",
                            rebuild=True)
    ball_speed: float = tweak(12.0, 1.0, 40.0, "Speed of a thrown ball [m/s]")
    ball_mass: float = tweak(8.0, 0.5, 50.0, "Mass of a thrown ball [kg]")


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    world.add(Ground(friction=p.friction))
    boxes = [world.add_body(Box((HALF, HALF, HALF)), (0.0, HALF + 2 * HALF * k, 0.0), mass=1.0,
                            friction=p.friction) for k in range(p.count)]
    height = 2 * HALF * p.count
    top = boxes[-1]
    scene = Scene(world, camera=CameraHint(target=(0.0, height / 2, 0.0),
                                           distance=max(8.0, 1.6 * height), yaw=35.0,
                                           pitch=12.0),
                  dt=1.0 / 60.0,
                  handles={"boxes": boxes, "params": p, "thrown": 0,
                           "top_start": top.position.copy()},
                  plots={"top box height [m]": lambda s: float(top.position[1])})
    return scene


def apply(scene: Scene, p: Params) -> None:
    scene.handles["params"] = p


def throw(scene: Scene, p: Params) -> None:
    """A ball from the camera's side, aimed at the tower's middle."""
    h = scene.handles
    middle = 2 * HALF * len(h["boxes"]) / 2
    start = np.array([-8.0, middle + 1.0, 3.0])
    aim = np.array([0.0, middle, 0.0]) - start
    velocity = p.ball_speed * aim / np.linalg.norm(aim) + (0.0, 2.0, 0.0)
    scene.world.add_body(Sphere(0.35), start, velocity=velocity, mass=p.ball_mass,
                         friction=0.3)
    h["thrown"] += 1


KEYS = {"SPACE": ("Throw a ball at the tower", throw), "CLICK": ("Throw a ball", throw)}


def check(scene: Scene) -> None:
    """Untouched, the tower stands: the top box within 1 mm of where it started, nothing
    moving faster than 1 mm/s."""
    h = scene.handles
    if h["thrown"]:
        return
    bodies = scene.world.bodies
    drift = np.linalg.norm(h["boxes"][-1].position - h["top_start"])
    assert drift < 1e-3, f"the top box drifted {drift * 1e3:.2f} mm"
    assert np.abs(bodies.velocity).max() < 1e-3
