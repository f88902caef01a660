"""The direct solve of ``direct.py`` for rigid-body contact points (normal rows only).

Gauss–Seidel on a stack converges slowly: the error of a tower of n boxes shrinks by about
cos²(π/(n+1)) per pass, so a cold 10-box tower still squeezes by 1.6 mm after 30 passes and
then walks sideways (measured: top box 0.13 m off after 10 s). A small set that has not
converged gets the exact normal impulses instead: the same complementarity problem and
active-set solver as the particles (``direct.solve_lcp``), with the rows J = [n, rA×n | −n,
−rB×n] and W the bodies' inverse mass and world inverse inertia blocks. Friction impulses are
held fixed during the solve; Gauss–Seidel passes after it settle them.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .body_stages import _kick, _relative_velocity
from .direct import solve_lcp

#: Sets up to this many points get the direct solve (a 10-box tower has 40). Its cost grows as
#: the cube: measured 9 ms a solve at ~250 points on this 2-core machine, the whole step
#: for a 100-body pile.
DIRECT_MAX_POINTS = 64


@njit(cache=True, inline="always")
def _coupling(inv_mass, inv_i, i, nx, ny, nz, cx, cy, cz, mx, my, mz, ex, ey, ez):
    """J_i W J_jᵀ through body i: w n·m + (r_i×n)·I⁻¹(r_j×m), with c = r_i×n, e = r_j×m."""
    t = inv_i[i]
    return (inv_mass[i] * (nx * mx + ny * my + nz * mz)
            + cx * (t[0, 0] * ex + t[0, 1] * ey + t[0, 2] * ez)
            + cy * (t[1, 0] * ex + t[1, 1] * ey + t[1, 2] * ez)
            + cz * (t[2, 0] * ex + t[2, 1] * ey + t[2, 2] * ez))


@njit(cache=True, nogil=True)
def delassus(ca, cb, n, ra, rb, inv_mass, inv_i, vel, ang, a_mat, jv):
    """The normal rows' A = J W Jᵀ (M, M) and J·v (M,), the separating velocities [m/s]."""
    m = ca.shape[0]
    arm = np.empty((m, 2, 3))  # r×n of each row's two ends (b's with the sign of −n)
    for c in range(m):
        nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
        for side in range(2):
            r = ra if side == 0 else rb
            arm[c, side, 0] = r[c, 1] * nz - r[c, 2] * ny
            arm[c, side, 1] = r[c, 2] * nx - r[c, 0] * nz
            arm[c, side, 2] = r[c, 0] * ny - r[c, 1] * nx
        vx, vy, vz = _relative_velocity(vel, ang, ca[c], cb[c], ra[c, 0], ra[c, 1], ra[c, 2],
                                        rb[c, 0], rb[c, 1], rb[c, 2])
        jv[c] = vx * nx + vy * ny + vz * nz
    for c in range(m):
        for d in range(c, m):
            total = 0.0
            for sc in range(2):
                i = ca[c] if sc == 0 else cb[c]
                if i < 0:
                    continue
                for sd in range(2):
                    if (ca[d] if sd == 0 else cb[d]) != i:
                        continue
                    sign = 1.0 if sc == sd else -1.0
                    total += sign * _coupling(
                        inv_mass, inv_i, i, n[c, 0], n[c, 1], n[c, 2], arm[c, sc, 0],
                        arm[c, sc, 1], arm[c, sc, 2], n[d, 0], n[d, 1], n[d, 2], arm[d, sd, 0],
                        arm[d, sd, 1], arm[d, sd, 2])
            a_mat[c, d] = total
            a_mat[d, c] = total


@njit(cache=True, nogil=True)
def apply_normals(ca, cb, n, ra, rb, inv_mass, inv_i, vel, ang, change):
    """Apply the normal impulses ``change`` (M,) [N·s] to both ends of each row."""
    for c in range(ca.shape[0]):
        px, py, pz = change[c] * n[c, 0], change[c] * n[c, 1], change[c] * n[c, 2]
        for side in range(2):
            i = ca[c] if side == 0 else cb[c]
            if i < 0:
                continue
            r = ra if side == 0 else rb
            s = 1.0 if side == 0 else -1.0
            dvx, dvy, dvz, dwx, dwy, dwz = _kick(inv_mass, inv_i, i, r[c, 0], r[c, 1], r[c, 2],
                                                 s * px, s * py, s * pz, 0.0, 0.0, 0.0)
            vel[i, 0] += dvx
            vel[i, 1] += dvy
            vel[i, 2] += dvz
            ang[i, 0] += dwx
            ang[i, 1] += dwy
            ang[i, 2] += dwz


def solve_normals(bodies, contacts, rows) -> None:
    """Replace the accumulated normal impulses by the exact ones; apply the difference."""
    c = contacts
    b = bodies
    m = c.count
    a_mat = np.empty((m, m))
    jv = np.empty(m)
    delassus(c.a, c.b, c.normal, c.r_a, c.r_b, b.inv_mass, b.inv_inertia_world, b.velocity,
             b.angular_velocity, a_mat, jv)
    lam0 = rows.impulse.copy()
    q = jv - rows.target - a_mat @ lam0
    lam = solve_lcp(a_mat, q, (lam0 > 0) | (q + a_mat @ lam0 < 0), np.zeros(m, dtype=bool))
    apply_normals(c.a, c.b, c.normal, c.r_a, c.r_b, b.inv_mass, b.inv_inertia_world,
                  b.velocity, b.angular_velocity, lam - lam0)
    rows.impulse[:] = lam
