"""Picking a particle under the mouse: a ray against every drawn sphere, vectorized."""

from __future__ import annotations

import numpy as np

from ..scene import Scene


def drawn_radii(scene: Scene) -> np.ndarray:
    """The radius each particle is drawn with [m], shape (N,): its own, or ``point_radius``."""
    r = scene.world.particles.radius
    return np.where(r > 0, r, scene.point_radius)


def pick_particle(scene: Scene, origin, direction) -> int | None:
    """The index of the nearest visible particle whose drawn sphere the ray hits, or None.

    Args:
        origin: Ray origin [m], shape (3,).
        direction: Ray direction, shape (3,) (normalised here).
    """
    pos = scene.world.particles.position
    if len(pos) == 0:
        return None
    o = np.asarray(origin, dtype=np.float64).reshape(3)
    d = np.asarray(direction, dtype=np.float64).reshape(3)
    d = d / np.linalg.norm(d)
    r = drawn_radii(scene)
    oc = pos - o
    b = oc @ d                      # distance along the ray to the closest approach
    c = np.einsum("ij,ij->i", oc, oc) - r * r
    disc = b * b - c
    hit = disc >= 0
    if scene.hidden is not None:
        hidden = np.asarray(scene.hidden, bool)
        hit[: len(hidden)] &= ~hidden[: len(hit)]
    if not hit.any():
        return None
    root = np.sqrt(np.where(hit, disc, 0.0))
    t = np.where(b - root >= 0, b - root, b + root)   # inside a sphere: the exit point
    t = np.where(hit & (t >= 0), t, np.inf)
    best = int(np.argmin(t))
    return best if np.isfinite(t[best]) else None
