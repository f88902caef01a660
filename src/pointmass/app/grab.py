"""Grabbing a particle with the mouse: a damped spring toward the cursor (no GL, no pyglet).

The spring force is scaled by the particle's mass, F = m·(ω²·(target − x) − 2ζω·v), so every
particle follows the cursor at the same rate ω whatever its mass (gz-sim's MouseDrag, bullet's
point-to-point pick). ζ = 1 is critical damping: it follows without ringing. The target moves in
the camera-facing plane through the particle where it was grabbed, so dragging the mouse moves
it across the screen, never toward or away from the eye.
"""

from __future__ import annotations

import numpy as np

from ..forces import ForceGenerator
from ..particles import Particles

#: Colour of the spring line [RGB].
SPRING_COLOR = (1.0, 0.85, 0.2)


class MouseSpring(ForceGenerator):
    """Pulls one particle toward ``target`` [m] with a mass-scaled, damped spring.

    Args:
        index: The grabbed particle.
        target: Where the cursor points [m], shape (3,); update it while dragging.
        omega: Natural angular frequency [rad/s]; keep ω·dt well under 2 (semi-implicit Euler).
        zeta: Damping ratio (1: critical).
    """

    def __init__(self, index: int, target, *, omega: float = 12.0, zeta: float = 1.0) -> None:
        self.index = int(index)
        self.target = np.asarray(target, dtype=np.float64).reshape(3).copy()
        self.omega = float(omega)
        self.zeta = float(zeta)

    def validate(self, particles: Particles) -> None:
        if not 0 <= self.index < particles.count:
            raise ValueError(f"MouseSpring index {self.index} is not a particle "
                             f"(the world has {particles.count})")

    def apply(self, particles: Particles, dt: float) -> None:
        i = self.index
        w = particles.inv_mass[i]
        if w <= 0:                   # immovable: nothing to pull
            return
        x, v = particles.position[i], particles.velocity[i]
        pull = self.omega**2 * (self.target - x) - 2.0 * self.zeta * self.omega * v
        particles.force[i] += pull / w


def plane_point(origin, direction, point, normal) -> np.ndarray | None:
    """Where the ray (origin, direction) meets the plane through ``point`` with ``normal``,
    or None when it runs parallel to it or the plane is behind the eye."""
    o, d = np.asarray(origin, float), np.asarray(direction, float)
    n, p = np.asarray(normal, float), np.asarray(point, float)
    denom = float(d @ n)
    if abs(denom) < 1e-9:
        return None
    t = float((p - o) @ n) / denom
    return o + t * d if t > 0 else None


class Grab:
    """A grab in progress: the spring in the world and the plane the target moves in."""

    def __init__(self, world, index: int, normal) -> None:
        self.world = world
        pos = world.particles.position[index].copy()
        self.normal = np.asarray(normal, dtype=np.float64)
        self.plane_point = pos
        self.spring = world.add(MouseSpring(index, pos))

    @property
    def index(self) -> int:
        return self.spring.index

    def move(self, origin, direction) -> None:
        """Point the target where the cursor ray meets the grab plane."""
        hit = plane_point(origin, direction, self.plane_point, self.normal)
        if hit is not None:
            self.spring.target = hit

    def line(self) -> tuple:
        """(start, end, rgb) for the renderer's ``extra_lines``: particle to cursor."""
        start = self.world.particles.position[self.index].copy()
        return (start, self.spring.target.copy(), SPRING_COLOR)

    def release(self) -> None:
        if self.spring in self.world.forces:
            self.world.remove(self.spring)
