"""Angular integration of one body with the implicit gyroscopic term (Box3D's method)."""

import numpy as np
from numba import njit

from pointmass.rigid.quaternion import cross, inv_rotate, quat_mul, quat_normalize, rotate


@njit(cache=True)
def _solve3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve a (3,3) x = b (3,) by Cramer's rule (numba's solver would need scipy)."""
    c0 = cross(a[:, 1], a[:, 2])
    det = a[0, 0] * c0[0] + a[1, 0] * c0[1] + a[2, 0] * c0[2]
    x = np.empty(3)
    for i in range(3):
        m = a.copy()
        m[:, i] = b
        ci = cross(m[:, 1], m[:, 2])
        x[i] = (m[0, 0] * ci[0] + m[1, 0] * ci[1] + m[2, 0] * ci[2]) / det
    return x


@njit(cache=True)
def gyroscopic_step(q, omega, inertia_body, h):
    """One Newton step of I(w2 - w1) + h w2 x I w2 = 0 in body coordinates.

    q (4,) orientation, omega (3,) world angular velocity [rad/s], inertia_body (3,) principal
    moments [kg m^2], h step [s]. Returns the new world angular velocity (3,).
    """
    w = inv_rotate(q, omega)
    iw = inertia_body * w
    f = h * cross(w, iw)
    jac = np.zeros((3, 3))
    for i in range(3):
        jac[i, i] = inertia_body[i]
    # d/dw (w x Iw) = skew(w) I - skew(Iw)
    for j in range(3):
        e = np.zeros(3)
        e[j] = 1.0
        col = cross(e, iw) + cross(w, inertia_body * e)
        for i in range(3):
            jac[i, j] += h * col[i]
    return rotate(q, w - _solve3(jac, f))


@njit(cache=True)
def advance_orientation(q, omega, h):
    """q' = normalize(q + h/2 [0, omega] q) for world angular velocity omega (3,)."""
    dq = quat_mul(np.array([0.0, omega[0], omega[1], omega[2]]), q)
    return quat_normalize(q + 0.5 * h * dq)
