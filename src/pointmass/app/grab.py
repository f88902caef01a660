"""Grabbing with the mouse: a damped spring from the grabbed point toward the cursor (no GL,
no pyglet). One mechanism, two kinds of target: a particle (``MouseSpring``, here) or a point
of a rigid body (``body_spring.BodyMouseSpring``), sharing the law (``rigid.pull.pull_gains``)
and the ``Grab`` that moves the target and draws the line.

The spring is scaled to what resists the pull, not only to the grabbed particle: the mass of
everything rods and cables tie to it (a platform moves as one truss) and the stiffness of the
springs attached to it (a cloth node is held by four). So F = k·(target − x) − c·v with
k = max(M·ω², 2·Σk_springs) and c = 2ζ·√(k·M): a lone particle follows the cursor at rate ω
(gz-sim's MouseDrag, bullet's point-to-point pick), a cloth node gives way to it visibly. Both are
capped so the explicit step stays stable for the grabbed particle alone (h²k/m ≤ 1/2,
h·c/m ≤ 1/2), which is what lets the grab be this strong without blowing a light node away.
ζ = 1 is critical damping. The target moves in the camera-facing plane through the grabbed
point where it was grabbed, so dragging moves it across the screen, never toward the eye.
"""

from __future__ import annotations

import numpy as np

from ..forces import ForceGenerator
from ..particles import Particles
from ..rigid.pull import pull_gains
from ..springs import _SpringSet

#: Colour of the spring line [RGB].
SPRING_COLOR = (1.0, 0.85, 0.2)


def resistance(world, index: int) -> tuple[float, float]:
    """(mass [kg], stiffness [N/m]) resisting a pull on particle ``index``: the movable mass of
    the particles that rods and cables join to it (they move together), and the spring
    constants of the springs and bungees attached to it."""
    p = world.particles
    links = [g for g in world.contact_generators
             if getattr(g, "kind", None) in ("rod", "cable") and hasattr(g, "b")]
    cluster, frontier = {index}, [index]
    while frontier:
        i = frontier.pop()
        for g in links:
            a, b = np.asarray(g.a), np.asarray(g.b)
            for j in np.concatenate([b[a == i], a[b == i]]).tolist():
                if j not in cluster:
                    cluster.add(j)
                    frontier.append(j)
    members = np.fromiter(cluster, dtype=np.int64)
    w = p.inv_mass[members]
    mass = float(np.sum(1.0 / w[w > 0])) if (w > 0).any() else 0.0
    stiffness = 0.0
    for g in world.forces:
        if isinstance(g, _SpringSet):      # springs and bungees, two-ended or anchored
            ends = [g.a, g.b] if hasattr(g, "b") else [g.particles]
            for e in ends:
                stiffness += float(g.spring_constant[np.asarray(e) == index].sum())
    return mass, stiffness


class MouseSpring(ForceGenerator):
    """Pulls one particle toward ``target`` [m] with a damped spring scaled to what resists.

    Args:
        index: The grabbed particle.
        target: Where the cursor points [m], shape (3,); update it while dragging.
        omega: Natural angular frequency [rad/s] of the pull on the resisting mass.
        zeta: Damping ratio (1: critical).
        mass, stiffness: What resists the pull (``resistance``); by default the particle's
            own mass and no springs.
    """

    bounded = True  # caps its own stiffness and damping against the step (stability.py)
    grabs = "particle"

    def __init__(self, index: int, target, *, omega: float = 12.0, zeta: float = 1.0,
                 mass: float | None = None, stiffness: float = 0.0) -> None:
        self.index = int(index)
        self.target = np.asarray(target, dtype=np.float64).reshape(3).copy()
        self.omega = float(omega)
        self.zeta = float(zeta)
        self.mass = mass
        self.stiffness = float(stiffness)

    def gains(self, particles: Particles, dt: float) -> tuple[float, float]:
        """(k [N/m], c [N·s/m]) for a step of ``dt`` [s], capped for stability."""
        m = 1.0 / float(particles.inv_mass[self.index])
        return pull_gains(max(self.mass or m, m), m, self.omega, self.zeta, dt,
                          self.stiffness)

    def validate(self, particles: Particles) -> None:
        if not 0 <= self.index < particles.count:
            raise ValueError(f"MouseSpring index {self.index} is not a particle "
                             f"(the world has {particles.count})")

    def apply(self, particles: Particles, dt: float) -> None:
        i = self.index
        w = particles.inv_mass[i]
        if w <= 0:                   # immovable: nothing to pull
            return
        k, c = self.gains(particles, dt)
        x, v = particles.position[i], particles.velocity[i]
        particles.force[i] += k * (self.target - x) - c * v

    def point(self, world) -> np.ndarray:
        """Where the grabbed particle is [m], (3,)."""
        return world.particles.position[self.index].copy()


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
    """A grab in progress: a mouse spring in the world (``MouseSpring`` on a particle or
    ``BodyMouseSpring`` on a point of a body) and the camera-facing plane its target moves in,
    through the grabbed point. ``grab_particle`` and ``grab_body`` make one."""

    def __init__(self, world, spring, normal) -> None:
        self.world = world
        self.normal = np.asarray(normal, dtype=np.float64)
        self.plane_point = spring.point(world)
        spring.target = self.plane_point.copy()
        self.spring = world.add(spring)

    @property
    def index(self) -> int:
        """The grabbed particle or body."""
        return self.spring.index

    @property
    def kind(self) -> str:
        """What is held: "particle" or "body"."""
        return self.spring.grabs

    def move(self, origin, direction) -> None:
        """Point the target where the cursor ray meets the grab plane."""
        hit = plane_point(origin, direction, self.plane_point, self.normal)
        if hit is not None:
            self.spring.target = hit

    def line(self) -> tuple:
        """(start, end, rgb) for the renderer's ``extra_lines``: grabbed point to cursor."""
        return (self.spring.point(self.world), self.spring.target.copy(), SPRING_COLOR)

    def release(self) -> None:
        spring = self.spring
        if any(spring is g for g in (*self.world.forces, *self.world.body_forces)):
            self.world.remove(spring)


def grab_particle(world, index: int, normal) -> Grab:
    """Grab particle ``index`` with a spring scaled to what resists it (``resistance``); the
    target moves in the plane through it with ``normal`` (the camera's forward)."""
    mass, stiffness = resistance(world, index)
    return Grab(world, MouseSpring(index, world.particles.position[index], mass=mass,
                                   stiffness=stiffness), normal)
