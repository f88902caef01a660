"""A particle launched under gravity, leaving a trail: the cookbook's first simulation.

The cookbook's first test creates `Particle(Vector3(10, 10, 10))` — its first argument is the
velocity — registers gravity and ticks at 60 Hz. Here the same launch from the origin, with a
ground to land on. Horizontal motion is untouched by gravity and the (frictionless) ground, so
x = z = 10·t exactly: the oracle.

Keys: none beyond the viewer's.   Run: pointmass run projectile --set gravity=3.7
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Ground, Scene, World, tweak

TITLE = "Projectile"


@dataclass
class Params:
    vx: float = tweak(10.0, 0.0, 30.0, "Launch velocity along x [m/s]", rebuild=True)
    vy: float = tweak(10.0, 0.0, 30.0, "Launch velocity up [m/s]", rebuild=True)
    vz: float = tweak(10.0, 0.0, 30.0, "Launch velocity along z [m/s]", rebuild=True)
    gravity: float = tweak(9.81, 0.0, 30.0, "Gravity [m/s²]")
    restitution: float = tweak(0.5, 0.0, 1.0, "Bounce of the ground")


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -p.gravity, 0.0))
    ball = world.add_particle((0.0, 0.0, 0.0), (p.vx, p.vy, p.vz), mass=1.0, radius=0.3)
    ground = world.add(Ground(0.0, restitution=p.restitution))
    # The camera follows the ball: it bounces on along x and z for ever.
    return Scene(world, camera=CameraHint(target=(10.5, 2.5, 10.5), distance=28.0, yaw=-45.0,
                                          pitch=18.0, follow=ball),
                 colors=np.array([[0.95, 0.45, 0.2]]), trails=[ball], trail_length=600,
                 handles={"ball": ball, "ground": ground, "launch": (p.vx, p.vz)},
                 dt=1.0 / 60.0)


def apply(scene: Scene, p: Params) -> None:
    scene.world.gravity = (0.0, -p.gravity, 0.0)
    scene.handles["ground"].restitution = p.restitution


def check(scene: Scene) -> None:
    """Horizontal motion is uniform: x = vx·t and z = vz·t."""
    x, y, z = scene.world.particles.position[scene.handles["ball"]]
    vx, vz = scene.handles["launch"]
    assert abs(x - vx * scene.time) < 1e-6 * (1 + abs(x)), (x, vx * scene.time)
    assert abs(z - vz * scene.time) < 1e-6 * (1 + abs(z)), (z, vz * scene.time)
    assert y > -0.3, f"the ball sank through the ground: y = {y}"
