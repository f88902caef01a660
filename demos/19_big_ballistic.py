"""Cyclone's bigballistic: rigid rounds of four kinds fired at a wall of boxes.

Rounds are solid spheres (I = 0.4·m·r²) with the book's masses, radii, damping and each its own
gravity (a ``BodyGravity``-style generator adds m·(g_round − g_world)): the pistol flies nearly
flat, artillery (200 kg) lobs into the top of the wall (its muzzle velocity lowered from the
book's (0, 30, 40), which clears the wall by 10 m), the fireball floats and slows, the laser goes
straight at 100 m/s (the book's tunnels through boxes, R10: here speculative contacts stop it
with the world's defaults). The boxes are 1 m, μ 0.9, e 0.1. At most ``POOL`` rounds live at once:
the oldest is reloaded as the next.

Keys: 1–4 pick the ammunition, SPACE or a click fires, R rebuilds the wall.
Run: pointmass run big_ballistic --set rows=6
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Ground, Scene, World, choice, tweak
from pointmass.rigid.bodies import inverse_inertia
from pointmass.rigid.forces import BodyForceGenerator
from pointmass.rigid.quaternion import world_inv_inertia_numpy
from pointmass.rigid.shapes import BOX, Box, Sphere, mass_properties

TITLE = "Big ballistic (rigid rounds)"
#: Shown over the scene until the first key or click.
HINT = "Click or press SPACE to fire at the wall | 1-4 pick the ammunition"
GRAVITY = np.array([0.0, -10.0, 0.0])
MUZZLE = np.array([0.0, 1.5, 0.0])
WALL_Z = 20.0
HALF = 0.5
POOL = 24
#: name: (mass [kg], velocity [m/s], gravity [m/s²], damping, radius [m])
AMMO = {
    "pistol": (1.5, (0.0, 0.0, 20.0), (0.0, -0.5, 0.0), 0.99, 0.2),
    "artillery": (200.0, (0.0, 10.0, 30.0), (0.0, -21.0, 0.0), 0.99, 0.4),
    "fireball": (4.0, (0.0, -0.5, 10.0), (0.0, 0.3, 0.0), 0.9, 0.6),
    "laser": (0.1, (0.0, 0.0, 100.0), (0.0, 0.0, 0.0), 0.99, 0.2),
}


@dataclass
class Params:
    ammo: str = choice("pistol", AMMO, "Ammunition fired next")
    rows: int = tweak(4, 1, 8, "Rows of boxes in the wall", rebuild=True)
    columns: int = tweak(5, 1, 9, "Boxes per row", rebuild=True)
    box_mass: float = tweak(8.0, 0.5, 100.0, "Mass of a box [kg]", rebuild=True)


class RoundGravity(BodyForceGenerator):
    """Each round's own gravity: m·(g_round − g_world) on top of the world's."""

    def __init__(self) -> None:
        self.rounds: list[int] = []
        self.extra: list[np.ndarray] = []

    def apply(self, bodies, dt: float) -> None:
        for i, extra in zip(self.rounds, self.extra, strict=True):
            if bodies.inv_mass[i] > 0:
                bodies.force[i] += extra / bodies.inv_mass[i]


def build(p: Params) -> Scene:
    world = World(gravity=GRAVITY)
    world.add(Ground(friction=0.9, restitution=0.1))
    boxes = []
    for row in range(p.rows):
        for col in range(p.columns):
            x = (col - (p.columns - 1) / 2) * 2 * HALF
            boxes.append(world.add_body(Box((HALF, HALF, HALF)), (x, HALF + 2 * HALF * row,
                                                                   WALL_Z),
                                        mass=p.box_mass, friction=0.9, restitution=0.1,
                                        linear_damping=0.95, angular_damping=0.8))
    gravity = world.add(RoundGravity())
    return Scene(world, camera=CameraHint(target=(0.0, 2.0, 10.5), distance=22.0, yaw=-125.0,
                                          pitch=16.0),
                 dt=1.0 / 60.0,
                 handles={"params": p, "boxes": boxes, "gravity": gravity, "rounds": [],
                          "kinds": [], "next": 0})


def apply(scene: Scene, p: Params) -> None:
    scene.handles["params"] = p


def fire(scene: Scene, p: Params) -> None:
    """A new round at the muzzle (a new body, or the oldest one reloaded once POOL live)."""
    h = scene.handles
    mass, velocity, g, damping, radius = AMMO[p.ammo]
    world = scene.world
    gravity = h["gravity"]
    if len(h["rounds"]) < POOL:
        body = world.add_body(Sphere(radius), MUZZLE, velocity=velocity, mass=mass,
                              friction=0.9, restitution=0.1, linear_damping=damping,
                              angular_damping=0.8)
        h["rounds"].append(body)
        h["kinds"].append(p.ammo)
        gravity.rounds.append(body.index)
        gravity.extra.append(np.asarray(g) - GRAVITY)
        return
    k = h["next"]
    h["next"] = (k + 1) % POOL
    body = h["rounds"][k]
    b, i = world.bodies, body.index
    _, moments = mass_properties(Sphere(radius), mass=mass)
    b.position[i] = MUZZLE
    b.orientation[i] = (1.0, 0.0, 0.0, 0.0)
    b.velocity[i] = velocity
    b.angular_velocity[i] = 0.0
    b.inv_mass[i] = 1.0 / mass
    b.inv_inertia[i] = inverse_inertia(moments)
    b.inv_inertia_world[i] = world_inv_inertia_numpy(b.orientation[i], b.inv_inertia[i])
    b.size[i] = (radius, 0.0, 0.0)
    b.linear_damping[i] = damping
    b.wake(i)  # written in place above, which does not wake a sleeping round
    h["kinds"][k] = p.ammo
    gravity.extra[k] = np.asarray(g) - GRAVITY


def _pick(name: str):
    def pick(scene: Scene, p: Params) -> None:
        p.ammo = name
    return pick


KEYS = {str(k): (f"Ammunition: {name}", _pick(name)) for k, name in enumerate(AMMO, start=1)}
KEYS["SPACE"] = ("Fire", fire)
KEYS["CLICK"] = ("Fire", fire)


def lowest_points(bodies) -> np.ndarray:
    """Height of each body's lowest point [m]: y − r for spheres, y − Σ|R₁ₖ|·hₖ for boxes."""
    q = bodies.orientation
    w, x, y, z = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    row = np.column_stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)])
    reach = np.where(bodies.shape == BOX, (np.abs(row) * bodies.size).sum(axis=1),
                     bodies.size[:, 0])
    return bodies.position[:, 1] - reach


def check(scene: Scene) -> None:
    """Rounds and boxes are finite and nothing has sunk below the ground (1 cm allowed)."""
    bodies = scene.world.bodies
    assert np.isfinite(bodies.position).all() and np.isfinite(bodies.velocity).all()
    low = lowest_points(bodies)
    assert low.min() > -0.01, f"body {int(low.argmin())} is {-low.min():.3f} m under the ground"
