"""Picking under the mouse: a ray against every drawn particle sphere (vectorized) and every
rigid body (spheres, turned boxes); ``pick`` takes the nearest of either."""

from __future__ import annotations

from typing import NamedTuple

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
    hit = _particle_hit(scene, origin, direction)
    return None if hit is None else hit[0]


def _particle_hit(scene: Scene, origin, direction) -> tuple[int, float] | None:
    """(index, distance along the normalised ray [m]) of the nearest particle hit, or None."""
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
    return (best, float(t[best])) if np.isfinite(t[best]) else None


class Hit(NamedTuple):
    """What a pick ray met first: a ``kind`` ("particle" or "body") and its ``index``, the
    ``point`` where the ray entered its drawn surface [m] (3,), and the ``distance`` along the
    ray [m]."""

    kind: str
    index: int  # type: ignore[assignment]  # a field named like tuple.index, as intended
    point: np.ndarray
    distance: float


def pick(scene: Scene, origin, direction) -> Hit | None:
    """The nearest particle or rigid body the ray hits, or None."""
    d = np.asarray(direction, dtype=np.float64).reshape(3)
    d = d / np.linalg.norm(d)
    o = np.asarray(origin, dtype=np.float64).reshape(3)
    found = []
    particle = _particle_hit(scene, o, d)
    if particle is not None:
        found.append(Hit("particle", particle[0], o + particle[1] * d, particle[1]))
    body = pick_body(scene.world, o, d)
    if body is not None:
        found.append(Hit("body", *body))
    return min(found, key=lambda h: h.distance) if found else None


def pick_body(world, origin, direction) -> tuple[int, np.ndarray, float] | None:
    """The nearest rigid body the ray hits: (index, hit point [m], distance along the ray), or
    None. Spheres by the ray–sphere test; boxes by the slab test in the box's own frame."""
    from ..rigid.bodies import world_rotation
    from ..rigid.shapes import BOX, SPHERE

    b = world.bodies
    o = np.asarray(origin, dtype=np.float64).reshape(3)
    d = np.asarray(direction, dtype=np.float64).reshape(3)
    d = d / np.linalg.norm(d)
    best: tuple[int, np.ndarray, float] | None = None
    for i in range(b.count):
        t = None
        if b.shape[i] == SPHERE:
            oc = b.position[i] - o
            along = oc @ d
            disc = along * along - (oc @ oc - b.size[i, 0] ** 2)
            if disc >= 0:
                root = np.sqrt(disc)
                t = along - root if along - root >= 0 else along + root
        elif b.shape[i] == BOX:
            r = world_rotation(b.orientation[i])
            lo_, ld = r.T @ (o - b.position[i]), r.T @ d       # the ray in the box's frame
            with np.errstate(divide="ignore", invalid="ignore"):
                t1 = (-b.size[i] - lo_) / ld
                t2 = (b.size[i] - lo_) / ld
            near = np.nanmax(np.minimum(t1, t2))
            far = np.nanmin(np.maximum(t1, t2))
            if near <= far and far >= 0:
                t = near if near >= 0 else far
        if t is not None and t >= 0 and (best is None or t < best[2]):
            best = (i, o + t * d, float(t))
    return best
