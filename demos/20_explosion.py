"""Cyclone's explosion demo, with an explosion that goes off (the book's ``updateForce`` is
empty).

Boxes and spheres dropped in a ring on the ground; an ``Explosion`` at the centre throws them
outward and up: each body within its radius gets the impulse strength·(1 − d/radius) over
0.05 s, d the distance from the blast to its nearest point, pushed at that point so boxes
tumble. It goes off by itself after ``auto_time`` seconds, and on SPACE or a click; ``again``
seconds after a blast the ring is put back and it goes off again, so the show never ends
before anyone is watching (a window that takes a while to open, a late look).

Keys: SPACE / click detonate.   Run: pointmass run explosion --set strength=100
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Ground, Scene, World, tweak
from pointmass.rigid.forces import Explosion
from pointmass.rigid.shapes import Box, Sphere

TITLE = "Explosion (rigid bodies)"
#: Shown over the scene until the first key or click.
HINT = "Click or press SPACE to set off the blast (it also goes off by itself)"
#: Just under the ground, so the blast throws things up as well as out.
CENTRE = np.array([0.0, -1.0, 0.0])


@dataclass
class Params:
    count: int = tweak(10, 2, 24, "Bodies in the ring (boxes and spheres in turn)",
                       rebuild=True)
    ring: float = tweak(2.0, 1.0, 4.0, "Radius of the ring [m]", rebuild=True)
    strength: float = tweak(50.0, 0.0, 300.0, "Impulse at the centre [N·s]")
    reach: float = tweak(6.0, 1.0, 12.0, "Radius the blast reaches [m]")
    auto_time: float = tweak(1.5, 0.0, 10.0, "Goes off by itself at … [s] (0: only by key)")
    again: float = tweak(6.0, 0.0, 30.0, "Ring put back and set off again … s after a blast "
                         "(0: once)")


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    world.add(Ground(friction=0.8, restitution=0.2))
    bodies = []
    for k in range(p.count):
        angle = 2 * np.pi * k / p.count
        x, z = p.ring * np.cos(angle), p.ring * np.sin(angle)
        if k % 2:
            # (rolling has no resistance here: damping stops the balls in the picture)
            body = world.add_body(Sphere(0.3), (x, 0.3 + 0.2 * k, z), mass=5.0,
                                  friction=0.8, restitution=0.2,
                                  linear_damping=0.6, angular_damping=0.15)
        else:
            body = world.add_body(Box((0.3, 0.3, 0.3)), (x, 0.3 + 0.2 * k, z),
                                  (np.cos(angle / 2), 0.0, np.sin(angle / 2), 0.0), mass=5.0,
                                  friction=0.8, restitution=0.2,
                                  linear_damping=0.95, angular_damping=0.8)
        bodies.append(body)
    return Scene(world, camera=CameraHint(target=(0.0, 0.5, 0.0), distance=22.0, yaw=30.0,
                                          pitch=22.0),
                 dt=1.0 / 60.0,
                 handles={"params": p, "bodies": bodies, "blast": None, "before": None,
                          "at": None, "armed": 0.0,
                          "start": (world.bodies.snapshot(), world.body_impulses.snapshot(),
                                    world.sleeping_impulses.snapshot())})


def apply(scene: Scene, p: Params) -> None:
    scene.handles["params"] = p


def detonate(scene: Scene, p: Params) -> None:
    """Set off an explosion at the centre (a new one, the old one spent)."""
    h = scene.handles
    world = scene.world
    if h["blast"] is not None:
        world.remove(h["blast"])
    h["blast"] = world.add(Explosion(CENTRE, p.strength, p.reach, duration=0.05))
    h["before"] = world.bodies.position.copy()
    h["at"] = scene.time


def rearm(scene: Scene) -> None:
    """Put the ring back as it was built (the blast spent); it goes off ``auto_time`` later."""
    h = scene.handles
    world = scene.world
    bodies, impulses, sleeping = h["start"]
    world.bodies.restore(bodies)
    world.body_impulses.restore(impulses)
    world.sleeping_impulses.restore(sleeping)
    if h["blast"] is not None:
        world.remove(h["blast"])
    h["blast"], h["before"], h["at"], h["armed"] = None, None, None, scene.time


def on_step(scene: Scene, dt: float) -> None:
    h = scene.handles
    p = h["params"]
    if h["at"] is None and p.auto_time > 0 and scene.time >= h["armed"] + p.auto_time:
        detonate(scene, p)
    elif h["at"] is not None and p.again > 0 and scene.time >= h["at"] + p.again:
        rearm(scene)


KEYS = {"SPACE": ("Detonate at the centre", detonate), "CLICK": ("Detonate", detonate)}


def check(scene: Scene) -> None:
    """Everything finite; 0.3 s after a blast every body it reached has moved away from the
    centre (in the ground plane, by at least 5 cm)."""
    h = scene.handles
    bodies = scene.world.bodies
    assert np.isfinite(bodies.position).all() and np.isfinite(bodies.velocity).all()
    if h["at"] is None or scene.time < h["at"] + 0.3 or h["blast"].strength == 0.0:
        return
    before = h["before"]
    out = (before - CENTRE)[:, [0, 2]]
    dist = np.linalg.norm(out, axis=1)
    reached = np.linalg.norm(before - CENTRE, axis=1) - 0.3 < h["blast"].radius
    moved = np.einsum("ij,ij->i", (bodies.position - before)[:, [0, 2]], out / dist[:, None])
    assert (moved[reached] > 0.05).all(), f"moved outward by {moved[reached].round(3)} m"
