"""What a narrow-phase kernel writes: up to four contact points sharing one normal.

Every kernel ``pair(A..., B..., margin, normal, points, depth, ids) -> count`` writes into
caller-owned arrays (so a driver loop over pairs allocates nothing) and returns how many points
it wrote, 0 when the shapes are farther apart than ``margin``:

* ``normal`` (3,): unit, from B to A: A is pushed along +normal, B along −normal (the particles'
  contact convention, ``contacts.py``);
* ``points`` (4, 3): world points midway between the two surfaces [m];
* ``depth`` (4,): penetration [m], > 0 overlapping, < 0 a gap (a speculative point, kept when
  the gap is under ``margin``: the solver only lets it close, Box2D's speculative contacts);
* ``ids`` (4,) int64: feature ids, the same for the same touching features next step, so the
  impulse history can warm start each point (rigid-notes R7, R8).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

#: Most points one pair yields: enough to hold a face on a face (Box3D, Bullet, Jolt keep 4).
MAX_POINTS = 4


class Manifold(NamedTuple):
    """One pair's contact points (the first ``count`` rows are valid)."""

    count: int
    normal: np.ndarray
    points: np.ndarray
    depth: np.ndarray
    ids: np.ndarray


def empty_outputs() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Fresh (normal, points, depth, ids) arrays for one kernel call."""
    return (np.zeros(3), np.zeros((MAX_POINTS, 3)), np.zeros(MAX_POINTS),
            np.full(MAX_POINTS, -1, dtype=np.int64))


@njit(cache=True, nogil=True)
def reduce_points(cand, sep, count, normal, keep):
    """Choose at most 4 of ``count`` candidate points (cand (K, 3), separations sep (K,)) that
    keep the deepest point and the largest area, written as indices into ``keep`` (4,); returns
    how many. Box3D and Jolt reduce the same way: deepest, farthest from it, then the two that
    make the largest triangles on either side of that line (``normal`` orients the areas)."""
    if count <= 4:
        for k in range(count):
            keep[k] = k
        return count
    a = 0
    for k in range(1, count):
        if sep[k] < sep[a]:
            a = k
    b = -1
    best = -1.0
    for k in range(count):
        dx, dy, dz = cand[k, 0] - cand[a, 0], cand[k, 1] - cand[a, 1], cand[k, 2] - cand[a, 2]
        d2 = dx * dx + dy * dy + dz * dz
        if k != a and d2 > best:
            best, b = d2, k
    ex, ey, ez = cand[b, 0] - cand[a, 0], cand[b, 1] - cand[a, 1], cand[b, 2] - cand[a, 2]
    c, d = -1, -1
    most, least = 0.0, 0.0
    for k in range(count):
        if k == a or k == b:
            continue
        fx, fy, fz = cand[k, 0] - cand[a, 0], cand[k, 1] - cand[a, 1], cand[k, 2] - cand[a, 2]
        area = ((ey * fz - ez * fy) * normal[0] + (ez * fx - ex * fz) * normal[1]
                + (ex * fy - ey * fx) * normal[2])
        if area > most:
            most, c = area, k
        if area < least:
            least, d = area, k
    n = 0
    for k in (a, b, c, d):
        if k >= 0:
            keep[n] = k
            n += 1
    return n
