"""Stage 3 of ``body_stages`` — the sequential-impulse passes over body contact points — with
each row's angular terms computed once per substep instead of once per pass.

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
The results equal ``body_stages``' formulas up to rounding (the products are grouped
differently), not bit for bit.
"""

from __future__ import annotations

import math

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


@njit(cache=True, nogil=True)
def solve_velocities(start, ca, cb, n, t1, t2, mu, radius, mass_n, mass_t1, mass_t2, mass_tw,
                     target, inv_mass, vel, ang, impulse, jt1, jt2, jtw, arm, farm, tolerance,
                     max_passes):
    """Gauss–Seidel passes (``body_stages``' stage 3) until no row's velocity changes by more
    than ``tolerance`` [m/s] in a pass (the twist's angular change counts times ρ), at most
    ``max_passes``. Per manifold k (rows ``start[k]`` to ``start[k + 1]``), each row applied
    before the next reads the velocities: the twist (skipped for one point), the two tangents
    at the centre (clamped together to the disc μ·Λ), both skipped when μ = 0, then each
    point's normal (accumulated, ≥ 0). Returns the passes run."""
    passes = 0
    while passes < max_passes:
        passes += 1
        largest = 0.0
        for k in range(t1.shape[0]):
            s0 = start[k]
            s1 = start[k + 1]
            a = ca[s0]
            b = cb[s0]
            wa = inv_mass[a]
            wb = inv_mass[b] if b >= 0 else 0.0
            nx, ny, nz = n[s0, 0], n[s0, 1], n[s0, 2]
            if mu[k] > 0.0:
                total = 0.0
                for c in range(s0, s1):
                    total += impulse[c]
                if mass_tw[k] != 0.0 and radius[k] != 0.0:  # twist, within ±μ·ρ·Λ
                    spin = ang[a, 0] * nx + ang[a, 1] * ny + ang[a, 2] * nz
                    if b >= 0:
                        spin -= ang[b, 0] * nx + ang[b, 1] * ny + ang[b, 2] * nz
                    limit = mu[k] * total * radius[k]
                    new = min(max(jtw[k] - spin * mass_tw[k], -limit), limit)
                    d = new - jtw[k]
                    jtw[k] = new
                    largest = max(largest, abs(d) / mass_tw[k] * radius[k])
                    for u in range(3):
                        ang[a, u] += d * farm[k, 24 + u]
                        if b >= 0:
                            ang[b, u] -= d * farm[k, 27 + u]
                # the tangents at the friction centre, within Coulomb's disc μ·Λ
                v1 = _along(vel, ang, a, t1[k, 0], t1[k, 1], t1[k, 2], farm, k, 0)
                v2 = _along(vel, ang, a, t2[k, 0], t2[k, 1], t2[k, 2], farm, k, 3)
                if b >= 0:
                    v1 -= _along(vel, ang, b, t1[k, 0], t1[k, 1], t1[k, 2], farm, k, 6)
                    v2 -= _along(vel, ang, b, t2[k, 0], t2[k, 1], t2[k, 2], farm, k, 9)
                new1 = jt1[k] - v1 * mass_t1[k]
                new2 = jt2[k] - v2 * mass_t2[k]
                limit = mu[k] * total
                size = math.sqrt(new1 * new1 + new2 * new2)
                if size > limit:
                    s = limit / size
                    new1 *= s
                    new2 *= s
                d1 = new1 - jt1[k]
                d2 = new2 - jt2[k]
                jt1[k] = new1
                jt2[k] = new2
                largest = max(largest,
                              abs(d1) * (1.0 / mass_t1[k] if mass_t1[k] > 0.0 else 0.0),
                              abs(d2) * (1.0 / mass_t2[k] if mass_t2[k] > 0.0 else 0.0))
                for u in range(3):
                    p = d1 * t1[k, u] + d2 * t2[k, u]
                    vel[a, u] += wa * p
                    ang[a, u] += d1 * farm[k, 12 + u] + d2 * farm[k, 15 + u]
                    if b >= 0:
                        vel[b, u] -= wb * p
                        ang[b, u] -= d1 * farm[k, 18 + u] + d2 * farm[k, 21 + u]
            for c in range(s0, s1):  # the normals: accumulated, pushes only
                if mass_n[c] == 0.0:
                    continue
                vs = _along(vel, ang, a, nx, ny, nz, arm, c, 0)
                if b >= 0:
                    vs -= _along(vel, ang, b, nx, ny, nz, arm, c, 3)
                new = max(impulse[c] + (target[c] - vs) * mass_n[c], 0.0)
                d = new - impulse[c]
                if d == 0.0:
                    continue
                impulse[c] = new
                largest = max(largest, abs(d) / mass_n[c])
                vel[a, 0] += wa * d * nx
                vel[a, 1] += wa * d * ny
                vel[a, 2] += wa * d * nz
                ang[a, 0] += d * arm[c, 6]
                ang[a, 1] += d * arm[c, 7]
                ang[a, 2] += d * arm[c, 8]
                if b >= 0:
                    vel[b, 0] -= wb * d * nx
                    vel[b, 1] -= wb * d * ny
                    vel[b, 2] -= wb * d * nz
                    ang[b, 0] -= d * arm[c, 9]
                    ang[b, 1] -= d * arm[c, 10]
                    ang[b, 2] -= d * arm[c, 11]
        if largest <= tolerance:
            break
    return passes
