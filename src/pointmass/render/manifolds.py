"""The contact overlay for rigid bodies: each manifold of the last substep, drawn as a dot at
every contact point, a short line along its normal, and a thin outline joining the points of
one manifold (the patch a face rests on). Pure numpy, copied into the FrameState at capture.

Speculative points (a gap still inside the margin: the solver only lets them close) are drawn
dimmer, so the margin at work can be seen without being mistaken for a touch. A gap under the
solver's slop (0.1 mm) counts as touching: a box resting on the ground sits at a depth of
±1e-15 m, which would otherwise flicker between the two.

A row's point is where the narrow phase put it, midway between the surfaces; it is kept
relative to body ``b`` (or absolute against a plane), so a point under a resting box stays
on the ground after the step moved the box (``rigid/contacts.py``).
"""

from __future__ import annotations

import numpy as np

from ..rigid.shapes import BOX
from . import style
from .gather import LINE_FLOATS, line_rows

#: Size of a contact dot [px at 720 rows], and the color of the rim around it.
DOT_WIDTH = 7.0
DOT_RIM = (0.08, 0.08, 0.08)
#: The line along the normal: this fraction of the smaller body's smallest half extent, at
#: most NORMAL_LENGTH [m].
NORMAL_FRACTION = 0.6
NORMAL_LENGTH = 0.3
NORMAL_WIDTH = 2.0
OUTLINE_WIDTH = 1.5
#: The outline is fainter than the points it joins.
OUTLINE_ALPHA = 0.6
#: Alpha of touching and of speculative points; a point counts as touching when its gap is
#: under TOUCHING_DEPTH [m] (0.1 mm: float noise on a resting face).
TOUCHING_DEPTH = 1e-4
TOUCHING_ALPHA = 1.0
SPECULATIVE_ALPHA = 0.3


def contact_points(world) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray,
                                   np.ndarray]:
    """(points [m] (M, 3), normals (M, 3), depths [m] (M,), manifold id (M,), scale [m] (M,))
    of the world's rigid contact rows in its last substep. A manifold is a run of rows of one
    pair (a, b); a row's scale is the smallest half extent of the bodies it joins."""
    c = world.body_contacts
    n = c.count
    bodies = world.bodies
    a, b = np.asarray(c.a[:n]), np.asarray(c.b[:n])
    base = np.where((b >= 0)[:, None], bodies.position[np.maximum(b, 0)], 0.0)
    points = base + c.r_b[:n]
    starts = np.ones(n, bool)
    starts[1:] = (a[1:] != a[:-1]) | (b[1:] != b[:-1])
    return (points, np.array(c.normal[:n]), np.array(c.depth[:n]), np.cumsum(starts) - 1,
            _row_scale(bodies, a, b))


def _row_scale(bodies, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The smaller of the two bodies' smallest half extents (a sphere's radius) per row [m];
    ``a`` ≥ the body count is a particle (``particle_body.py``): only ``b`` counts then."""
    count = bodies.count
    size = bodies.size[:count]
    half = np.where(bodies.shape[:count] == BOX, size.min(axis=1), size[:, 0])
    half = np.append(half, np.inf)              # index ``count``: no body (plane, particle)
    own = half[np.where(a < count, a, count)]
    other = half[np.where(b >= 0, b, count)]
    return np.minimum(own, other)


def manifold_lines(world, width_scale: float) -> list[np.ndarray]:
    """Overlay line rows for every rigid contact: manifold outlines, normals, then dots (a
    dark rim under each so it reads on any color)."""
    points, normals, depth, manifold, scale = contact_points(world)
    if not len(points):
        return []
    alpha = np.where(depth > -TOUCHING_DEPTH, TOUCHING_ALPHA, SPECULATIVE_ALPHA)
    rgb = style.CONTACT_COLOR
    length = np.minimum(NORMAL_LENGTH, NORMAL_FRACTION * scale)[:, None]
    return [outline_rows(points, normals, manifold, alpha, width_scale),
            line_rows(points, points + length * normals, rgb, alpha,
                      NORMAL_WIDTH * width_scale),
            line_rows(points, points, DOT_RIM, alpha, (DOT_WIDTH + 3.0) * width_scale),
            line_rows(points, points, rgb, alpha, DOT_WIDTH * width_scale)]   # square dots


def outline_rows(points, normals, manifold, alpha, width_scale: float) -> np.ndarray:
    """The closed outline of each manifold of two points or more: its points in turn around
    their centre, in the plane across the normal."""
    first, second = [], []
    for m in range(int(manifold[-1]) + 1):
        rows = np.flatnonzero(manifold == m)
        if len(rows) < 2:
            continue
        ring = rows[_around(points[rows], normals[rows[0]])]
        if len(ring) == 2:                     # an edge: one segment, not there and back
            first.append(ring[:1])
            second.append(ring[1:])
        else:
            first.append(ring)
            second.append(np.roll(ring, -1))
    if not first:
        return np.zeros((0, LINE_FLOATS), np.float32)
    i, j = np.concatenate(first), np.concatenate(second)
    return line_rows(points[i], points[j], style.CONTACT_COLOR,
                     OUTLINE_ALPHA * np.minimum(alpha[i], alpha[j]), OUTLINE_WIDTH * width_scale)


def _around(points: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """The order of ``points`` by angle about their centre, seen along ``normal``."""
    u = np.cross(normal, (1.0, 0.0, 0.0) if abs(normal[0]) < 0.9 else (0.0, 1.0, 0.0))
    u /= np.linalg.norm(u)
    v = np.cross(normal, u)
    d = points - points.mean(axis=0)
    return np.argsort(np.arctan2(d @ v, d @ u))
