"""The rows of a joint's angular constraints in the current pose: per slot a world axis, the
position value C and the row type (an equality, a one-sided limit, or off). What a hinge's two
locks and a cone's swing and twist limits mean geometrically; the solver (``pointmass.solver``:
``joint_stages``, ``joint_soft``) builds its velocity rows and soft position bias from
them, and ``JointSet.angular_errors`` reports how far each joint is off them. Here, in
``rigid``, so that ``rigid`` never imports ``solver`` (the solver imports the bodies' and
joints' definitions, one direction only)."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .joints import BALL, HINGE
from .scalar import qmul, qrot

#: Row types of an angular slot.
OFF = 0
EQUAL = 1
LIMIT = 2


@njit(cache=True, nogil=True)
def _frames(quat, a, b, fa, fb, j):
    """World quaternions of the joint frame as carried by A and by B (x axis: the joint axis)."""
    qa = qmul(quat[a, 0], quat[a, 1], quat[a, 2], quat[a, 3], fa[j, 0], fa[j, 1], fa[j, 2],
              fa[j, 3])
    if b >= 0:
        qb = qmul(quat[b, 0], quat[b, 1], quat[b, 2], quat[b, 3], fb[j, 0], fb[j, 1], fb[j, 2],
                  fb[j, 3])
    else:
        qb = (fb[j, 0], fb[j, 1], fb[j, 2], fb[j, 3])
    return qa, qb


@njit(cache=True, nogil=True)
def _twist(qa, qb):
    """Angle [rad] A has turned about the joint axis relative to B (swing–twist decomposition
    of qb⁻¹·qa: its twist part is (w, x, 0, 0) normalised). Its rate is (ωA − ωB)·axis."""
    w, x, _, _ = qmul(qb[0], -qb[1], -qb[2], -qb[3], qa[0], qa[1], qa[2], qa[3])
    if w < 0.0:
        w, x = -w, -x
    return 2.0 * math.atan2(x, w)


@njit(cache=True, nogil=True)
def _limit_row(out, s, angle, low, high, ux, uy, uz):
    """Slot s: the nearer bound of [low, high] on ``angle``, whose rate is u·(ωB − ωA)."""
    if low == -math.inf and high == math.inf:
        out[s, 4] = OFF
        return
    if angle < 0.5 * (low + high):
        out[s, 0], out[s, 1], out[s, 2], out[s, 3] = ux, uy, uz, angle - low
    else:
        out[s, 0], out[s, 1], out[s, 2], out[s, 3] = -ux, -uy, -uz, high - angle
    out[s, 4] = LIMIT


@njit(cache=True, nogil=True)
def relative_spin(ang, a, b, ux, uy, uz):
    """An angular row's rate: (ω_b − ω_a)·u about its unit axis u (ω_b = 0 for the world,
    b < 0)."""
    rel = 0.0
    for k in range(3):
        wb = ang[b, k] if b >= 0 else 0.0
        rel += (wb - ang[a, k]) * (ux if k == 0 else uy if k == 1 else uz)
    return rel


@njit(cache=True, nogil=True)
def angular_rows(quat, a, b, fa, fb, kind, lim, j, out):
    """The angular rows of joint j in the current pose into ``out`` (3, 5): per slot the world
    axis u (3), the position value C [rad] and the row type (OFF, EQUAL, LIMIT)."""
    for s in range(3):
        out[s, 4] = OFF
    if kind[j] == BALL:
        return
    qa, qb = _frames(quat, a, b, fa, fb, j)
    ax, ay, az = qrot(qa[0], qa[1], qa[2], qa[3], 1.0, 0.0, 0.0)
    bx, by, bz = qrot(qb[0], qb[1], qb[2], qb[3], 1.0, 0.0, 0.0)
    if kind[j] == HINGE:
        # locks: B's axis has no component along A's two cross directions
        for s in range(2):
            cx, cy, cz = qrot(qa[0], qa[1], qa[2], qa[3], 0.0, 1.0 - s, 1.0 * s)
            out[s, 0] = by * cz - bz * cy  # d(b·c)/dt = (ωB − ωA)·(b × c)
            out[s, 1] = bz * cx - bx * cz
            out[s, 2] = bx * cy - by * cx
            out[s, 3] = bx * cx + by * cy + bz * cz
            out[s, 4] = EQUAL
        _limit_row(out, 2, _twist(qa, qb), lim[j, 1], lim[j, 2], -ax, -ay, -az)
        return
    # cone: swing = angle between the axes, dswing/dt = (ωB − ωA)·(a × b)/|a × b|
    nx, ny, nz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
    size = math.sqrt(nx * nx + ny * ny + nz * nz)
    if lim[j, 0] < math.pi and size > 1e-9:
        swing = math.atan2(size, ax * bx + ay * by + az * bz)
        out[0, 0], out[0, 1], out[0, 2] = -nx / size, -ny / size, -nz / size
        out[0, 3] = lim[j, 0] - swing
        out[0, 4] = LIMIT
    # twist about the mean axis (exact when the swing is small)
    mx, my, mz = ax + bx, ay + by, az + bz
    size = math.sqrt(mx * mx + my * my + mz * mz)
    if size > 1e-9:
        _limit_row(out, 1, _twist(qa, qb), lim[j, 1], lim[j, 2], -mx / size, -my / size,
                   -mz / size)


@njit(cache=True, nogil=True)
def angular_errors(ja, jb, fa, fb, kind, lim, quat, out):
    """Per joint, the largest angle [rad] by which it is beyond a limit or off its hinge axis
    now (0 when every angular row is met), into ``out`` (J,)."""
    rows = np.empty((3, 5))
    for j in range(ja.shape[0]):
        angular_rows(quat, ja[j], jb[j], fa, fb, kind, lim, j, rows)
        worst = 0.0
        for s in range(3):
            if rows[s, 4] == EQUAL:
                # C = b·c = sin of the angle off the axis
                worst = max(worst, math.asin(min(1.0, abs(rows[s, 3]))))
            elif rows[s, 4] == LIMIT:
                worst = max(worst, -rows[s, 3])
        out[j] = worst
