"""Cyclone's platform: a rigid truss of six particles and fifteen rods that tips under a load.

Two particles rest on the ground (the pivot edge) and four form a 7 m × 2 m top deck that
overhangs further on one side, so the truss is a see-saw. Every pair of particles is joined by
a rod, which makes it rigid. A load on the deck is spread bilinearly over its four corners as
extra mass, as Cyclone does: walk it past the pivot and the platform tips the other way. (Its
weight as forces on 1 kg corners made a 50 kg load fling the truss over: the load must have
inertia too, so the tip is no faster than gravity.)

Keys: A/D move the load along the deck, W/S across it (hold them to walk).
Run: pointmass run platform --set load_mass=25
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from pointmass import BoxVisual, CameraHint, Ground, Rod, Scene, World, tweak
from pointmass.controls import walk, wasd_keys

TITLE = "Platform (see-saw truss)"
#: Shown over the scene until the first key or click.
HINT = "Hold A/D to move the load along the deck, W/S to move it across"
G = 9.81
X_LEFT, X_RIGHT = -3.0, 4.0
CORNERS = np.array([2, 3, 4, 5])  # left-front, left-back, right-front, right-back
RADIUS = 0.15  # the particles are balls resting *on* the ground, not points half sunk into it
POSITIONS = np.array([(0, 0, 1), (0, 0, -1), (X_LEFT, 2, 1), (X_LEFT, 2, -1), (X_RIGHT, 2, 1),
                      (X_RIGHT, 2, -1)], float) + np.array([0.0, RADIUS, 0.0])


@dataclass
class Params:
    load_mass: float = tweak(10.0, 0.0, 50.0, "Mass of the load [kg]")
    particle_mass: float = tweak(1.0, 0.1, 10.0, "Mass of each truss particle [kg]",
                                 rebuild=True)


class Load:
    """The load, shared bilinearly by the deck's four corners; ``u`` in [0, 1] runs along the
    deck (left to right), ``v`` in [0, 1] across it (front to back)."""

    def __init__(self, mass: float, particle_mass: float) -> None:
        self.mass, self.particle_mass, self.u, self.v = mass, particle_mass, 0.5, 0.5

    def weights(self) -> np.ndarray:
        u, v = self.u, self.v
        return np.array([(1 - u) * (1 - v), (1 - u) * v, u * (1 - v), u * v])

    def spread(self, particles) -> None:
        """Give each corner its share of the load as extra mass (gravity then weighs it)."""
        particles.inv_mass[CORNERS] = 1.0 / (self.particle_mass + self.mass * self.weights())


def build(p: Params) -> Scene:
    # World defaults: a 50 kg load on 1 kg pivots rests on the ground without dipping into it
    # (the solver's exact solve for small, badly conditioned sets; measured 3e-14 m).
    world = World(gravity=(0.0, -G, 0.0))
    world.add_particles(POSITIONS, masses=p.particle_mass, radii=RADIUS,
                        damping=0.3)  # damping calms the see-saw's slams
    a, b = np.array(list(itertools.combinations(range(6), 2))).T
    rods = world.add(Rod(a, b, np.linalg.norm(POSITIONS[a] - POSITIONS[b], axis=1)))
    world.add(Ground(restitution=0.1))
    load = Load(p.load_mass, p.particle_mass)
    load.spread(world.particles)
    box = BoxVisual(half_size=(0.35, 0.35, 0.35), color=(0.85, 0.3, 0.2))
    scene = Scene(world, camera=CameraHint(target=(0.5, 1.0, 0.0), distance=12.0, yaw=20.0,
                                           pitch=15.0),
                  colors=np.array([(0.9, 0.9, 0.9)] * 2 + [(0.3, 0.6, 0.95)] * 4),
                  boxes=[box], dt=1.0 / 120.0,
                  handles={"load": load, "box": box, "rods": rods})
    _place_box(scene)
    return scene


def apply(scene: Scene, p: Params) -> None:
    scene.handles["load"].mass = p.load_mass
    scene.handles["load"].spread(scene.world.particles)


def _place_box(scene: Scene) -> None:
    pos = scene.world.particles.position[CORNERS]
    under = scene.handles["load"].weights() @ pos
    scene.handles["box"].center = tuple(under + np.array([0.0, 0.4, 0.0]))


def move(scene: Scene, dx: float, dz: float) -> None:
    """Move the load by (dx, dz) metres along and across the deck."""
    load = scene.handles["load"]
    load.u = float(np.clip(load.u + dx / (X_RIGHT - X_LEFT), 0.0, 1.0))
    load.v = float(np.clip(load.v - dz / 2.0, 0.0, 1.0))
    load.spread(scene.world.particles)
    _place_box(scene)


def on_keys_held(scene: Scene, keys: frozenset, dt: float) -> None:
    walk(scene, keys, dt, move)  # held keys walk the load at 4 m/s


def on_step(scene: Scene, dt: float) -> None:
    _place_box(scene)


KEYS = wasd_keys(lambda scene, p, dx, dz: move(scene, 0.5 * dx, 0.5 * dz), "the load")


def check(scene: Scene) -> None:
    """Rods keep their lengths within 1 %, and no ball sinks more than 5 cm into the ground."""
    parts = scene.world.particles
    assert np.isfinite(parts.position).all()
    rods = scene.handles["rods"]
    error = np.abs(rods.current_lengths(parts) / rods.length - 1)
    assert error.max() < 0.01, f"a rod is off its length by {error.max():.2%}"
    assert parts.position[:, 1].min() > RADIUS - 0.05, "the platform sank into the ground"
