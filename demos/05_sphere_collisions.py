"""Two spheres meeting head-on and two off-centre; restitution is a slider.

The cookbook's hard-constraint chapter made visible: closing velocity along the contact normal,
restitution, and momentum shared by inverse mass. The head-on pair (masses 1 and 3 kg) obeys the
1-D collision formula v1' = (m1·v1 + m2·v2 − m2·e·(v1 − v2)) / (m1 + m2): the oracle. The
off-centre pair glances off along the line between the centres. They relaunch every few seconds.

Keys: none beyond the viewer's.   Run: pointmass run sphere_collisions --set restitution=1
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Scene, SphereCollisions, World, tweak

TITLE = "Sphere collisions"
RADIUS = 0.5
MASSES = (1.0, 3.0, 1.0, 1.0)


@dataclass
class Params:
    restitution: float = tweak(0.8, 0.0, 1.0, "Coefficient of restitution e")
    speed: float = tweak(4.0, 0.5, 10.0, "Approach speed of each sphere [m/s]")
    offset: float = tweak(0.5, 0.0, 0.95, "Off-centre pair: offset / (2·radius)")
    relaunch: float = tweak(3.0, 1.0, 10.0, "Seconds between launches [s]")


def launch(scene: Scene, p: Params) -> None:
    """Put the spheres back at their starting points with their approach velocities."""
    b = p.offset * 2.0 * RADIUS
    pos = np.array([(-3.0, 1.0, -1.5), (3.0, 1.0, -1.5), (-3.0, 1.0, 1.5), (3.0, 1.0, 1.5 + b)])
    vel = np.array([(p.speed, 0, 0), (-p.speed, 0, 0), (p.speed, 0, 0), (-p.speed, 0, 0)], float)
    particles = scene.world.particles
    particles.position[:] = pos
    particles.velocity[:] = vel
    scene.handles["launched_at"] = scene.time
    scene.handles["before"] = vel[:2, 0].copy()
    scene.handles["e"] = p.restitution


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, 0.0, 0.0))
    world.add_particles(np.zeros((4, 3)), masses=MASSES, radii=RADIUS)
    collisions = world.add(SphereCollisions(restitution=p.restitution))
    colors = np.array([(0.9, 0.3, 0.25), (0.25, 0.55, 0.9), (0.95, 0.75, 0.2), (0.35, 0.75, 0.4)])
    scene = Scene(world, camera=CameraHint(target=(0.0, 1.0, 0.0), distance=32.0, yaw=0.0,
                                           pitch=55.0),
                  colors=colors, trails=[0, 1, 2, 3], trail_length=120, dt=1.0 / 120.0,
                  handles={"collisions": collisions, "params": p})
    launch(scene, p)
    return scene


def apply(scene: Scene, p: Params) -> None:
    scene.handles["collisions"].restitution = p.restitution
    scene.handles["params"] = p


def on_step(scene: Scene, dt: float) -> None:
    p = scene.handles["params"]
    if scene.time - scene.handles["launched_at"] >= p.relaunch - 1e-9:
        launch(scene, p)


def check(scene: Scene) -> None:
    """Once the head-on pair has separated, its velocities follow the 1-D collision formula."""
    p = scene.handles["params"]
    since = scene.time - scene.handles["launched_at"]
    gap = 6.0 - 2.0 * RADIUS
    if since < gap / (2.0 * p.speed) + 0.1:
        return  # not met yet
    (m1, m2), (v1, v2), e = MASSES[:2], scene.handles["before"], scene.handles["e"]
    expected1 = (m1 * v1 + m2 * v2 - m2 * e * (v1 - v2)) / (m1 + m2)
    expected2 = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / (m1 + m2)
    got = scene.world.particles.velocity[:2, 0]
    assert np.allclose(got, (expected1, expected2), atol=1e-6), (got, expected1, expected2)
