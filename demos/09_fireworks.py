"""Cyclone's fireworks: nine kinds of firework that burst into payloads of other kinds.

A ring buffer of 1024 particles. Each firework type has a rule (the book's numbers): a fuse age
range, a launch velocity range, a damping, and payloads of (type, count). When its fuse runs
out a firework dies and its children start where it was, with its velocity plus their own
random velocity. Dead particles are hidden and pinned. Randomness is seeded, so a run is
repeatable; one firework is launched automatically every ``launch_interval`` seconds.

The book's bursts are a handful of dots a couple of metres across; at a screen's distance they
do not read. So the final sparks (payloads of kinds that do not burst again) come ``sparks``
times as many, children leave with ``spread`` times their own random velocity, and the show is
drawn at night: every particle glows (an unlit core and halo, added to the sky) with a short
fading trail, and a spark dims over the last ``FADE`` seconds of its life.

Keys: 1–9 launch a firework of that type from x = −5, 0 or 5.   Run: pointmass run fireworks
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Scene, World, tweak

TITLE = "Fireworks"
#: Shown over the scene until the first key or click.
HINT = "Press 1-9 to launch a firework of that type"
POOL = 1024
#: type: (age range [s], velocity min, velocity max [m/s], damping, payloads [(type, count)])
RULES = {
    1: ((0.5, 1.4), (-5, 25, -5), (5, 28, 5), 0.1, [(3, 5), (5, 5)]),
    2: ((0.5, 1.0), (-5, 10, -5), (5, 20, 5), 0.8, [(4, 2)]),
    3: ((0.5, 1.5), (-5, -5, -5), (5, 5, 5), 0.1, []),
    4: ((0.25, 0.5), (-20, 5, -5), (20, 5, 5), 0.2, []),
    5: ((0.5, 1.0), (-20, 2, -5), (20, 18, 5), 0.01, [(3, 5)]),
    6: ((3.0, 5.0), (-5, 5, -5), (5, 10, 5), 0.95, []),
    7: ((4.0, 5.0), (-5, 50, -5), (5, 60, 5), 0.01, [(8, 10)]),
    8: ((0.25, 0.5), (-1, -1, -1), (1, 1, 1), 0.01, []),
    9: ((3.0, 5.0), (-15, 10, -5), (15, 15, 5), 0.95, []),
}
#: The final sparks of one burst share a color drawn from these (rockets keep their kind's
#: color from COLORS), so neighbouring bursts tell apart.
SPARK_COLORS = np.array([(1.0, 0.25, 0.2), (1.0, 0.75, 0.15), (0.35, 1.0, 0.4), (0.3, 0.55, 1.0),
                         (0.85, 0.35, 1.0), (1.0, 0.45, 0.75), (0.3, 1.0, 1.0), (1.0, 1.0, 0.8)])
#: A spark (a kind with no payload) dims to DIM of its color over its last FADE seconds [s].
FADE = 0.6
DIM = 0.15
#: By type: whether it bursts into a payload (type 0 is unused).
BURSTS = np.array([False] + [bool(RULES[k][4]) for k in sorted(RULES)])
#: Types the automatic launcher picks from: the ones that rise and burst, the big bursters
#: (1 and 5) more often than the small ones, the slow riser (7) and the comet (9).
SHOWY = (1, 1, 1, 2, 5, 5, 7, 9)
COLORS = np.array([(1, 1, 1), (1.0, 0.3, 0.2), (1.0, 0.8, 0.2), (0.3, 0.9, 0.4), (0.3, 0.6, 1.0),
                   (0.9, 0.4, 1.0), (1.0, 0.6, 0.2), (0.4, 1.0, 1.0), (1.0, 1.0, 0.6),
                   (1.0, 0.5, 0.7)], float)


@dataclass
class Params:
    seed: int = tweak(1, 0, 9999, "Random seed", rebuild=True)
    launch_interval: float = tweak(0.4, 0.0, 10.0, "Launch a random firework every … [s] (0: off)")
    sparks: int = tweak(6, 1, 20, "Final sparks per burst, × the book's count")
    spread: float = tweak(2.5, 0.5, 5.0, "Children's own random velocity, × the book's")


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    world.add_particles(np.zeros((POOL, 3)), masses=np.inf)
    return Scene(world, camera=CameraHint(target=(0.0, 9.0, 0.0), distance=26.0, yaw=0.0,
                                          pitch=-6.0, fov=60.0),
                 colors=np.ones((POOL, 3)), hidden=np.ones(POOL, bool), point_radius=0.12,
                 dt=1.0 / 60.0, trails=[], trail_length=8, sky="night", glow=True,
                 handles={"params": p, "rng": np.random.default_rng(p.seed), "next": 0,
                          "type": np.zeros(POOL, int), "age": np.zeros(POOL),
                          "color": np.ones((POOL, 3)),
                          "since_launch": p.launch_interval, "launches": 0, "dts": [],
                          "pressed": False})


def apply(scene: Scene, p: Params) -> None:
    scene.handles["params"] = p


def create(scene: Scene, kind: int, position, velocity, spread: float = 1.0,
           color=None) -> None:
    """Start one firework of ``kind`` in the next slot of the ring (taking over the oldest
    particle if the pool is full), with ``spread`` times its kind's random velocity, in
    ``color`` (default: its kind's)."""
    h = scene.handles
    rng = h["rng"]
    (age_lo, age_hi), v_lo, v_hi, damping, _ = RULES[kind]
    i = h["next"]
    h["next"] = (i + 1) % POOL
    parts = scene.world.particles
    parts.position[i] = position
    parts.velocity[i] = np.asarray(velocity) + spread * rng.uniform(v_lo, v_hi)
    parts.inv_mass[i] = 1.0
    parts.damping[i] = damping
    h["type"][i] = kind
    h["age"][i] = rng.uniform(age_lo, age_hi)
    h["color"][i] = COLORS[kind] if color is None else color
    scene.colors[i] = h["color"][i]
    if scene.hidden[i]:                   # a dead slot's trail ended when it was hidden
        scene.trails.append(i)
    scene.hidden[i] = False


def payload(kind: int, p: Params) -> list[tuple[int, int]]:
    """What a firework of ``kind`` bursts into: the book's payload, with the final sparks (kinds
    that do not burst again) ``p.sparks`` times as many."""
    return [(child, count * p.sparks if not RULES[child][4] else count)
            for child, count in RULES[kind][4]]


def kill(scene: Scene, i: int) -> None:
    """Hide and pin particle ``i``, and stop its trail."""
    parts = scene.world.particles
    scene.hidden[i] = True
    parts.inv_mass[i] = 0.0
    parts.velocity[i] = 0.0
    scene.trails.remove(i)


def launch(scene: Scene, kind: int) -> None:
    x = scene.handles["rng"].choice([-5.0, 0.0, 5.0])
    create(scene, kind, (x, 0.0, 0.0), (0.0, 0.0, 0.0))


def on_step(scene: Scene, dt: float) -> None:
    h = scene.handles
    h["dts"].append(dt)
    p = h["params"]
    h["since_launch"] += dt
    if p.launch_interval > 0 and h["since_launch"] >= p.launch_interval:
        h["since_launch"] = 0.0
        # The show opens with a big burster, so its first second already has a burst.
        launch(scene, int(h["rng"].choice(SHOWY)) if h["launches"] else 1)
        h["launches"] += 1
    parts = scene.world.particles
    live = ~scene.hidden
    h["age"][live] -= dt
    expired = np.flatnonzero(live & ((h["age"] < 0) | (parts.position[:, 1] < 0)))
    for i in expired:  # a fixed order, so the random draws are repeatable
        pos, vel, kind = parts.position[i].copy(), parts.velocity[i].copy(), h["type"][i]
        kill(scene, i)
        shade = SPARK_COLORS[h["rng"].integers(len(SPARK_COLORS))]
        for child, count in payload(kind, p):
            for _ in range(count):
                create(scene, child, pos, vel, p.spread, None if BURSTS[child] else shade)
    fade(scene)


def fade(scene: Scene) -> None:
    """Dim each live spark over the last FADE seconds of its life (rockets that will burst keep
    their full color), so a burst dies away instead of blinking out."""
    h = scene.handles
    live = np.flatnonzero(~scene.hidden)
    kinds = h["type"][live]
    level = np.where(BURSTS[kinds], 1.0, np.clip(h["age"][live] / FADE, DIM, 1.0))
    scene.colors[live] = h["color"][live] * level[:, None]


def _launcher(kind: int):
    def press(scene: Scene, p: Params) -> None:
        scene.handles["pressed"] = True
        launch(scene, kind)
    return press


KEYS = {str(k): (f"Launch a type-{k} firework", _launcher(k)) for k in RULES}


def check(scene: Scene) -> None:
    """Live particles are finite and within the pool, dead ones pinned and untrailed, and
    every live particle glows between DIM and all of its own color; with no key pressed, replaying
    the same steps from the same seed gives bit-identical positions."""
    parts = scene.world.particles
    pos = parts.position
    live = ~scene.hidden
    assert np.isfinite(pos[live]).all() and live.sum() <= POOL
    assert (parts.inv_mass[~live] == 0).all() and (parts.velocity[~live] == 0).all()
    assert sorted(scene.trails) == np.flatnonzero(live).tolist(), "trails are not the live set"
    full = scene.handles["color"][live]
    assert (scene.colors[live] <= full + 1e-12).all() and \
        (scene.colors[live] >= DIM * full - 1e-12).all()
    if scene.handles["pressed"]:
        return
    again = build(scene.handles["params"])
    for dt in scene.handles["dts"]:
        on_step(again, dt)
        again.world.step(dt)
    assert np.array_equal(again.world.particles.position, pos), "fireworks are not repeatable"
    assert np.array_equal(again.hidden, scene.hidden)
    assert np.array_equal(again.colors, scene.colors)
