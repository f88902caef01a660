"""Unit quaternions (w, x, y, z) and small 3x3 helpers as numba-compatible functions.

Quaternions are float64 arrays of shape (4,), scalar first. Rotations are active:
``rotate(q, v)`` turns the body-space vector ``v`` into world space.
"""

import math

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def quat_mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product a*b (apply b, then a)."""
    out = np.empty(4)
    out[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3]
    out[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2]
    out[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1]
    out[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]
    return out


@njit(cache=True, nogil=True)
def quat_conj(q: np.ndarray) -> np.ndarray:
    """Conjugate, the inverse of a unit quaternion."""
    return np.array([q[0], -q[1], -q[2], -q[3]])


@njit(cache=True, nogil=True)
def quat_normalize(q: np.ndarray) -> np.ndarray:
    """q / |q|; the identity for a zero quaternion (never NaN)."""
    n = np.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    if n == 0.0:
        return np.array([1.0, 0.0, 0.0, 0.0])
    return q / n


@njit(cache=True, nogil=True)
def quat_from_axis_angle(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotation by ``angle`` radians about ``axis`` (normalised here; zero axis -> identity)."""
    n = np.sqrt(axis[0] ** 2 + axis[1] ** 2 + axis[2] ** 2)
    if n == 0.0:
        return np.array([1.0, 0.0, 0.0, 0.0])
    s = np.sin(0.5 * angle) / n
    return np.array([np.cos(0.5 * angle), axis[0] * s, axis[1] * s, axis[2] * s])


def quat_from_axis_angle_numpy(axis, angle: float) -> np.ndarray:
    """``quat_from_axis_angle`` in plain Python floats, for a scene built from Python: the same
    bits (tested) and nothing to compile while it is built (see ``world_inv_inertia_numpy``)."""
    ax, ay, az = (float(c) for c in axis)
    n = math.sqrt(ax ** 2 + ay ** 2 + az ** 2)
    if n == 0.0:
        return np.array([1.0, 0.0, 0.0, 0.0])
    s = math.sin(0.5 * angle) / n
    return np.array([math.cos(0.5 * angle), ax * s, ay * s, az * s])


@njit(cache=True, nogil=True)
def quat_to_matrix(q: np.ndarray) -> np.ndarray:
    """3x3 rotation matrix of a unit quaternion."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    m = np.empty((3, 3))
    m[0, 0] = 1 - 2 * (y * y + z * z)
    m[0, 1] = 2 * (x * y - w * z)
    m[0, 2] = 2 * (x * z + w * y)
    m[1, 0] = 2 * (x * y + w * z)
    m[1, 1] = 1 - 2 * (x * x + z * z)
    m[1, 2] = 2 * (y * z - w * x)
    m[2, 0] = 2 * (x * z - w * y)
    m[2, 1] = 2 * (y * z + w * x)
    m[2, 2] = 1 - 2 * (x * x + y * y)
    return m


@njit(cache=True, nogil=True)
def rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rotate body-space vector v (3,) into world space."""
    return mat_vec(quat_to_matrix(q), v)


@njit(cache=True, nogil=True)
def inv_rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rotate world-space vector v (3,) into body space."""
    return mat_vec(quat_to_matrix(q).T, v)


@njit(cache=True, nogil=True)
def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b for (3,) vectors."""
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )


@njit(cache=True, nogil=True)
def skew(a: np.ndarray) -> np.ndarray:
    """Matrix S with S @ b == a x b."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


@njit(cache=True, nogil=True)
def world_inv_inertia(q: np.ndarray, inv_inertia_body: np.ndarray) -> np.ndarray:
    """R diag(inv_inertia_body) R^T: world inverse inertia (3,3) from principal values (3,)."""
    r = quat_to_matrix(q)
    out = np.zeros((3, 3))
    for i in range(3):
        for j in range(3):
            for k in range(3):
                out[i, j] += r[i, k] * inv_inertia_body[k] * r[j, k]
    return out


def world_inv_inertia_numpy(q: np.ndarray, inv_inertia_body: np.ndarray) -> np.ndarray:
    """``world_inv_inertia`` in numpy, for one body set from Python (adding a body, setting an
    orientation): the same products summed in the same order, so the same bits (tested), and
    no kernel to compile while a demo is built. On a fresh install that compile (numba's first,
    with its array helpers: seconds) held up a window until the scene existed; now the first
    step compiles it, in the window's worker, under its notice."""
    w, x, y, z = (float(c) for c in q)
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    inv = np.asarray(inv_inertia_body, dtype=np.float64)
    out = np.zeros((3, 3))
    for k in range(3):
        out += (r[:, k] * inv[k])[:, None] * r[None, :, k]
    return out


@njit(cache=True, nogil=True)
def mat_vec(m: np.ndarray, v: np.ndarray) -> np.ndarray:
    """m (3,3) times v (3,), in plain loops (numba's @ would need scipy)."""
    out = np.zeros(3)
    for i in range(3):
        out[i] = m[i, 0] * v[0] + m[i, 1] * v[1] + m[i, 2] * v[2]
    return out
