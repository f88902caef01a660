"""Two particles (1 kg and 20 kg) bound by a strong spring; the light one is launched.

The cookbook's "putting it all together" example: springs pull the pair together while gravity
accelerates both equally. Its checklist: the heavier particle is less affected, the lighter one
does most of the curving. The cookbook starts both at (2, 2, 2), where a spring has no direction;
here the heavy one starts one rest length away. Springs, gravity and the (frictionless) ground
are all vertical or internal, so the pair's horizontal momentum never changes: the oracle.

Keys: none beyond the viewer's.   Run: pointmass run spring_pair --set stiffness=20
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Ground, Scene, Spring, World, tweak

TITLE = "Spring pair"


@dataclass
class Params:
    stiffness: float = tweak(100.0, 1.0, 500.0, "Spring constant k [N/m]")
    rest_length: float = tweak(2.0, 0.5, 5.0, "Spring rest length [m]")
    heavy_mass: float = tweak(20.0, 1.0, 100.0, "Mass of the heavy particle [kg]", rebuild=True)
    launch_speed: float = tweak(30.0, 0.0, 60.0, "Forward launch speed of the light one [m/s]",
                                rebuild=True)


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    light = world.add_particle((2.0, 2.0, 2.0), (0.0, 10.0, p.launch_speed), mass=1.0,
                               radius=0.2)
    heavy = world.add_particle((2.0, 2.0, 2.0 - p.rest_length), mass=p.heavy_mass, radius=0.45)
    spring = world.add(Spring(light, heavy, p.stiffness, p.rest_length))
    world.add(Ground(0.0, restitution=0.4))
    momentum = world.particles.momentum().copy()
    # The camera follows the heavy end: the launched pair travels on.
    return Scene(world, camera=CameraHint(target=(2.0, 2.0, 6.0), distance=16.0, yaw=-70.0,
                                          pitch=15.0, follow=heavy),
                 colors=np.array([[0.3, 0.6, 0.95], [0.9, 0.35, 0.25]]), trails=[light, heavy],
                 handles={"spring": spring, "momentum": momentum}, dt=1.0 / 120.0)


def apply(scene: Scene, p: Params) -> None:
    scene.handles["spring"].spring_constant = p.stiffness
    scene.handles["spring"].rest_length = p.rest_length


def check(scene: Scene) -> None:
    """Horizontal momentum (x and z) is conserved: the spring's forces are internal."""
    now = scene.world.particles.momentum()
    start = scene.handles["momentum"]
    assert np.allclose(now[[0, 2]], start[[0, 2]], atol=1e-6), (now, start)
