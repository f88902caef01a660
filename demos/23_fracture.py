"""Cyclone's fracture demo: a ball hits a block hard enough to break it into its eight octants.

An 8 m, 100 kg block stands on the ground; a 0.25 m, 5 kg ball is thrown at it from
(0, 5, 20) with Cyclone's random velocity (±4 binomial sideways, U(1, 6) up, −20 m/s along z;
seeded). After each step the demo reads the normal impulse the solver gave the ball–block
contact over the step (``world.body_contacts.impulse``); above ``break_impulse`` the block
splits: the big body becomes one of its half-size octants in place
(``Bodies.set_shape`` gives it the octant's mass and inertia) and the seven others are added,
each moving with the block's velocity at its centre, v + ω × r, plus an outward push. The
parts fall and come to rest on the ground. Cyclone splits around the contact point with a
wrong volume and inertia for the pieces (cyclone-notes #28); the octants' mass properties here
come from their shape.

Keys: SPACE / click reassemble the block and throw the next random ball (R rebuilds: the
first ball again).   Run: pointmass run fracture --set break_impulse=200
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Ground, Scene, World, tweak
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.shapes import BOX, Box, Sphere

TITLE = "Fracture (a block breaks on impact)"
#: Shown over the scene until the first key or click.
HINT = "Click or press SPACE to throw a ball at the block"
HALF = 4.0
BLOCK_MASS = 100.0
BALL_RADIUS = 0.25
BALL_MASS = 5.0
BALL_START = (0.0, 5.0, 20.0)
#: The octants' centres in the block's coordinates [m].
OCTANTS = np.array([(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * HALF / 2
SURFACE = {"friction": 0.9, "restitution": 0.2}


@dataclass
class Params:
    break_impulse: float = tweak(40.0, 1.0, 500.0, "Normal impulse that breaks the block [N·s]")
    push: float = tweak(6.0, 0.0, 10.0, "Outward speed the parts get when it breaks [m/s]")
    seed: int = tweak(1, 0, 9999, "Random seed of the throws", rebuild=True)


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    world.add(Ground(**SURFACE))
    block = world.add_body(Box((HALF, HALF, HALF)), (0.0, HALF, 0.0), mass=BLOCK_MASS,
                           linear_damping=0.9, angular_damping=0.9, **SURFACE)
    # (rolling has no resistance here: damping stops the ball in the picture)
    ball = world.add_body(Sphere(BALL_RADIUS), BALL_START, mass=BALL_MASS, linear_damping=0.95,
                          angular_damping=0.1, **SURFACE)
    scene = Scene(world, camera=CameraHint(target=(0.0, 3.0, 6.0), distance=34.0, yaw=50.0,
                                           pitch=18.0),
                  dt=1.0 / 60.0,
                  handles={"params": p, "block": block.index, "ball": ball.index,
                           "rng": np.random.default_rng(p.seed), "parts": [],
                           "split": None})
    scene.handles["intact"] = world.bodies.snapshot()
    throw(scene, p, first=True)
    return scene


def apply(scene: Scene, p: Params) -> None:
    scene.handles["params"] = p


def throw(scene: Scene, p: Params, first: bool = False) -> None:
    """Put the block back together and throw a ball with Cyclone's random velocity."""
    h = scene.handles
    world = scene.world
    if not first:
        world.bodies.restore(h["intact"])
        world.body_impulses.clear()
        h["parts"], h["split"] = [], None
    rng = h["rng"]
    velocity = (4.0 * (rng.random() - rng.random()), rng.uniform(1.0, 6.0), -20.0)
    i = h["ball"]
    world.bodies.position[i] = BALL_START
    world.bodies.velocity[i] = velocity
    world.bodies.angular_velocity[i] = 0.0


KEYS = {"SPACE": ("Reassemble the block and throw a ball", throw),
        "CLICK": ("Reassemble the block and throw a ball", throw)}


