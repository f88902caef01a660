"""A ball pit: N spheres poured into a box with walls, colliding until they come to rest.

The stress test for the engine: sphere–sphere contacts found through a spatial hash (linear in
N), the box's floor and four walls, and the resolver in sweep mode for thousands of contacts.
N goes up to 20 000 (a rebuild parameter); the box grows with N so the pile stays a few layers
deep. Friction (Coulomb, in the sweep) lets the pile settle instead of slumping forever.
The oracle: nothing escapes the box and the spheres barely overlap.

Keys: SPACE stirs the pit (kicks every ball up).   Run: pointmass run ball_pit --set count=5000
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import Box, BoxVisual, CameraHint, Scene, SphereCollisions, World, tweak

TITLE = "Ball pit"
RADIUS = 0.1


@dataclass
class Params:
    count: int = tweak(2000, 10, 20000, "Number of spheres", rebuild=True)
    restitution: float = tweak(0.5, 0.0, 1.0, "Bounce of spheres and walls")
    friction: float = tweak(0.5, 0.0, 1.5, "Coulomb friction μ between spheres and walls")
    gravity: float = tweak(9.81, 0.0, 30.0, "Gravity [m/s²]")
    seed: int = tweak(1, 0, 9999, "Random seed of the pour", rebuild=True)


def box_half_width(count: int) -> float:
    """Half the box's width [m]: room for the pile to settle about 1.5 m deep."""
    volume = count * (2 * RADIUS) ** 3 / 0.6
    return max(1.0, 0.5 * math.sqrt(volume / 1.5))


def build(p: Params) -> Scene:
    rng = np.random.default_rng(p.seed)
    half = box_half_width(p.count)
    world = World(gravity=(0.0, -p.gravity, 0.0))
    # Pour from a loose lattice above the box, jittered so the pile does not stack in columns.
    side = max(1, int((2 * half - 2 * RADIUS) / (2.4 * RADIUS)))
    k = np.arange(p.count)
    lattice = np.column_stack([k % side, k // (side * side), (k // side) % side]) * 2.4 * RADIUS
    positions = lattice + np.array([-half + 1.2 * RADIUS, 0.5, -half + 1.2 * RADIUS])
    positions += rng.uniform(-0.1, 0.1, positions.shape) * RADIUS
    world.add_particles(positions, rng.normal(0.0, 0.3, positions.shape), radii=RADIUS,
                        masses=1.0)
    box = world.add(Box((-half, 0.0, -half), (half, 100.0, half), restitution=p.restitution,
                        friction=p.friction))
    spheres = world.add(SphereCollisions(restitution=p.restitution, friction=p.friction))
    hue = positions[:, 1] / max(positions[:, 1].max(), 1e-9)
    colors = np.column_stack([0.95 - 0.6 * hue, 0.35 + 0.4 * np.sin(np.pi * hue), 0.25 + 0.7 * hue])
    walls = [BoxVisual(center=(x, 0.4, z), half_size=(hx, 0.4, hz), color=(0.45, 0.5, 0.6),
                       wireframe=True)
             for x, z, hx, hz in ((-half, 0, 0.0, half), (half, 0, 0.0, half),
                                  (0, -half, half, 0.0), (0, half, half, 0.0))]
    return Scene(world, camera=CameraHint(target=(0.0, 0.5, 0.0), distance=3.2 * half + 1.5,
                                          yaw=30.0, pitch=35.0),
                 colors=colors, boxes=walls, dt=1.0 / 60.0,
                 handles={"box": box, "spheres": spheres, "half": half})


def apply(scene: Scene, p: Params) -> None:
    scene.handles["box"].restitution = p.restitution
    scene.handles["spheres"].restitution = p.restitution
    scene.handles["box"].friction = p.friction
    scene.handles["spheres"].friction = p.friction
    scene.world.gravity = (0.0, -p.gravity, 0.0)


def stir(scene: Scene, p: Params) -> None:
    scene.world.particles.velocity[:, 1] += 4.0


KEYS = {"SPACE": ("Stir the pit", stir)}


def check(scene: Scene) -> None:
    """Every sphere is inside the box, and overlaps are small (under 10 % of a radius)."""
    pos = scene.world.particles.position
    half = scene.handles["half"]
    slack = 0.1 * RADIUS
    assert (np.abs(pos[:, [0, 2]]) <= half - RADIUS + slack).all(), "a sphere left the box"
    assert (pos[:, 1] >= RADIUS - slack).all(), "a sphere sank through the floor"
    overlap = scene.world.contacts.penetration.max(initial=0.0)  # left after the last step
    assert overlap < 0.1 * RADIUS, f"spheres overlap by {overlap:.4f} m"
