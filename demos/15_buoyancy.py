"""Balls of different densities bobbing in water whose density you choose.

Each ball gets Archimedes' lift from a Buoyancy generator: none above the surface, ρ·V·g when
fully under, and the submerged fraction in between (Cyclone's sign error would push a half-
submerged ball down). Water drag damps the bobbing. A ball lighter than the water floats where
the submerged fraction equals its density ratio (the oracle); a heavier one sinks to the bottom.

Keys: none beyond the viewer's.   Run: pointmass run buoyancy --set water_density=1500
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import (
    BoxVisual,
    Buoyancy,
    CameraHint,
    Drag,
    Ground,
    PlaneVisual,
    Scene,
    World,
    tweak,
)

TITLE = "Buoyancy"
RADIUS = 0.3
VOLUME = 4.0 / 3.0 * math.pi * RADIUS**3
DENSITIES = (250.0, 500.0, 750.0, 900.0, 1200.0)  # ball densities [kg/m³]
BOTTOM = -3.0


@dataclass
class Params:
    water_density: float = tweak(1000.0, 100.0, 3000.0, "Water density ρ [kg/m³]")
    water_drag: float = tweak(200.0, 0.0, 600.0, "Drag on the balls k1 [N·s/m]")
    drop_height: float = tweak(2.0, 0.0, 6.0, "Height the balls drop from [m]", rebuild=True)


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    xs = (np.arange(len(DENSITIES)) - 2.0) * 1.2
    positions = np.column_stack([xs, np.full(len(xs), p.drop_height), np.zeros(len(xs))])
    masses = np.array(DENSITIES) * VOLUME
    balls = world.add_particles(positions, masses=masses, radii=RADIUS)
    # max_depth = the ball's radius: fully submerged once its centre is a radius under water.
    buoyancy = world.add(Buoyancy(RADIUS, VOLUME, 0.0, p.water_density))
    drag = world.add(Drag(p.water_drag, 0.0))
    world.add(Ground(BOTTOM, restitution=0.1))
    shade = (np.array(DENSITIES) - 200.0) / 1100.0
    colors = np.column_stack([0.95 - 0.5 * shade, 0.8 - 0.5 * shade, 0.3 + 0.2 * shade])
    water = PlaneVisual(center=(0.0, 0.0, 0.0), normal=(0.0, 1.0, 0.0), half_size=(4.0, 2.0),
                        color=(0.2, 0.45, 0.85, 0.45))
    pool = BoxVisual(center=(0.0, BOTTOM / 2, 0.0), half_size=(4.0, -BOTTOM / 2, 2.0),
                     color=(0.3, 0.5, 0.8), wireframe=True)
    return Scene(world, camera=CameraHint(target=(0.0, -0.5, 0.0), distance=10.0, yaw=10.0,
                                          pitch=12.0),
                 colors=colors, planes=[water], boxes=[pool], ground_height=BOTTOM, dt=1.0 / 120.0,
                 handles={"balls": balls, "buoyancy": buoyancy, "drag": drag})


def apply(scene: Scene, p: Params) -> None:
    scene.handles["buoyancy"].liquid_density = p.water_density
    scene.handles["drag"].k1 = p.water_drag


def floating_height(density: float, water_density: float) -> float:
    """Where a ball of ``density`` floats [m]: submerged fraction (s − y)/(2s) = ρ_ball/ρ_water."""
    return RADIUS - 2.0 * RADIUS * density / water_density


def check(scene: Scene) -> None:
    """Once settled, floaters sit at their equilibrium depth and sinkers on the bottom."""
    if scene.time < 8.0 or scene.handles["drag"].k1 < 150.0:
        return
    rho = scene.handles["buoyancy"].liquid_density
    y = scene.world.particles.position[scene.handles["balls"], 1]
    for density, height in zip(DENSITIES, y):
        if density < rho:
            expected = floating_height(density, rho)
            assert abs(height - expected) < 0.02, (density, height, expected)
        else:
            assert height < BOTTOM + RADIUS + 0.05, (density, height)
