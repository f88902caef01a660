"""A small demo for the viewer tests: balls dropped on the ground (not in demos/, so the tests do
not change when the gallery does)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Ground, Scene, SphereCollisions, World, tweak

TITLE = "Viewer test: balls"


@dataclass
class Params:
    count: int = tweak(3, 1, 20, "Number of balls", rebuild=True)
    bounce: float = tweak(0.5, 0.0, 1.0, "Ground restitution")
    flag: bool = tweak(False, description="A checkbox")


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    xs = np.linspace(-1.0, 1.0, p.count) if p.count > 1 else np.zeros(1)
    for x in xs:
        world.add_particle((float(x), 0.3, 0.0), mass=1.0, radius=0.3)
    ground = world.add(Ground(height=0.0, restitution=p.bounce))
    world.add(SphereCollisions(restitution=0.5))
    return Scene(world, camera=CameraHint(target=(0.0, 0.5, 0.0), distance=6.0, yaw=0.0,
                                          pitch=15.0),
                 handles={"ground": ground, "fired": 0},
                 plots={"v_y": lambda s: float(s.world.particles.velocity[0, 1])})


def apply(scene: Scene, p: Params) -> None:
    scene.handles["ground"].restitution = p.bounce


def _fire(scene: Scene, p: Params) -> None:
    scene.handles["fired"] += 1


KEYS = {"SPACE": ("Fire", _fire)}
