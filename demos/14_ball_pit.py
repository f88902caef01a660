"""A ball pit: N spheres poured into a box with walls, colliding until they come to rest.

The spheres pour in from a spout above the box over ``pour_seconds`` (waiting spheres are parked
below the floor, hidden and immovable), so the pile grows and flows for most of a recording.
The stress test for the engine: sphere–sphere contacts found through a spatial hash (linear in
N), the box's floor and four walls, and the default solver on thousands of contacts.
N goes up to 20 000 (a rebuild parameter); the box grows with N so the pile stays a few layers
deep. Friction (Coulomb) lets the pile settle instead of slumping forever.
The oracle: nothing escapes the box and the spheres barely overlap.

Keys: SPACE stirs the pit (kicks every ball up).   Run: pointmass run ball_pit --set count=5000
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import BoxContainer, BoxVisual, CameraHint, Scene, SphereCollisions, World, tweak

TITLE = "Ball pit"
#: Shown over the scene until the first key or click.
HINT = "Press SPACE to stir the pit"
RADIUS = 0.1


@dataclass
class Params:
    count: int = tweak(2000, 10, 20000, "Number of spheres", rebuild=True)
    restitution: float = tweak(0.5, 0.0, 1.0, "Bounce of spheres and walls")
    friction: float = tweak(0.5, 0.0, 1.5, "Coulomb friction μ between spheres and walls")
    gravity: float = tweak(9.81, 0.0, 30.0, "Gravity [m/s²]")
    seed: int = tweak(1, 0, 9999, "Random seed of the pour", rebuild=True)
    pour_seconds: float = tweak(7.0, 0.5, 30.0, "Seconds the pour lasts", rebuild=True)


#: Where waiting spheres are parked [m]: a lattice below the floor (immovable pairs are skipped
#: by the collision search, and the lattice keeps them out of each other's hash cells).
PARK_DEPTH = -20.0

def box_half_width(count: int) -> float:
    """Half the box's width [m]: room for the pile to settle about 1.5 m deep."""
    volume = count * (2 * RADIUS) ** 3 / 0.6
    return max(1.0, 0.5 * math.sqrt(volume / 1.5))


def build(p: Params) -> Scene:
    rng = np.random.default_rng(p.seed)
    half = box_half_width(p.count)
    world = World(gravity=(0.0, -p.gravity, 0.0))
    side = math.ceil(math.sqrt(p.count))
    k = np.arange(p.count)
    parked = np.column_stack([k % side, np.zeros(p.count), k // side]) * 3 * RADIUS
    parked += (-1.5 * RADIUS * side, PARK_DEPTH, -1.5 * RADIUS * side)
    world.add_particles(parked, radii=RADIUS, masses=np.inf)
    box = world.add(BoxContainer((-half, 0.0, -half), (half, 100.0, half),
                                 restitution=p.restitution, friction=p.friction))
    spheres = world.add(SphereCollisions(restitution=p.restitution, friction=p.friction))
    # Colors by pour order: the first spheres red at the bottom, the last blue on top.
    order = k / max(p.count - 1, 1)
    colors = np.column_stack([0.95 - 0.6 * order, 0.35 + 0.4 * np.sin(np.pi * order),
                              0.25 + 0.7 * order])
    depth = 1.6 * pile_depth(p.count, half)  # the heap stands higher than the mean depth
    walls = [BoxVisual(center=(x, depth / 2, z), half_size=(hx, depth / 2, hz),
                       color=(0.55, 0.6, 0.7), wireframe=True)
             for x, z, hx, hz in ((-half, 0, 0.0, half), (half, 0, 0.0, half),
                                  (0, -half, half, 0.0), (0, half, half, 0.0))]
    spout = (rng.uniform(-0.3, 0.3, (p.count, 2)) * half).tolist()
    return Scene(world, camera=CameraHint(target=(0.0, 0.6, 0.0), distance=3.2 * half + 2.0,
                                          yaw=30.0, pitch=35.0),
                 colors=colors, boxes=walls, dt=1.0 / 60.0, hidden=np.ones(p.count, bool),
                 handles={"box": box, "spheres": spheres, "half": half, "released": 0,
                          "rate": p.count / p.pour_seconds, "spout": spout,
                          "spout_height": depth + 0.5})


def pile_depth(count: int, half: float) -> float:
    """Height the settled pile reaches [m] (random packing about 0.6 of the volume)."""
    return count * (2 * RADIUS) ** 3 / 0.6 / (2 * half) ** 2 + 2 * RADIUS


def on_step(scene: Scene, dt: float) -> None:
    """Release the spheres due by now from the spout, a few per step, in pour order."""
    h = scene.handles
    due = min(len(h["spout"]), math.floor(h["rate"] * (scene.time + dt)))
    p = scene.world.particles
    for i in range(h["released"], due):
        x, z = h["spout"][i]
        p.position[i] = (x, h["spout_height"] + 2.5 * RADIUS * (i % 3), z)
        p.velocity[i] = (0.0, -1.0, 0.0)
        p.set_mass(i, 1.0)
        scene.hidden[i] = False
    h["released"] = max(h["released"], due)


def apply(scene: Scene, p: Params) -> None:
    scene.handles["box"].restitution = p.restitution
    scene.handles["spheres"].restitution = p.restitution
    scene.handles["box"].friction = p.friction
    scene.handles["spheres"].friction = p.friction
    scene.world.gravity = (0.0, -p.gravity, 0.0)


def stir(scene: Scene, p: Params) -> None:
    scene.world.particles.velocity[~scene.hidden, 1] += 4.0


KEYS = {"SPACE": ("Stir the pit", stir)}


def check(scene: Scene) -> None:
    """Every poured sphere is inside the box, and overlaps are small (under 10 % of a
    radius)."""
    pos = scene.world.particles.position[~scene.hidden]
    half = scene.handles["half"]
    slack = 0.1 * RADIUS
    assert (np.abs(pos[:, [0, 2]]) <= half - RADIUS + slack).all(), "a sphere left the box"
    assert (pos[:, 1] >= RADIUS - slack).all(), "a sphere sank through the floor"
    overlap = scene.world.contacts.penetration.max(initial=0.0)  # left after the last step
    assert overlap < 0.1 * RADIUS, f"spheres overlap by {overlap:.4f} m"
