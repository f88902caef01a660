"""A cloth: a grid of particles joined by springs, pinned at two corners, with drag and wind.

One Spring generator holds every structural (grid) and shear (diagonal) spring of the cloth, so
a 40×40 cloth costs one compiled loop per step. Springs are drawn coloured by strain. The two
pinned corners have infinite mass: they never move (the oracle), however hard the wind blows.

Keys: none beyond the viewer's.   Run: pointmass run cloth --set wind=6 --set size=30
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Drag, ForceGenerator, Scene, Spring, World, tweak

TITLE = "Cloth"
WIDTH = 3.0


@dataclass
class Params:
    size: int = tweak(20, 4, 60, "Particles along each side", rebuild=True)
    stiffness: float = tweak(250.0, 5.0, 400.0, "Spring constant k [N/m]")
    damping: float = tweak(0.05, 0.0, 1.0, "Spring damping [N·s/m]")
    drag: float = tweak(0.02, 0.0, 0.5, "Air drag k1 [N·s/m]")
    wind: float = tweak(2.0, 0.0, 10.0, "Wind speed through the cloth [m/s]")


class Wind(ForceGenerator):
    """Air pushing on each particle in proportion to the wind's speed relative to it, in gusts."""

    def __init__(self, speed: float, coefficient: float = 0.02) -> None:
        self.speed = speed
        self.coefficient = coefficient
        self.time = 0.0

    def apply(self, particles, dt: float) -> None:
        self.time += dt
        gust = 0.75 + 0.25 * math.sin(1.7 * self.time) * math.sin(0.6 * self.time)
        air = np.array([0.3, 0.0, 1.0]) * self.speed * gust
        moving = particles.inv_mass > 0
        particles.force[moving] += self.coefficient * (air - particles.velocity[moving])


def grid_springs(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs of the structural and shear springs of an n×n grid (row-major)."""
    ids = np.arange(n * n).reshape(n, n)
    pairs = [(ids[:, :-1], ids[:, 1:]), (ids[:-1, :], ids[1:, :]),
             (ids[:-1, :-1], ids[1:, 1:]), (ids[:-1, 1:], ids[1:, :-1])]
    return (np.concatenate([a.ravel() for a, _ in pairs]),
            np.concatenate([b.ravel() for _, b in pairs]))


def build(p: Params) -> Scene:
    n = p.size
    spacing = WIDTH / (n - 1)
    # The stiff springs on light particles need a small step: the scene's dt is 1/240 s.
    world = World(gravity=(0.0, -9.81, 0.0))
    u, v = np.meshgrid(np.arange(n), np.arange(n))
    positions = np.column_stack([u.ravel() * spacing - WIDTH / 2, 4.0 - v.ravel() * spacing,
                                 np.zeros(n * n)])
    masses = np.full(n * n, 0.02)
    masses[[0, n - 1]] = math.inf  # the two top corners hang on pins
    cloth = world.add_particles(positions, masses=masses)
    a, b = grid_springs(n)
    rest = np.linalg.norm(positions[a] - positions[b], axis=1)
    springs = world.add(Spring(cloth[a], cloth[b], p.stiffness, rest, damping=p.damping))
    drag = world.add(Drag(p.drag, 0.0))
    wind = world.add(Wind(p.wind))
    colors = np.where(((u + v) % 2).ravel()[:, None] == 0, (0.85, 0.25, 0.3), (0.95, 0.9, 0.85))
    return Scene(world, camera=CameraHint(target=(0.0, 2.5, 0.5), distance=7.5, yaw=35.0,
                                          pitch=15.0),
                 colors=colors, point_radius=0.35 * spacing, dt=1.0 / 240.0,
                 handles={"springs": springs, "drag": drag, "wind": wind,
                          "pins": positions[[0, n - 1]].copy(), "pin_ids": cloth[[0, n - 1]]})


def apply(scene: Scene, p: Params) -> None:
    scene.handles["springs"].spring_constant = p.stiffness
    scene.handles["springs"].damping = p.damping
    scene.handles["drag"].k1 = p.drag
    scene.handles["wind"].speed = p.wind


def check(scene: Scene) -> None:
    """The pinned corners have not moved, and the cloth hangs below them."""
    pos = scene.world.particles.position
    assert np.array_equal(pos[scene.handles["pin_ids"]], scene.handles["pins"])
    assert pos[:, 1].max() <= scene.handles["pins"][:, 1].max() + 0.5
