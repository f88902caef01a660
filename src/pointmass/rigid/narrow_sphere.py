"""Narrow phase for pairs with a sphere: sphere–plane, sphere–sphere, sphere–box.

Each yields at most one point (a sphere touches anything convex at one point); the output
convention is ``manifold.py``'s. A plane is n·x = d with the solid on the side −n (a half-space,
the particles' ``Plane``); a box is (centre, orientation (w, x, y, z), half-extents).
"""

import math

from numba import njit

from .scalar import qrot, qrot_inv

#: Normal used when two centres coincide: any direction is right, so pick a fixed one (up) rather
#: than NaN; the bodies then separate vertically, deterministically.
FALLBACK_NORMAL = (0.0, 1.0, 0.0)


@njit(cache=True, nogil=True)
def sphere_plane(c, r, n, d, margin, normal, points, depth, ids):
    """Sphere (centre c (3,), radius r) against the plane n·x = d (unit n (3,)). A = sphere."""
    dist = c[0] * n[0] + c[1] * n[1] + c[2] * n[2] - d
    gap = dist - r
    if gap >= margin:
        return 0
    back = 0.5 * (dist + r)  # midway between the sphere's lowest point and the plane
    for k in range(3):
        normal[k] = n[k]
        points[0, k] = c[k] - back * n[k]
    depth[0] = -gap
    ids[0] = 0
    return 1


@njit(cache=True, nogil=True)
def sphere_sphere(ca, ra, cb, rb, margin, normal, points, depth, ids):
    """Sphere A (ca, ra) against sphere B (cb, rb)."""
    dx, dy, dz = ca[0] - cb[0], ca[1] - cb[1], ca[2] - cb[2]
    dist = math.sqrt(dx * dx + dy * dy + dz * dz)
    gap = dist - ra - rb
    if gap >= margin:
        return 0
    if dist > 0.0:
        nx, ny, nz = dx / dist, dy / dist, dz / dist
    else:
        nx, ny, nz = FALLBACK_NORMAL
    normal[0], normal[1], normal[2] = nx, ny, nz
    # midway between A's point ca − ra·n and B's point cb + rb·n
    s = 0.5 * (rb - ra)
    points[0, 0] = 0.5 * (ca[0] + cb[0]) + s * nx
    points[0, 1] = 0.5 * (ca[1] + cb[1]) + s * ny
    points[0, 2] = 0.5 * (ca[2] + cb[2]) + s * nz
    depth[0] = -gap
    ids[0] = 0
    return 1


@njit(cache=True, nogil=True)
def sphere_box(c, r, pb, qb, hb, margin, normal, points, depth, ids):
    """Sphere A (c, r) against box B (centre pb, orientation qb, half-extents hb).

    Outside the box the normal runs from the box's closest point to the centre (face, edge or
    corner region alike); with the centre inside, it is the normal of the nearest face. The id
    names the region: 0 outside, 1 + face index (axis·2 + side) inside.
    """
    lx, ly, lz = qrot_inv(qb[0], qb[1], qb[2], qb[3], c[0] - pb[0], c[1] - pb[1], c[2] - pb[2])
    cx, cy, cz = min(max(lx, -hb[0]), hb[0]), min(max(ly, -hb[1]), hb[1]), \
        min(max(lz, -hb[2]), hb[2])
    dx, dy, dz = lx - cx, ly - cy, lz - cz
    dist2 = dx * dx + dy * dy + dz * dz
    if dist2 > 0.0:  # centre outside: the closest point is on the surface
        dist = math.sqrt(dist2)
        gap = dist - r
        if gap >= margin:
            return 0
        nx, ny, nz = dx / dist, dy / dist, dz / dist
        feature = 0
    else:  # centre inside: push out through the nearest face
        axis, room = 0, hb[0] - abs(lx)
        if hb[1] - abs(ly) < room:
            axis, room = 1, hb[1] - abs(ly)
        if hb[2] - abs(lz) < room:
            axis, room = 2, hb[2] - abs(lz)
        local = (lx, ly, lz)
        side = 1.0 if local[axis] >= 0.0 else -1.0
        nx = side if axis == 0 else 0.0
        ny = side if axis == 1 else 0.0
        nz = side if axis == 2 else 0.0
        cx, cy, cz = cx + nx * room, cy + ny * room, cz + nz * room
        gap = -room - r
        feature = 1 + 2 * axis + (0 if side > 0 else 1)
    wx, wy, wz = qrot(qb[0], qb[1], qb[2], qb[3], nx, ny, nz)
    sx, sy, sz = qrot(qb[0], qb[1], qb[2], qb[3], cx, cy, cz)  # box surface point, world
    normal[0], normal[1], normal[2] = wx, wy, wz
    # midway between the box's surface point and the sphere's deepest point c − r·n
    points[0, 0] = 0.5 * (pb[0] + sx + c[0] - r * wx)
    points[0, 1] = 0.5 * (pb[1] + sy + c[1] - r * wy)
    points[0, 2] = 0.5 * (pb[2] + sz + c[2] - r * wz)
    depth[0] = -gap
    ids[0] = feature
    return 1
