"""The angular terms of the soft step's contact rows (``body_soft``), computed once per
substep instead of once per pass.

A row along a direction d acting at arms rA, rB reads the relative velocity along d as
(vA − vB)·d + ωA·(rA×d) − ωB·(rB×d) and an impulse λ along it changes ωA by λ·IA⁻¹(rA×d)
and ωB by −λ·IB⁻¹(rB×d). Neither rA×d nor IA⁻¹(rA×d) changes during the passes (the bodies
do not move or turn until the drift), so ``prepare_arms`` writes them per row and a pass
reads 6 numbers a body instead of forming a cross product and a 3×3 product twice (Box2D's
contact solver keeps the same terms; measured on the 1000-box pit at rest, 4076 points in
1570 manifolds, 30 passes: 4.1 ms against 5.0 ms when recomputed in each pass).

Layout of the terms, 3 numbers each (B's are zero for scenery, b < 0):
* ``arm`` (M, 12), per point, d = n: rA×n, rB×n, IA⁻¹(rA×n), IB⁻¹(rB×n);
* ``farm`` (K, 30), per manifold, at the friction centre (fA, fB): fA×t1, fA×t2, fB×t1,
  fB×t2, IA⁻¹(fA×t1), IA⁻¹(fA×t2), IB⁻¹(fB×t1), IB⁻¹(fB×t2), and for the twist IA⁻¹n, IB⁻¹n.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True, inline="always")
def _terms(inv_i, i, rx, ry, rz, dx, dy, dz, out, at_cross, at_response):
    """Write r×d at ``out[at_cross:+3]`` and I⁻¹(r×d) of body i at ``out[at_response:+3]``
    (zeros for i < 0)."""
    cx = ry * dz - rz * dy
    cy = rz * dx - rx * dz
    cz = rx * dy - ry * dx
    if i < 0:
        cx = cy = cz = 0.0
    out[at_cross] = cx
    out[at_cross + 1] = cy
    out[at_cross + 2] = cz
    _response(inv_i, i, cx, cy, cz, out, at_response)


@njit(cache=True, inline="always")
def _response(inv_i, i, cx, cy, cz, out, at):
    """Write I⁻¹c of body i at ``out[at:+3]`` (zeros for i < 0)."""
    for u in range(3):
        out[at + u] = 0.0 if i < 0 else (
            inv_i[i, u, 0] * cx + inv_i[i, u, 1] * cy + inv_i[i, u, 2] * cz)


@njit(cache=True, nogil=True)
def prepare_arms(start, ca, cb, n, ra, rb, fa, fb, t1, t2, inv_i, arm, farm):
    """Fill ``arm`` (M, 12) per point and ``farm`` (K, 30) per manifold (module docstring)."""
    for c in range(ca.shape[0]):
        a, b = ca[c], cb[c]
        nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
        _terms(inv_i, a, ra[c, 0], ra[c, 1], ra[c, 2], nx, ny, nz, arm[c], 0, 6)
        _terms(inv_i, b, rb[c, 0], rb[c, 1], rb[c, 2], nx, ny, nz, arm[c], 3, 9)
    for k in range(t1.shape[0]):
        s0 = start[k]
        a, b = ca[s0], cb[s0]
        f = farm[k]
        for j in range(2):
            t = t1[k] if j == 0 else t2[k]
            _terms(inv_i, a, fa[k, 0], fa[k, 1], fa[k, 2], t[0], t[1], t[2], f, 3 * j,
                   12 + 3 * j)
            _terms(inv_i, b, fb[k, 0], fb[k, 1], fb[k, 2], t[0], t[1], t[2], f, 6 + 3 * j,
                   18 + 3 * j)
        _response(inv_i, a, n[s0, 0], n[s0, 1], n[s0, 2], f, 24)
        _response(inv_i, b, n[s0, 0], n[s0, 1], n[s0, 2], f, 27)


@njit(cache=True, inline="always")
def _along(vel, ang, i, dx, dy, dz, arms, row, at):
    """Velocity of body i's point along d: v·d + ω·(r×d), r×d at ``arms[row, at:+3]`` (2-D
    indexing: a row view taken in the loop made the passes 50 % slower)."""
    return (vel[i, 0] * dx + vel[i, 1] * dy + vel[i, 2] * dz + ang[i, 0] * arms[row, at]
            + ang[i, 1] * arms[row, at + 1] + ang[i, 2] * arms[row, at + 2])
