"""Quaternion and 3-vector operations on scalars, for hot numba loops.

``quaternion.py`` works on small arrays, which reads well but allocates: in a loop over bodies
each ``np.array`` costs about as much as the arithmetic. These take and return plain floats
(tuples), so a driver loop loads, calls and stores without any allocation. Quaternions are
(w, x, y, z), scalar first, as in ``quaternion.py``.
"""

import math

from numba import njit


@njit(cache=True, nogil=True)
def qrot(qw, qx, qy, qz, vx, vy, vz):
    """Rotate (vx, vy, vz) by the unit quaternion q (body space -> world space)."""
    # v' = v + 2w (u x v) + 2 u x (u x v), u = (qx, qy, qz)
    tx = 2.0 * (qy * vz - qz * vy)
    ty = 2.0 * (qz * vx - qx * vz)
    tz = 2.0 * (qx * vy - qy * vx)
    return (vx + qw * tx + (qy * tz - qz * ty),
            vy + qw * ty + (qz * tx - qx * tz),
            vz + qw * tz + (qx * ty - qy * tx))


@njit(cache=True, nogil=True)
def qrot_inv(qw, qx, qy, qz, vx, vy, vz):
    """Rotate (vx, vy, vz) by the conjugate of q (world space -> body space)."""
    return qrot(qw, -qx, -qy, -qz, vx, vy, vz)


@njit(cache=True, nogil=True)
def qmul(aw, ax, ay, az, bw, bx, by, bz):
    """Hamilton product a*b (apply b, then a)."""
    return (aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw)


@njit(cache=True, nogil=True)
def qnormalize(qw, qx, qy, qz):
    """q / |q|; the identity for a zero quaternion (never NaN)."""
    n = math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    if n == 0.0:
        return 1.0, 0.0, 0.0, 0.0
    return qw / n, qx / n, qy / n, qz / n


@njit(cache=True, nogil=True)
def turn(quat, i, tx, ty, tz):
    """Rotate row i of ``quat`` (N, 4) by the small rotation vector θ = (tx, ty, tz) [rad]:
    q += ½(0, θ)q, normalised (the position projections' angular correction). Nothing for
    i < 0 (the world) or θ = 0."""
    if i < 0 or (tx == 0.0 and ty == 0.0 and tz == 0.0):
        return
    dw, dx, dy, dz = qmul(0.0, tx, ty, tz, quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3])
    qw, qx, qy, qz = qnormalize(quat[i, 0] + 0.5 * dw, quat[i, 1] + 0.5 * dx,
                                quat[i, 2] + 0.5 * dy, quat[i, 3] + 0.5 * dz)
    quat[i, 0] = qw
    quat[i, 1] = qx
    quat[i, 2] = qy
    quat[i, 3] = qz


@njit(cache=True, nogil=True)
def qexp(wx, wy, wz, h):
    """Unit quaternion of a rotation by the angle h·|w| about w: the exact rotation of a constant
    angular velocity w [rad/s] over h [s] (not the first-order q + ½h(0, w)q, which stretches q
    and turns too little at large h·|w|)."""
    n = math.sqrt(wx * wx + wy * wy + wz * wz)
    if n == 0.0:
        return 1.0, 0.0, 0.0, 0.0
    half = 0.5 * h * n
    s = math.sin(half) / n
    return math.cos(half), wx * s, wy * s, wz * s


@njit(cache=True, nogil=True)
def axis_rotate(ax, ay, az, angle, vx, vy, vz):
    """Rotate v by ``angle`` [rad] about the axis a (need not be unit; zero -> v), Rodrigues."""
    n = math.sqrt(ax * ax + ay * ay + az * az)
    if n == 0.0:
        return vx, vy, vz
    ux, uy, uz = ax / n, ay / n, az / n
    c = math.cos(angle)
    s = math.sin(angle)
    d = (ux * vx + uy * vy + uz * vz) * (1.0 - c)
    return (vx * c + (uy * vz - uz * vy) * s + ux * d,
            vy * c + (uz * vx - ux * vz) * s + uy * d,
            vz * c + (ux * vy - uy * vx) * s + uz * d)


@njit(cache=True, nogil=True)
def solve3(a00, a01, a02, a10, a11, a12, a20, a21, a22, bx, by, bz):
    """Solve the 3x3 system A x = b by Cramer's rule; (0, 0, 0) if A is singular."""
    c00 = a11 * a22 - a12 * a21
    c01 = a12 * a20 - a10 * a22
    c02 = a10 * a21 - a11 * a20
    det = a00 * c00 + a01 * c01 + a02 * c02
    if det == 0.0:
        return 0.0, 0.0, 0.0
    inv = 1.0 / det
    x = (bx * c00 + by * (a02 * a21 - a01 * a22) + bz * (a01 * a12 - a02 * a11)) * inv
    y = (bx * c01 + by * (a00 * a22 - a02 * a20) + bz * (a02 * a10 - a00 * a12)) * inv
    z = (bx * c02 + by * (a01 * a20 - a00 * a21) + bz * (a00 * a11 - a01 * a10)) * inv
    return x, y, z
