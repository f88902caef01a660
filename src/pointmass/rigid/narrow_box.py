"""Narrow phase for box–plane: one point per box corner under the plane, at most four.

A box resting flat gets its four bottom corners; a box sunk deeper than its height could have
more under the plane, and ``reduce_points`` keeps the deepest and the widest four. The id of a
point is its corner's index (bit k set = +half-extent along body axis k), stable while the box
rocks on the same corners.
"""

import numpy as np
from numba import njit

from .manifold import reduce_points
from .scalar import qrot


@njit(cache=True, nogil=True)
def box_axes(q):
    """World directions of the body axes of orientation q, as a (3, 3) array of rows."""
    axes = np.empty((3, 3))
    box_axes_into(q, axes)
    return axes


@njit(cache=True, nogil=True)
def box_axes_into(q, axes):
    """``box_axes`` written into ``axes`` (3, 3)."""
    for k in range(3):
        e0 = 1.0 if k == 0 else 0.0
        e1 = 1.0 if k == 1 else 0.0
        e2 = 1.0 if k == 2 else 0.0
        x, y, z = qrot(q[0], q[1], q[2], q[3], e0, e1, e2)
        axes[k, 0], axes[k, 1], axes[k, 2] = x, y, z


@njit(cache=True, nogil=True)
def box_plane(pb, qb, hb, n, d, margin, normal, points, depth, ids):
    """Box A (centre pb, orientation qb, half-extents hb) against the plane n·x = d (B)."""
    axes = box_axes(qb)
    cand = np.empty((8, 3))
    sep = np.empty(8)
    corner = np.empty(8, dtype=np.int64)
    count = 0
    for k in range(8):
        x, y, z = pb[0], pb[1], pb[2]
        for a in range(3):
            s = hb[a] if (k >> a) & 1 else -hb[a]
            x += s * axes[a, 0]
            y += s * axes[a, 1]
            z += s * axes[a, 2]
        gap = x * n[0] + y * n[1] + z * n[2] - d
        if gap < margin:
            # midway between the corner and its foot on the plane
            cand[count, 0] = x - 0.5 * gap * n[0]
            cand[count, 1] = y - 0.5 * gap * n[1]
            cand[count, 2] = z - 0.5 * gap * n[2]
            sep[count] = gap
            corner[count] = k
            count += 1
    keep = np.empty(4, dtype=np.int64)
    # np.int64: ``count`` starts as the constant 0, which would compile reduce_points again
    # for Literal[int](0) (see box_box.box_box_into)
    kept = reduce_points(cand, sep, np.int64(count), n, keep)
    for k in range(3):
        normal[k] = n[k]
    for j in range(kept):
        i = keep[j]
        points[j, 0], points[j, 1], points[j, 2] = cand[i, 0], cand[i, 1], cand[i, 2]
        depth[j] = -sep[i]
        ids[j] = corner[i]
    return kept
