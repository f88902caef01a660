"""Cyclone's ballistic demo: pistol, artillery, fireball and laser rounds fired down a range.

Four kinds of ammunition, each with its own mass, muzzle velocity, gravity and damping (the
book's numbers): the pistol drops gently, artillery lobs in a high arc, the fireball floats up
and slows, the laser flies straight. At most 16 rounds live at once (a ring buffer of particles);
a round dies when it falls below the ground, after 5 s, or past z = 200 m, and is hidden (its
trail too). Automatic fire cycles through the four kinds unless ``auto_cycle`` is off. White
markers stand every 20 m down the range.

Keys: 1–4 pick the ammunition, SPACE or a click fires.   Run: pointmass run ballistic
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from pointmass import BoxVisual, CameraHint, ForceGenerator, Scene, World, choice, tweak

TITLE = "Ballistic"
#: Shown over the scene until the first key or click.
HINT = "Click or press SPACE to fire | 1-4 pick the ammunition"
POOL = 16
MUZZLE = np.array([0.0, 1.5, 0.0])
#: name: (mass [kg], velocity [m/s], gravity [m/s²], damping, color, drawn radius [m])
AMMO = {
    "pistol": (2.0, (0.0, 0.0, 35.0), (0.0, -1.0, 0.0), 0.99, (0.25, 0.55, 0.95), 0.3),
    "artillery": (200.0, (0.0, 30.0, 40.0), (0.0, -20.0, 0.0), 0.99, (0.35, 0.75, 0.40), 0.6),
    "fireball": (1.0, (0.0, 0.0, 10.0), (0.0, 0.6, 0.0), 0.9, (0.95, 0.45, 0.15), 0.5),
    "laser": (0.1, (0.0, 0.0, 100.0), (0.0, 0.0, 0.0), 0.99, (0.95, 0.25, 0.25), 0.2),
}


@dataclass
class Params:
    ammo: str = choice("pistol", AMMO, "Ammunition fired next")
    auto_fire_interval: float = tweak(0.5, 0.0, 5.0, "Fire automatically every … [s] (0: off)")
    auto_cycle: bool = tweak(True, description="Automatic fire cycles through the four kinds")


class RoundGravity(ForceGenerator):
    """m·g_i on each live round, with its own gravity g_i (rows of ``g``, shape (16, 3))."""

    def __init__(self) -> None:
        self.g = np.zeros((POOL, 3))

    def apply(self, particles, dt: float) -> None:
        w = particles.inv_mass[:POOL]
        live = w > 0
        particles.force[:POOL][live] += self.g[live] / w[live, None]


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, 0.0, 0.0))
    # Radius is only drawn here (nothing collides): no collision generator is added.
    world.add_particles(np.tile(MUZZLE, (POOL, 1)), masses=np.inf, radii=0.3)
    gravity = world.add(RoundGravity())
    markers = [BoxVisual(center=(-2.0, 0.3, z), half_size=(0.3, 0.3, 0.3), color=(0.9, 0.9, 0.9))
               for z in range(20, 201, 20)]
    scene = Scene(world, camera=CameraHint(target=(0.0, 9.0, 70.0), distance=95.0, yaw=-65.0,
                                           pitch=12.0, fov=50.0),
                  colors=np.full((POOL, 3), 0.8), hidden=np.ones(POOL, bool), boxes=markers,
                  trails=[], trail_length=90, dt=1.0 / 120.0,
                  handles={"params": p, "gravity": gravity, "next": 0, "age": np.zeros(POOL),
                           "kind": [""] * POOL, "since_fire": 0.0, "cycle": 0})
    return scene


def apply(scene: Scene, p: Params) -> None:
    scene.handles["params"] = p


def fire(scene: Scene, p: Params) -> None:
    """Load the next slot of the ring with a round of the chosen ammunition."""
    h = scene.handles
    i = h["next"]
    h["next"] = (i + 1) % POOL
    mass, velocity, g, damping, color, radius = AMMO[p.ammo]
    parts = scene.world.particles
    parts.position[i] = MUZZLE
    parts.velocity[i] = velocity
    parts.inv_mass[i] = 1.0 / mass
    parts.damping[i] = damping
    parts.radius[i] = radius
    h["gravity"].g[i] = g
    h["age"][i] = 0.0
    h["kind"][i] = p.ammo
    scene.colors[i] = color
    scene.hidden[i] = False
    # A fresh round starts a fresh trail (a slot's old trail ended when it left the list).
    if i not in scene.trails:
        scene.trails.append(i)


def _kill(scene: Scene, dead: np.ndarray) -> None:
    parts = scene.world.particles
    parts.inv_mass[:POOL][dead] = 0.0
    parts.velocity[:POOL][dead] = 0.0
    parts.position[:POOL][dead] = MUZZLE
    scene.hidden[dead] = True
    scene.handles["gravity"].g[dead] = 0.0
    # The renderer draws trails of hidden particles too: drop dead rounds from the trail list,
    # or a line would join the impact point to the parking place.
    scene.trails[:] = [i for i in scene.trails if not dead[i]]


def on_step(scene: Scene, dt: float) -> None:
    h = scene.handles
    p = h["params"]
    h["since_fire"] += dt
    if p.auto_fire_interval > 0 and h["since_fire"] >= p.auto_fire_interval:
        h["since_fire"] = 0.0
        if p.auto_cycle:
            names = list(AMMO)
            fire(scene, dataclasses.replace(p, ammo=names[h["cycle"] % len(names)]))
            h["cycle"] += 1
        else:
            fire(scene, p)
    pos = scene.world.particles.position[:POOL]
    live = ~scene.hidden
    dead = live & ((pos[:, 1] < 0.0) | (h["age"] > 5.0) | (pos[:, 2] > 200.0))
    if dead.any():
        _kill(scene, dead)
    h["age"][~scene.hidden] += dt  # age at the end of this step


def _pick(name: str):
    def pick(scene: Scene, p: Params) -> None:
        p.ammo = name
    return pick


KEYS = {str(k): (f"Ammunition: {name}", _pick(name)) for k, name in enumerate(AMMO, start=1)}
KEYS["SPACE"] = ("Fire", fire)
KEYS["CLICK"] = ("Fire", fire)


def check(scene: Scene) -> None:
    """Live rounds are inside the range; each matches its analytic damped ballistic path."""
    h = scene.handles
    live = ~scene.hidden
    pos = scene.world.particles.position[:POOL]
    assert np.isfinite(pos).all()
    assert (pos[live, 1] >= -1.0).all() and (pos[live, 2] <= 205.0).all()
    assert (np.abs(pos[live, 0]) < 1e-9).all()
    for i in np.flatnonzero(live):
        _, v0, g, d, _, _ = AMMO[h["kind"][i]]
        t = h["age"][i]
        if t < 0.5:
            continue
        k = -np.log(d)  # v' = g - k·v (continuous limit of v *= d^dt)
        v0, g = np.array(v0), np.array(g)
        expected = MUZZLE + g * t / k + (v0 - g / k) * (1 - np.exp(-k * t)) / k
        err = np.linalg.norm(pos[i] - expected)
        assert err < 0.01 * (1 + np.linalg.norm(expected - MUZZLE)), f"round {i} off by {err}"
