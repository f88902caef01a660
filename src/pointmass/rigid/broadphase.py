"""Broadphase for rigid bodies: sort and sweep on axis-aligned boxes.

Each body's AABB (a sphere's cube, or a box's |R|·h extent) is grown by the contact margin plus
how far the body can move this step, so every pair that could touch before the step ends is
found (speculative contacts, as the particles' spatial hash does with its margin). The boxes are
sorted by their low x and swept: a pair is tested on y and z only while their x intervals
overlap. O(N log N + pairs) for bodies spread along x; the particle spatial hash would do for
piles, but at the sizes of issue 13 (towers, pyramids, ~1000-box pits) the sort is cheaper than
hashing and needs no cell size for bodies of mixed sizes.

The pair list is deterministic: ``np.argsort(kind="stable")`` breaks ties by index, and each
pair is written as (lower index, higher index) in sweep order.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .scalar import qrot
from .shapes import BOX, SPHERE


@njit(cache=True, nogil=True)
def bounds(pos, quat, vel, ang, shape, size, margin, dt, low, high, reach):
    """AABBs (low, high (N, 3)) of every body with a shape, grown by ``margin`` [m] and by the
    distance its points can travel in ``dt`` [s]; ``reach`` (N,) gets that travel. Bodies without
    a shape get an empty box (low > high)."""
    for i in range(pos.shape[0]):
        kind = shape[i]
        if kind == SPHERE:
            ex = ey = ez = size[i, 0]
            radius = size[i, 0]
        elif kind == BOX:
            ex = ey = ez = 0.0
            for k in range(3):
                e0 = 1.0 if k == 0 else 0.0
                e1 = 1.0 if k == 1 else 0.0
                e2 = 1.0 if k == 2 else 0.0
                ax, ay, az = qrot(quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3], e0, e1, e2)
                ex += size[i, k] * abs(ax)
                ey += size[i, k] * abs(ay)
                ez += size[i, k] * abs(az)
            radius = math.sqrt(size[i, 0] ** 2 + size[i, 1] ** 2 + size[i, 2] ** 2)
        else:
            for k in range(3):
                low[i, k] = 1.0
                high[i, k] = -1.0
            reach[i] = 0.0
            continue
        speed = math.sqrt(vel[i, 0] ** 2 + vel[i, 1] ** 2 + vel[i, 2] ** 2)
        spin = math.sqrt(ang[i, 0] ** 2 + ang[i, 1] ** 2 + ang[i, 2] ** 2)
        reach[i] = (speed + spin * radius) * dt
        grow = margin + reach[i]
        low[i, 0] = pos[i, 0] - ex - grow
        low[i, 1] = pos[i, 1] - ey - grow
        low[i, 2] = pos[i, 2] - ez - grow
        high[i, 0] = pos[i, 0] + ex + grow
        high[i, 1] = pos[i, 1] + ey + grow
        high[i, 2] = pos[i, 2] + ez + grow


@njit(cache=True, nogil=True)
def sweep(low, high, order, inv_mass, out_a, out_b):
    """Overlapping pairs of AABBs, bodies taken in ``order`` (sorted by low x); a pair of two
    immovable bodies is skipped. Returns the pair count, or -(count needed) when ``out_a`` is
    too short."""
    count = 0
    cap = out_a.shape[0]
    n = order.shape[0]
    for u in range(n):
        i = order[u]
        if low[i, 0] > high[i, 0]:
            continue
        for v in range(u + 1, n):
            j = order[v]
            if low[j, 0] > high[i, 0]:
                break
            if low[j, 0] > high[j, 0]:
                continue
            if (low[j, 1] > high[i, 1] or low[i, 1] > high[j, 1] or low[j, 2] > high[i, 2]
                    or low[i, 2] > high[j, 2]):
                continue
            if inv_mass[i] == 0.0 and inv_mass[j] == 0.0:
                continue
            if count < cap:
                out_a[count] = min(i, j)
                out_b[count] = max(i, j)
            count += 1
    return count if count <= cap else -count


@njit(cache=True, nogil=True)
def find_pairs(pos, quat, vel, ang, shape, size, inv_mass, margin, dt):
    """(first (P,), second (P,), reach (N,)) for the bodies' AABBs; see the module docstring."""
    n = pos.shape[0]
    low = np.empty((n, 3))
    high = np.empty((n, 3))
    reach = np.empty(n)
    bounds(pos, quat, vel, ang, shape, size, margin, dt, low, high, reach)
    xs = np.empty(n)
    for i in range(n):
        xs[i] = low[i, 0]
    order = np.argsort(xs, kind="stable")
    cap = max(4 * n, 16)
    while True:
        out_a = np.empty(cap, np.int64)
        out_b = np.empty(cap, np.int64)
        count = sweep(low, high, order, inv_mass, out_a, out_b)
        if count >= 0:
            return out_a[:count], out_b[:count], reach
        cap = -count
