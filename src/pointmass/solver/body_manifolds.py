"""Friction once per manifold (Box3D's model, rigid-notes §2): the rows of a manifold share one
friction block at their friction centre — two tangent impulses and a twist impulse about the
normal — instead of two tangents at every point.

A manifold is a run of consecutive rows with the same bodies and the same normal (the narrow
phase writes a pair's ≤ 4 points together, ``rigid/collide.py``; a particle–body row is a
manifold of one). The block acts at the centre of the points, so a resting face costs three
friction rows instead of eight, and a single point (a sphere) is exactly the per-point model.

Limits, with Λ the manifold's summed normal impulse: the tangent impulse lies in the disc
μ·Λ (Coulomb's cone for the whole face) and the twist impulse within ±μ·ρ·Λ, ρ the mean
distance of the points from the centre — the torque per-point friction could give the same
points under equal loads; ρ = 0 for one point, which then has no twist friction.

The impulse history keeps friction per point key (``history.py``): each point of a manifold
keeps 1/k of the block, as the world vector j1·t1 + j2·t2 + jτ·n (the twist rides on the
normal component, which tangent friction never uses); a manifold recalls the sum of what its
points kept, so a point that appears or vanishes changes the warm start by its share only.
A manifold recalls only what its passes revise (no twist for one point, nothing for μ = 0):
an impulse no row clamps would be applied and kept again every step (``gather_friction``).
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True, inline="always")
def arm_mass(inv_i, i, rx, ry, rz, dx, dy, dz):
    """(r×d)·I⁻¹(r×d) for body i (read only)."""
    cx = ry * dz - rz * dy
    cy = rz * dx - rx * dz
    cz = rx * dy - ry * dx
    m = inv_i[i]
    return (cx * (m[0, 0] * cx + m[0, 1] * cy + m[0, 2] * cz)
            + cy * (m[1, 0] * cx + m[1, 1] * cy + m[1, 2] * cz)
            + cz * (m[2, 0] * cx + m[2, 1] * cy + m[2, 2] * cz))


@njit(cache=True, inline="always")
def _basis(nx, ny, nz):
    """Two unit tangents (t1, t2) with (n, t1, t2) right-handed; a fixed function of n, so the
    friction impulse kept for warm starting means the same thing next step."""
    if abs(nx) >= 0.57735:
        s = 1.0 / math.sqrt(nx * nx + ny * ny)
        ax, ay, az = ny * s, -nx * s, 0.0
    else:
        s = 1.0 / math.sqrt(ny * ny + nz * nz)
        ax, ay, az = 0.0, nz * s, -ny * s
    return ax, ay, az, ny * az - nz * ay, nz * ax - nx * az, nx * ay - ny * ax


@njit(cache=True, nogil=True)
def find_manifolds(ca, cb, n, start):
    """Write the first row of each manifold into ``start`` (M + 1,) and the row count after
    the last; returns the number of manifolds K (``start[:K + 1]`` is valid)."""
    k = 0
    m = ca.shape[0]
    for c in range(m):
        if (c == 0 or ca[c] != ca[c - 1] or cb[c] != cb[c - 1] or n[c, 0] != n[c - 1, 0]
                or n[c, 1] != n[c - 1, 1] or n[c, 2] != n[c - 1, 2]):
            start[k] = c
            k += 1
    start[k] = m
    return k


@njit(cache=True, inline="always")
def _inv_inertia_along(inv_i, i, nx, ny, nz):
    """n·I⁻¹n of body i."""
    m = inv_i[i]
    return (nx * (m[0, 0] * nx + m[0, 1] * ny + m[0, 2] * nz)
            + ny * (m[1, 0] * nx + m[1, 1] * ny + m[1, 2] * nz)
            + nz * (m[2, 0] * nx + m[2, 1] * ny + m[2, 2] * nz))


@njit(cache=True, nogil=True)
def prepare_friction(start, ca, cb, n, ra, rb, mu, inv_mass, inv_i, t1, t2, fa, fb, mass_t1,
                     mass_t2, mass_tw, radius, fmu, turns, carry):
    """Per manifold k: tangents t1, t2 (K, 3); the arms fa, fb (K, 3) from each centre of mass
    to the friction centre; the effective masses of the two tangents and of the twist; the
    twist radius ρ [m]; μ.

    ``turns`` (M,): each point's normal mode (``body_soft.FIXED`` = 0: fixed in the world).
    ``carry``: the tangents hold this step's last ones, and a manifold whose normal turns
    within the step (``body_soft.normals``) carries them along: the last t1 made normal to n
    again, t2 = n × t1. Its friction impulse is summed through the substeps in its tangents
    (``jt1``, ``jt2``); found again by ``_basis``, which jumps where |nx| crosses 1/√3, the
    sum turned in the substep its normal crossed there, by as much as the two bases differ
    (115° for a normal that turns by 0.05° across it)."""
    for k in range(t1.shape[0]):
        s0 = start[k]
        s1 = start[k + 1]
        a = ca[s0]
        b = cb[s0]
        nx, ny, nz = n[s0, 0], n[s0, 1], n[s0, 2]
        ax, ay, az, bx, by, bz = _basis(nx, ny, nz)
        if carry and turns[s0] != 0:
            d = t1[k, 0] * nx + t1[k, 1] * ny + t1[k, 2] * nz
            cx, cy, cz = t1[k, 0] - d * nx, t1[k, 1] - d * ny, t1[k, 2] - d * nz
            length = math.sqrt(cx * cx + cy * cy + cz * cz)
            if length > 0.5:  # (a normal that turned by less than 60° since the last)
                ax, ay, az = cx / length, cy / length, cz / length
                bx, by, bz = ny * az - nz * ay, nz * ax - nx * az, nx * ay - ny * ax
        t1[k, 0], t1[k, 1], t1[k, 2] = ax, ay, az
        t2[k, 0], t2[k, 1], t2[k, 2] = bx, by, bz
        inv_k = 1.0 / (s1 - s0)
        for j in range(3):
            sa = 0.0
            sb = 0.0
            for c in range(s0, s1):
                sa += ra[c, j]
                sb += rb[c, j]
            fa[k, j] = sa * inv_k
            fb[k, j] = sb * inv_k
        rho = 0.0
        for c in range(s0, s1):
            dx = ra[c, 0] - fa[k, 0]
            dy = ra[c, 1] - fa[k, 1]
            dz = ra[c, 2] - fa[k, 2]
            rho += math.sqrt(dx * dx + dy * dy + dz * dz)
        radius[k] = rho * inv_k
        fmu[k] = mu[s0]
        k1 = inv_mass[a] + arm_mass(inv_i, a, fa[k, 0], fa[k, 1], fa[k, 2], ax, ay, az)
        k2 = inv_mass[a] + arm_mass(inv_i, a, fa[k, 0], fa[k, 1], fa[k, 2], bx, by, bz)
        kt = _inv_inertia_along(inv_i, a, nx, ny, nz)
        if b >= 0:
            k1 += inv_mass[b] + arm_mass(inv_i, b, fb[k, 0], fb[k, 1], fb[k, 2], ax, ay, az)
            k2 += inv_mass[b] + arm_mass(inv_i, b, fb[k, 0], fb[k, 1], fb[k, 2], bx, by, bz)
            kt += _inv_inertia_along(inv_i, b, nx, ny, nz)
        mass_t1[k] = 1.0 / k1 if k1 > 0.0 else 0.0
        mass_t2[k] = 1.0 / k2 if k2 > 0.0 else 0.0
        mass_tw[k] = 1.0 / kt if kt > 0.0 else 0.0


@njit(cache=True, nogil=True)
def gather_friction(start, n, t1, t2, fmu, radius, mass_tw, kept, jt1, jt2, jtw):
    """The manifolds' warm start from the points' kept world vectors ``kept`` (M, 3).

    Only rows the passes will revise begin from what was kept: no tangents where μ = 0, no
    twist where the manifold has none (one point, ρ = 0). A warm start the passes never
    clamp is applied again and kept again every step: a box that came down from a face onto
    one corner kept its face's twist share and was spun up by it each step (the fracture
    demo's parts: 3.1 kJ -> 15.8 kJ in 1.2 s)."""
    for k in range(t1.shape[0]):
        sx = 0.0
        sy = 0.0
        sz = 0.0
        for c in range(start[k], start[k + 1]):
            sx += kept[c, 0]
            sy += kept[c, 1]
            sz += kept[c, 2]
        s0 = start[k]
        jt1[k] = sx * t1[k, 0] + sy * t1[k, 1] + sz * t1[k, 2]
        jt2[k] = sx * t2[k, 0] + sy * t2[k, 1] + sz * t2[k, 2]
        jtw[k] = sx * n[s0, 0] + sy * n[s0, 1] + sz * n[s0, 2]
        if fmu[k] <= 0.0:
            jt1[k] = jt2[k] = jtw[k] = 0.0
        elif radius[k] <= 0.0 or mass_tw[k] <= 0.0:
            jtw[k] = 0.0


@njit(cache=True, nogil=True)
def split_friction(start, n, t1, t2, jt1, jt2, jtw, out):
    """Each point's share of its manifold's block as a world vector, ``out`` (M, 3), to keep."""
    for k in range(t1.shape[0]):
        s0 = start[k]
        s1 = start[k + 1]
        share = 1.0 / (s1 - s0)
        for j in range(3):
            v = (jt1[k] * t1[k, j] + jt2[k] * t2[k, j] + jtw[k] * n[s0, j]) * share
            for c in range(s0, s1):
                out[c, j] = v
