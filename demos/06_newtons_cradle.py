"""Newton's cradle: five touching spheres on strings; lift one and momentum passes through.

Each ball hangs from a fixed anchor by a rod (a string that stays taut) and touches its
neighbours. The solver's impact stage handles the impact one contact at a time, each time with
the velocities left by the last (the book's sequential propagation): the first ball stops, the
next takes its speed, and so on down the row until the last ball swings out. (A simultaneous
solver would share the momentum among all five instead.) The world uses the defaults.

Keys: none beyond the viewer's.   Run: pointmass run newtons_cradle --set lifted=2
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import AnchoredRod, CameraHint, Scene, SphereCollisions, World, tweak

TITLE = "Newton's cradle"
COUNT = 5
RADIUS = 0.25
LENGTH = 2.0
TOP = 3.0


@dataclass
class Params:
    lifted: int = tweak(1, 1, 4, "Balls lifted and released together", rebuild=True)
    angle: float = tweak(40.0, 5.0, 80.0, "Release angle from the vertical [deg]", rebuild=True)
    restitution: float = tweak(1.0, 0.0, 1.0, "Restitution between balls")


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    xs = (np.arange(COUNT) - (COUNT - 1) / 2) * 2.0 * RADIUS
    anchors = np.column_stack([xs, np.full(COUNT, TOP), np.zeros(COUNT)])
    positions = anchors - (0.0, LENGTH, 0.0)
    swing = math.radians(p.angle)
    for i in range(p.lifted):  # lifted balls keep touching: swing them about their anchors
        positions[i] = anchors[i] + LENGTH * np.array([-math.sin(swing), -math.cos(swing), 0.0])
    balls = world.add_particles(positions, masses=1.0, radii=RADIUS)
    world.add(AnchoredRod(balls, anchors, LENGTH))
    collisions = world.add(SphereCollisions(restitution=p.restitution))
    colors = np.tile((0.78, 0.80, 0.85), (COUNT, 1))
    colors[: p.lifted] = (0.95, 0.55, 0.2)
    return Scene(world, camera=CameraHint(target=(0.0, 1.8, 0.0), distance=5.5, yaw=10.0,
                                          pitch=8.0),
                 colors=colors, dt=1.0 / 240.0,
                 handles={"collisions": collisions, "params": p, "last_peak": 0.0,
                          "first_at_peak": 0.0})


def apply(scene: Scene, p: Params) -> None:
    scene.handles["collisions"].restitution = p.restitution
    scene.handles["params"] = p


def on_step(scene: Scene, dt: float) -> None:
    """Track, during the first swing, the last ball's top speed and the first ball's speed then."""
    if scene.time > 1.2:
        return
    speed = np.linalg.norm(scene.world.particles.velocity, axis=1)
    if speed[-1] > scene.handles["last_peak"]:
        scene.handles["last_peak"] = float(speed[-1])
        scene.handles["first_at_peak"] = float(speed[0])


def check(scene: Scene) -> None:
    """Momentum passed through: the last ball swung out and the first one (nearly) stopped."""
    p = scene.handles["params"]
    if scene.time < 1.2 or p.lifted != 1 or p.restitution < 1.0:
        return
    drop = LENGTH * (1.0 - math.cos(math.radians(p.angle)))
    impact = math.sqrt(2.0 * 9.81 * drop)
    assert scene.handles["last_peak"] > 0.8 * impact, (scene.handles["last_peak"], impact)
    assert scene.handles["first_at_peak"] < 0.2 * impact, scene.handles["first_at_peak"]
