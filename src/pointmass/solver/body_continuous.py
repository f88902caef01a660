"""Continuous collision of the soft step: a fast body is moved back along its step to where it
first comes within ``SLOP`` of a static body or a plane (Box2D v3's ``b2SolveContinuous``,
``src/solver.c``, with ``b2TimeOfImpact``'s target separation).

Why: the soft step finds its rows once a step, at the step's start (``rigid/collide.py``,
with the margin of what each body can travel). Measured on benchmarks/rigid_fuzz.py's
joint-free scenes (seeds 0–299, 300 steps, before this stage): 28 of 91 ended a step more than
2 cm inside something; 27 of them a fast body (one step's travel 0.3–26 × its smallest
half-extent, or spinning a corner 0.5–3.8 × that far) inside a wall or the ground, a body that
had a row against that plane at the step's start; one a pair of moving spheres. A spinning
box brings an unseen corner to the wall, a box thrown back by a bounce or a neighbour crosses
what its rows did not look for; and a rough box shot at 30–60° at a 5 cm wall spins on its
friction and leaves through it (tests/physics/rigid/test_thin_wall.py).

What (after the substeps and the restitution):

1. A body is fast, as Box2D's ``b2_isFast``, when the farthest point of its shape moved, or
   moves at its end velocity, more than ``SAFETY`` × its smallest half-extent in the step:
   ``|Δx| + θ·R`` or ``(|v| + |ω|·R)·dt``, R its bounding radius (0 for a sphere, whose
   surface a spin does not move). A slower body's rows, found with its travel, hold it.
2. Its step is swept as Box2D sweeps it: from the pose of the step's start to the pose of its
   end, the centre along the straight line and the orientation by the shortest rotation
   between the two (a slerp), against every static body and plane its swept bounding sphere
   comes near (and not the pairs a joint joins).
3. The time of impact of each is found by conservative advancement (Mirtich 1996; Box2D's
   ``b2TimeOfImpact`` is the same iteration on its distance): no point of the shape moves
   faster along the sweep than L = |Δx| + θ·R, so from a separation s the pair is at least
   s − L·Δt apart after Δt, and advancing by (s − target)/L never passes the target. The
   separations are exact signed distances (sphere and box against a plane, a sphere, a box)
   or, box against box, the largest gap over the 15 separating axes, a lower bound of the
   distance (which the advance needs: it only ever stops short).
4. The target is ``SLOP`` (Box2D's linear slop: where a TOI stops a body), or for a pair that
   starts the step within 2·``SLOP`` (touching: sliding, resting, pushed), ``SLOP`` less than
   its separation then: a body that rests or slides on the ground is left alone, one whose
   corner the step would drive deeper than ``SLOP`` past where it started is stopped first.
5. The body is put at the earliest time of impact's pose; its velocities are kept (Box2D's
   too): it arrives with them, and the next step's collision finds the contact within its
   travel and its row stops it.

Momentum: the stage moves positions only, so every body's linear momentum and spin are those
the solve gave; the angular momentum about a fixed origin, Σ x × p, changes by Δx × p of a
moved body. It acts only against static bodies and planes, which take momentum anyway (as
Box2D's clamp, which does not conserve it either); pairs of moving bodies are left to the
rows, so their collisions keep both momenta to round-off (tests/physics/rigid).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..rigid.scalar import qmul, qrot, qrot_inv
from ..rigid.shapes import BOX, SPHERE

#: Box2D's ``B2_LINEAR_SLOP`` [m]: the separation a time of impact stops a body at, and how
#: much deeper than at the step's start a touching pair may end it. (The collision's
#: speculative margin, ``collide.SPECULATIVE_MARGIN``, is the same 5 mm: the stopped body is
#: within it at the next step's start.)
SLOP = 0.005
#: Box2D's ``safetyFactor``: a body is fast when a point of it moves more than this fraction
#: of its smallest half-extent in a step.
SAFETY = 0.5
#: Conservative-advancement iterations at most (``b2TimeOfImpact``'s 20); each lands short of
#: the target, so stopping early is safe, only earlier.
ITERATIONS = 20
#: The advancement stops within this of the target [m] (``b2TimeOfImpact``'s 0.25 × slop).
TOLERANCE = 0.25 * SLOP


@njit(cache=True, nogil=True)
def _rotation_between(q0, q1):
    """The shortest rotation taking orientation q0 to q1, as (unit axis, angle ∈ [0, π])."""
    w, x, y, z = qmul(q1[0], q1[1], q1[2], q1[3], q0[0], -q0[1], -q0[2], -q0[3])
    if w < 0.0:
        w, x, y, z = -w, -x, -y, -z
    s = math.sqrt(x * x + y * y + z * z)
    if s < 1e-15:
        return 1.0, 0.0, 0.0, 0.0
    return x / s, y / s, z / s, 2.0 * math.atan2(s, min(w, 1.0))


@njit(cache=True, nogil=True)
def _pose_at(x0, q0, dx, ux, uy, uz, angle, t):
    """The swept pose at fraction t: x0 + t·dx and q0 turned by t·angle about u."""
    half = 0.5 * t * angle
    s = math.sin(half)
    w, x, y, z = qmul(math.cos(half), ux * s, uy * s, uz * s, q0[0], q0[1], q0[2], q0[3])
    n = math.sqrt(w * w + x * x + y * y + z * z)
    return (x0[0] + t * dx[0], x0[1] + t * dx[1], x0[2] + t * dx[2],
            w / n, x / n, y / n, z / n)


@njit(cache=True, nogil=True)
def _point_box(px, py, pz, c, qw, qx, qy, qz, h):
    """Signed distance from a point to a box (centre c, orientation q, half-extents h)."""
    lx, ly, lz = qrot_inv(qw, qx, qy, qz, px - c[0], py - c[1], pz - c[2])
    dx = abs(lx) - h[0]
    dy = abs(ly) - h[1]
    dz = abs(lz) - h[2]
    ox, oy, oz = max(dx, 0.0), max(dy, 0.0), max(dz, 0.0)
    return math.sqrt(ox * ox + oy * oy + oz * oz) + min(max(dx, dy, dz), 0.0)


@njit(cache=True, nogil=True)
def _box_axes(qw, qx, qy, qz, out):
    for k in range(3):
        e = (1.0 if k == 0 else 0.0, 1.0 if k == 1 else 0.0, 1.0 if k == 2 else 0.0)
        out[k, 0], out[k, 1], out[k, 2] = qrot(qw, qx, qy, qz, e[0], e[1], e[2])


@njit(cache=True, nogil=True)
def _reach(ax, h, lx, ly, lz):
    return (h[0] * abs(ax[0, 0] * lx + ax[0, 1] * ly + ax[0, 2] * lz)
            + h[1] * abs(ax[1, 0] * lx + ax[1, 1] * ly + ax[1, 2] * lz)
            + h[2] * abs(ax[2, 0] * lx + ax[2, 1] * ly + ax[2, 2] * lz))


@njit(cache=True, nogil=True)
def _box_box(pa, a, ha, pb, b, hb):
    """The largest gap of two boxes (axes rows a, b) over the 15 separating axes: their
    distance when apart along a face axis, a lower bound of it otherwise, and minus their
    penetration depth when they overlap."""
    dx, dy, dz = pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]
    best = -math.inf
    for k in range(15):
        if k < 3:
            lx, ly, lz = a[k, 0], a[k, 1], a[k, 2]
        elif k < 6:
            lx, ly, lz = b[k - 3, 0], b[k - 3, 1], b[k - 3, 2]
        else:
            i = (k - 6) // 3
            j = (k - 6) % 3
            lx = a[i, 1] * b[j, 2] - a[i, 2] * b[j, 1]
            ly = a[i, 2] * b[j, 0] - a[i, 0] * b[j, 2]
            lz = a[i, 0] * b[j, 1] - a[i, 1] * b[j, 0]
            n = math.sqrt(lx * lx + ly * ly + lz * lz)
            if n < 1e-6:  # parallel edges: the face axes cover them
                continue
            lx, ly, lz = lx / n, ly / n, lz / n
        gap = abs(dx * lx + dy * ly + dz * lz) - _reach(a, ha, lx, ly, lz) \
            - _reach(b, hb, lx, ly, lz)
        if gap > best:
            best = gap
    return best


@njit(cache=True, nogil=True)
def _separation(shape_i, size_i, px, py, pz, qw, qx, qy, qz, axes_i, axes_j, j, pos, shape,
                size, quat, plane_n, plane_d):
    """Signed separation of body i at pose (p, q) from static body j (≥ 0) or plane −1 − j."""
    if j < 0:
        s = -1 - j
        nx, ny, nz = plane_n[s, 0], plane_n[s, 1], plane_n[s, 2]
        d = px * nx + py * ny + pz * nz - plane_d[s]
        if shape_i == SPHERE:
            return d - size_i[0]
        _box_axes(qw, qx, qy, qz, axes_i)
        return d - _reach(axes_i, size_i, nx, ny, nz)
    if shape_i == SPHERE:
        if shape[j] == SPHERE:
            ex, ey, ez = px - pos[j, 0], py - pos[j, 1], pz - pos[j, 2]
            return math.sqrt(ex * ex + ey * ey + ez * ez) - size_i[0] - size[j, 0]
        qj = quat[j]
        return _point_box(px, py, pz, pos[j], qj[0], qj[1], qj[2], qj[3], size[j]) - size_i[0]
    if shape[j] == SPHERE:
        return _point_box(pos[j, 0], pos[j, 1], pos[j, 2], (px, py, pz), qw, qx, qy, qz,
                          size_i) - size[j, 0]
    _box_axes(qw, qx, qy, qz, axes_i)
    qj = quat[j]
    _box_axes(qj[0], qj[1], qj[2], qj[3], axes_j)
    return _box_box((px, py, pz), axes_i, size_i, pos[j], axes_j, size[j])


@njit(cache=True, nogil=True)
def _impact(i, j, x0, q0, dx, ux, uy, uz, angle, bound, limit, pos, shape, size, quat,
            plane_n, plane_d, axes_i, axes_j):
    """The fraction of the step (< ``limit``) at which body i's sweep first reaches the
    target separation from static body / plane j (module docstring), or ``limit``."""
    s = _separation(shape[i], size[i], x0[0], x0[1], x0[2], q0[0], q0[1], q0[2], q0[3],
                    axes_i, axes_j, j, pos, shape, size, quat, plane_n, plane_d)
    target = min(SLOP, s - SLOP)
    t = 0.0
    for _ in range(ITERATIONS):
        if s <= target + TOLERANCE:
            return t
        t += (s - target) / bound
        if t >= limit:
            return limit
        px, py, pz, qw, qx, qy, qz = _pose_at(x0, q0, dx, ux, uy, uz, angle, t)
        s = _separation(shape[i], size[i], px, py, pz, qw, qx, qy, qz, axes_i, axes_j, j, pos,
                        shape, size, quat, plane_n, plane_d)
    return t


@njit(cache=True, nogil=True)
def clamp(pos, quat, vel, ang, inv_mass, inv_inertia, inv_i, shape, size, awake, x_start,
          q_start, dt, plane_n, plane_d, exclude):
    """Move every fast awake body back to its earliest time of impact with a static body or a
    plane this step (module docstring); ``x_start``, ``q_start``: the poses of the step's start;
    ``exclude``: sorted keys lo·N + hi of jointed pairs. Returns how many bodies it moved."""
    nb = pos.shape[0]
    axes_i = np.empty((3, 3))
    axes_j = np.empty((3, 3))
    dx = np.empty(3)
    moved = 0
    statics = 0
    for j in range(nb):
        if inv_mass[j] == 0.0 and (shape[j] == SPHERE or shape[j] == BOX):
            statics += 1
    for i in range(nb):
        if inv_mass[i] == 0.0 or not awake[i] or (shape[i] != SPHERE and shape[i] != BOX):
            continue
        if shape[i] == SPHERE:
            radius = 0.0  # a spin does not move a sphere's surface
            smallest = size[i, 0]
            bounding = size[i, 0]
        else:
            radius = math.sqrt(size[i, 0] ** 2 + size[i, 1] ** 2 + size[i, 2] ** 2)
            smallest = min(size[i, 0], size[i, 1], size[i, 2])
            bounding = radius
        x0 = x_start[i]
        q0 = q_start[i]
        for k in range(3):
            dx[k] = pos[i, k] - x0[k]
        ux, uy, uz, angle = _rotation_between(q0, quat[i])
        travel = math.sqrt(dx[0] ** 2 + dx[1] ** 2 + dx[2] ** 2)
        bound = travel + angle * radius
        speed = math.sqrt(vel[i, 0] ** 2 + vel[i, 1] ** 2 + vel[i, 2] ** 2)
        spin = math.sqrt(ang[i, 0] ** 2 + ang[i, 1] ** 2 + ang[i, 2] ** 2)
        if max(bound, (speed + spin * radius) * dt) <= SAFETY * smallest or bound == 0.0:
            continue
        best = 1.0
        for s in range(plane_n.shape[0]):  # planes its swept bounding sphere comes near
            n0 = (x0[0] * plane_n[s, 0] + x0[1] * plane_n[s, 1] + x0[2] * plane_n[s, 2])
            n1 = (pos[i, 0] * plane_n[s, 0] + pos[i, 1] * plane_n[s, 1]
                  + pos[i, 2] * plane_n[s, 2])
            if min(n0, n1) - plane_d[s] - bounding > SLOP:
                continue
            best = _impact(i, -1 - s, x0, q0, dx, ux, uy, uz, angle, bound, best, pos, shape,
                           size, quat, plane_n, plane_d, axes_i, axes_j)
        if statics:
            for j in range(nb):
                if inv_mass[j] != 0.0 or j == i or (shape[j] != SPHERE and shape[j] != BOX):
                    continue
                key = min(i, j) * nb + max(i, j)
                at = np.searchsorted(exclude, key)
                if at < exclude.shape[0] and exclude[at] == key:
                    continue
                # the static body's bounding sphere against the segment the centre swept
                reach_j = size[j, 0] if shape[j] == SPHERE else math.sqrt(
                    size[j, 0] ** 2 + size[j, 1] ** 2 + size[j, 2] ** 2)
                f = 0.0
                if travel > 0.0:
                    f = ((pos[j, 0] - x0[0]) * dx[0] + (pos[j, 1] - x0[1]) * dx[1]
                         + (pos[j, 2] - x0[2]) * dx[2]) / (travel * travel)
                    f = min(max(f, 0.0), 1.0)
                cx = x0[0] + f * dx[0] - pos[j, 0]
                cy = x0[1] + f * dx[1] - pos[j, 1]
                cz = x0[2] + f * dx[2] - pos[j, 2]
                if math.sqrt(cx * cx + cy * cy + cz * cz) - bounding - reach_j > SLOP:
                    continue
                best = _impact(i, j, x0, q0, dx, ux, uy, uz, angle, bound, best, pos, shape,
                               size, quat, plane_n, plane_d, axes_i, axes_j)
        if best >= 1.0:
            continue
        px, py, pz, qw, qx, qy, qz = _pose_at(x0, q0, dx, ux, uy, uz, angle, best)
        pos[i, 0], pos[i, 1], pos[i, 2] = px, py, pz
        quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3] = qw, qx, qy, qz
        _box_axes(qw, qx, qy, qz, axes_i)  # rows: the body axes in world, R's columns
        for a in range(3):
            for b in range(3):
                v = 0.0
                for k in range(3):
                    v += axes_i[k, a] * inv_inertia[i, k] * axes_i[k, b]
                inv_i[i, a, b] = v
        moved += 1
    return moved


def sweep_back(bodies, planes, exclude, x_start: np.ndarray, q_start: np.ndarray,
               dt: float) -> int:
    """``clamp`` on a ``Bodies`` and the world's ``Plane``s; returns the bodies moved."""
    b = bodies
    n = len(planes)
    plane_n = np.array([p.normal for p in planes], dtype=np.float64).reshape(n, 3)
    plane_d = np.array([p.offset for p in planes], dtype=np.float64)
    if exclude is None:
        exclude = np.zeros(0, np.int64)
    return int(clamp(b.position, b.orientation, b.velocity, b.angular_velocity, b.inv_mass,
                     b.inv_inertia, b.inv_inertia_world, b.shape, b.size, b.awake, x_start,
                     q_start, dt, plane_n, plane_d, exclude))
