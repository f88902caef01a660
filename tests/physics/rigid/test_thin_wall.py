"""Issue 26, acceptance point 7: no tunnelling through a thin wall at any angle.

The scene: a static box wall 5 cm thick with a 2 m × 2 m face (centre at the origin, normal +x)
and a 1 kg projectile 0.1 m across (a box of half-extent 0.05, or a sphere of radius 0.05),
e = 0, no gravity, ``World()`` defaults, dt = 1/60. The projectile is shot at the wall's
centre from the −x side.

"Incidence" θ is the angle between the velocity and the wall's normal (−x): the velocity is
speed·(cos θ, sin θ, 0). A box's orientation can be read two ways, and both are tested:

* ``aligned``: the box's faces stay parallel to the wall's (its leading face meets the wall
  flat, sliding);
* ``rotated``: the box is turned by θ about z with its velocity, so it flies nose first (its
  leading face is square to its flight) and meets the wall with an edge, at θ to its face.
* ``tumbled`` (one more reading, for edges that cross): turned by θ about z and by 30° about
  its own flight, so a corner leads.

A start phase k of 16 offsets the start distance by k/16 of one step's travel, so the step
ends fall at every fraction of the flight. The projectile "passes through" when, between two
steps, its centre crosses the wall's mid-plane (x = 0) inside the wall's face (|y|, |z| ≤ 1 m);
a projectile that glances off or slides past the wall's edge does not count.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.quaternion import quat_from_axis_angle, quat_mul
from pointmass.rigid.shapes import Box, Sphere

DT = 1.0 / 60.0
HALF_WALL = (0.025, 1.0, 1.0)
SIZE = 0.05  # the projectile's half-extent / radius [m]
ANGLES = (0.0, 15.0, 30.0, 45.0, 60.0)
SPEEDS = (50.0, 100.0, 200.0, 500.0)
PHASES = 16
#: Distance [m] from the start to the wall's centre along the flight, before the phase offset:
#: the projectile starts clear of the wall at every angle.
START = 1.0


def _orientation(reading: str, theta: float) -> np.ndarray:
    z = np.array([0.0, 0.0, 1.0])
    if reading == "aligned":
        return np.array([1.0, 0.0, 0.0, 0.0])
    turn = quat_from_axis_angle(z, theta)
    if reading == "rotated":
        return turn
    flight = np.array([math.cos(theta), math.sin(theta), 0.0])
    return quat_mul(quat_from_axis_angle(flight, math.radians(30.0)), turn)


def shot(shape: str, reading: str, angle_deg: float, speed: float, phase: int) -> bool:
    """Whether the projectile passes through the wall in this shot (module docstring)."""
    theta = math.radians(angle_deg)
    direction = np.array([math.cos(theta), math.sin(theta), 0.0])
    travel = speed * DT
    distance = START + travel * phase / PHASES
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.add_body(Box(HALF_WALL), (0.0, 0.0, 0.0), mass=math.inf)
    body = world.add_body(
        Sphere(SIZE) if shape == "sphere" else Box((SIZE, SIZE, SIZE)),
        -distance * direction, _orientation(reading, theta), mass=1.0,
        velocity=speed * direction)
    # steps until the straight flight would be 2 m past the wall's centre
    steps = math.ceil((distance + 2.0) / travel)
    before = body.position.copy()
    for _ in range(steps):
        world.step(DT)
        after = body.position.copy()
        if before[0] < 0.0 <= after[0]:
            f = -before[0] / (after[0] - before[0])
            y, z = before[1:] + f * (after[1:] - before[1:])
            if abs(y) <= HALF_WALL[1] and abs(z) <= HALF_WALL[2]:
                return True
        before = after
    return False


def passes(shape: str, reading: str, angle_deg: float, speed: float) -> int:
    return sum(shot(shape, reading, angle_deg, speed, k) for k in range(PHASES))


CASES = ([("sphere", "aligned")] + [("box", r) for r in ("aligned", "rotated", "tumbled")])


@pytest.mark.parametrize(("shape", "reading"), CASES)
def test_no_shot_passes_through_a_thin_wall(shape, reading):
    counts = {(a, s): passes(shape, reading, a, s) for a in ANGLES for s in SPEEDS}
    assert counts == dict.fromkeys(counts, 0)


if __name__ == "__main__":
    for shape, reading in CASES:
        print(shape, reading)
        for a in ANGLES:
            print(f"  {a:4.0f}°", " ".join(f"{passes(shape, reading, a, s):3d}" for s in SPEEDS))