def hit_impulse(world: World, a: int, b: int) -> float:
    """Σ of the normal impulses [N·s] the solver applied last step between bodies a and b
    (``BodyContacts.impulse``: the whole step's, not the warm start of ``body_impulses``,
    which with the soft step is one substep's)."""
    c = world.body_contacts
    pair = ((c.a == a) & (c.b == b)) | ((c.a == b) & (c.b == a))
    return float(c.impulse[pair].sum())


def split(scene: Scene, push: float) -> None:
    """Break the block into its eight octants, each with the block's velocity at its centre
    (v + ω × r), then push each outward by ``push`` [m/s] (the pushes cancel: equal masses)."""
    h = scene.handles
    bodies = scene.world.bodies
    i = h["block"]
    turn = world_rotation(bodies.orientation[i])
    centre, v, w = bodies.position[i].copy(), bodies.velocity[i].copy(), \
        bodies.angular_velocity[i].copy()
    quat = bodies.orientation[i].copy()
    before = BLOCK_MASS * v
    octant = Box((HALF / 2, HALF / 2, HALF / 2))
    mass = BLOCK_MASS / len(OCTANTS)
    parts, momentum = [], np.zeros(3)
    for k, local in enumerate(OCTANTS):
        r = turn @ local
        velocity = v + np.cross(w, r)
        momentum += mass * velocity
        out = r / np.linalg.norm(r)
        if k == 0:
            bodies.set_shape(i, octant, mass=mass)
            bodies.position[i] = centre + r
            bodies.velocity[i] = velocity + push * out
            parts.append(i)
        else:
            parts.append(scene.world.add_body(
                octant, centre + r, quat, velocity=velocity + push * out,
                angular_velocity=w, mass=mass, linear_damping=0.9, angular_damping=0.9,
                **SURFACE).index)
    after = sum(mass * bodies.velocity[j] for j in parts)
    h["parts"] = parts
    h["split"] = {"time": scene.time, "before": before, "unpushed": momentum,
                  "after": after}


def on_step(scene: Scene, dt: float) -> None:
    """Before each step: if the last step's ball–block impulse broke the block, split it."""
    h = scene.handles
    if h["split"] is None and scene.time > 0.0:
        if hit_impulse(scene.world, h["block"], h["ball"]) > h["params"].break_impulse:
            split(scene, h["params"].push)


def check(scene: Scene) -> None:
    """By 2 s the default throw has broken the block into eight parts of 12.5 kg (100 kg in
    all); across the split the parts' momentum equals the block's (1e-9 relative, before the
    push and after it, the pushes cancelling); 5 s after the split every part rests on the
    ground (slower than 5 cm/s, none sunk more than 1 cm)."""
    h = scene.handles
    bodies = scene.world.bodies
    assert np.isfinite(bodies.position).all()
    if h["split"] is None:
        assert scene.time < 2.0 or h["params"].break_impulse > 60.0, "the block did not break"
        return
    parts = h["parts"]
    assert len(parts) == 8 and (bodies.shape[parts] == BOX).all()
    assert abs(sum(1.0 / bodies.inv_mass[j] for j in parts) - BLOCK_MASS) < 1e-9
    s = h["split"]
    scale = max(np.linalg.norm(s["before"]), 1.0)
    assert np.linalg.norm(s["unpushed"] - s["before"]) < 1e-9 * scale, s
    assert np.linalg.norm(s["after"] - s["before"]) < 1e-9 * scale, s
    if scene.time < s["time"] + 5.0:
        return
    speed = np.linalg.norm(bodies.velocity[parts], axis=1).max()
    assert speed < 0.05, f"a part still moves at {speed:.3f} m/s"
    low = min(lowest(bodies, j) for j in parts)
    assert low > -0.01, f"a part sank {-low:.3f} m into the ground"


def lowest(bodies, j: int) -> float:
    """Height of box ``j``'s lowest corner [m]."""
    turn = world_rotation(bodies.orientation[j])
    return float(bodies.position[j, 1] - np.abs(turn[1]) @ bodies.size[j])
