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

from .direct import solve_lcp

#: Sets up to this many points get the direct solve (a 10-box tower has 40). Its cost grows as
#: the cube: measured 9 ms a solve at ~250 points on this 2-core machine, the whole step
#: for a 100-body pile.
DIRECT_MAX_POINTS = 64


def solve_normals(bodies, contacts, rows) -> None:
    """Replace the accumulated normal impulses by the exact ones; apply the difference."""
    c = contacts
    b = bodies
    m = c.count
    ends = np.concatenate([c.a, c.b[c.b >= 0]])
    used, cols = np.unique(ends, return_inverse=True)
    col_a = cols[:m]
    col_b = np.full(m, -1)
    col_b[c.b >= 0] = cols[m:]
    k = used.shape[0]
    jac = np.zeros((m, k, 6))
    rows_idx = np.arange(m)
    jac[rows_idx, col_a, :3] = c.normal
    jac[rows_idx, col_a, 3:] = np.cross(c.r_a, c.normal)
    has_b = col_b >= 0
    jac[rows_idx[has_b], col_b[has_b], :3] = -c.normal[has_b]
    jac[rows_idx[has_b], col_b[has_b], 3:] = -np.cross(c.r_b[has_b], c.normal[has_b])
    w = np.zeros((k, 6, 6))
    w[:, 0, 0] = w[:, 1, 1] = w[:, 2, 2] = b.inv_mass[used]
    w[:, 3:, 3:] = b.inv_inertia_world[used]
    jw = np.einsum("mki,kij->mkj", jac, w).reshape(m, 6 * k)
    j2 = jac.reshape(m, 6 * k)
    a_mat = jw @ j2.T
    vel = np.concatenate([b.velocity[used], b.angular_velocity[used]], axis=1).reshape(-1)
    lam0 = rows.impulse.copy()
    q = j2 @ vel - rows.target - a_mat @ lam0
    free = np.zeros(m, dtype=bool)
    lam = solve_lcp(a_mat, q, (lam0 > 0) | (q + a_mat @ lam0 < 0), free)
    dv = (jw.T @ (lam - lam0)).reshape(k, 6)
    b.velocity[used] += dv[:, :3]
    b.angular_velocity[used] += dv[:, 3:]
    rows.impulse[:] = lam
