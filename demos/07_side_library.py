"""The cookbook's OpenGL side library: a rotating cube and a translating sphere.

The cookbook closes with a small OpenGL helper that "just renders a rotating cube and a
translating sphere as a demonstration". Here the cube is a drawn box turned a little every step,
and the sphere is a kinematic particle (infinite mass) sliding back and forth on a sine.

Run: pointmass run side_library --set spin=90    Record: pointmass record side_library -o s.mp4
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import BoxVisual, CameraHint, Scene, World, tweak

TITLE = "Side library: cube and sphere"


@dataclass
class Params:
    spin: float = tweak(45.0, -360.0, 360.0, "Cube spin rate [deg/s]")
    cube_size: float = tweak(1.2, 0.2, 3.0, "Cube edge length [m]")
    travel: float = tweak(2.5, 0.0, 5.0, "Sphere travel either side of the centre [m]")
    period: float = tweak(4.0, 0.5, 20.0, "Sphere back-and-forth period [s]")
    radius: float = tweak(0.5, 0.05, 2.0, "Sphere radius [m]")


_AXIS = np.array([1.0, 1.0, 0.3]) / np.linalg.norm([1.0, 1.0, 0.3])
_CUBE_CENTER = np.array([0.0, 1.6, -1.5])
_SPHERE_CENTER = np.array([0.0, 0.0, 1.2])


def rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotation matrix (3, 3) by ``angle`` [rad] about the unit ``axis`` (Rodrigues)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)


def sphere_position(p: Params, t: float) -> np.ndarray:
    """Where the sphere is at time ``t`` [s]: resting on the ground, x = travel·sin(2πt/period)."""
    x = p.travel * math.sin(2.0 * math.pi * t / p.period)
    return _SPHERE_CENTER + np.array([x, p.radius, 0.0])


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    ball = world.add_particle(sphere_position(p, 0.0), mass=math.inf, radius=p.radius)
    cube = BoxVisual(center=tuple(_CUBE_CENTER), half_size=(p.cube_size / 2,) * 3,
                     rotation=np.eye(3), color=(0.90, 0.55, 0.20))
    scene = Scene(world, camera=CameraHint(target=(0.0, 1.0, 0.0), distance=8.0, yaw=20.0,
                                           pitch=18.0),
                  colors=np.array([[0.25, 0.55, 0.90]]), boxes=[cube],
                  handles={"ball": ball, "cube": cube, "params": p}, dt=1.0 / 120.0,
                  # Nothing here has mass to give energy: the live plot shows the motion itself.
                  plots={"sphere x [m]": lambda s: float(s.world.particles.position[ball, 0]),
                         "cube turns": lambda s: math.radians(s.handles["params"].spin)
                         * s.time / (2 * math.pi)})
    return scene


def apply(scene: Scene, p: Params) -> None:
    """Live changes: the next step uses the new rates; sizes change at once."""
    scene.handles["params"] = p
    scene.handles["cube"].half_size = (p.cube_size / 2,) * 3
    scene.world.particles.radius[scene.handles["ball"]] = p.radius


def on_step(scene: Scene, dt: float) -> None:
    """Turn the cube, and give the kinematic sphere the velocity that lands it on its path."""
    p = scene.handles["params"]
    t_next = scene.time + dt
    scene.handles["cube"].rotation = rotation(_AXIS, math.radians(p.spin) * t_next)
    ball = scene.handles["ball"]
    particles = scene.world.particles
    particles.velocity[ball] = (sphere_position(p, t_next) - particles.position[ball]) / dt


def check(scene: Scene) -> None:
    """The cube stays a rigid rotation and the sphere stays on its path."""
    p = scene.handles["params"]
    r = scene.handles["cube"].rotation
    assert np.allclose(r @ r.T, np.eye(3), atol=1e-9)
    expected_angle = math.radians(p.spin) * scene.time
    assert np.allclose(r, rotation(_AXIS, expected_angle), atol=1e-9)
    pos = scene.world.particles.position[scene.handles["ball"]]
    assert np.allclose(pos, sphere_position(p, scene.time), atol=1e-9)
