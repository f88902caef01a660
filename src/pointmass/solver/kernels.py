"""The solver's per-contact kernels, each written once; every stage and mode is built from them.

Two struct-of-arrays arguments (numba namedtuples) carry the state into each stage; a stage
unpacks them once into local arrays and passes those to these kernels (reading an array out of
a tuple inside the loop costs a reference-count update per access: measured 224 ns per contact
visit, against 6 ns with locals).

- ``Bodies``: ``vel``, ``acc`` (N, 3), ``inv_mass`` (N,), and ``disp`` (N, 3), the
  displacement each particle has received since the contacts were generated. A contact's current
  depth is its generated depth minus (disp_a - disp_b)·n: the book's per-contact patching of
  penetrations (d -= Δp_a·n, d += Δp_b·n), applied lazily, so no movement is ever stale (Cyclone
  forgets to clear its stored movement on an early return). The positions themselves move once,
  by ``disp``, when the solve ends (``Solver.solve``): no stage reads them, and writing both in
  every row cost the projection passes ~10 % (the settled 10 000-sphere pit).
- ``ContactSet``: the contacts (``a``, ``b`` (-1: scenery), ``n`` (M, 3) from b to a, ``depth0``
  [m] (< 0: a gap), ``e`` restitution, ``mu`` friction, ``bil`` bilateral: a rod, whose impulse
  may pull and whose negative depth is an error too) and per-contact solver state (``wa``,
  ``wb`` inverse masses, ``k`` = 1 / (wa + wb), ``acc_sep`` [m/s], ``target`` [m/s],
  ``impulse`` [N·s] and ``tangent`` (M, 3) [N·s], the accumulated normal and friction impulses).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np
from numba import njit

Bodies = namedtuple("Bodies", "vel acc inv_mass disp")
ContactSet = namedtuple("ContactSet",
                        "a b n depth0 e mu bil wa wb k acc_sep target impulse tangent")

#: Penetrations smaller than this [m] count as resolved (float noise after a projection).
PENETRATION_EPSILON = 1e-9
#: Separating velocities above -this [m/s] count as not closing (float noise).
VELOCITY_EPSILON = 1e-9


@njit(cache=True, inline="always")
def relative(v, ca, cb, n, c):
    """(v[a] - v[b])·n of contact c, for v a per-particle (N, 3) array; b = -1 is scenery."""
    a = ca[c]
    b = cb[c]
    if b >= 0:
        return ((v[a, 0] - v[b, 0]) * n[c, 0] + (v[a, 1] - v[b, 1]) * n[c, 1]
                + (v[a, 2] - v[b, 2]) * n[c, 2])
    return v[a, 0] * n[c, 0] + v[a, 1] * n[c, 1] + v[a, 2] * n[c, 2]


@njit(cache=True, inline="always")
def closing_within_step(vs, d, dt):
    """Closing (vs < 0), and touching now or before the step ends (a speculative gap -d
    closes only if -vs·dt > -d): otherwise the pair is left alone, nothing stops early."""
    return vs < -VELOCITY_EPSILON and d - vs * dt > 0.0


@njit(cache=True, inline="always")
def bounce_target(vs, acc_sep, e, threshold):
    """The separating velocity a closing contact (vs < 0) leaves with [m/s].

    -e·vs (e is 0 below ``threshold``), less the **resting-contact trick**: the closing speed
    that this step's acceleration alone built up (acc_sep = Δa·n·dt < 0) is not bounced back,
    so objects resting under gravity do not jitter (the cookbook, Millington §7.2.3)."""
    if -vs <= threshold:
        e = 0.0
    target = -e * vs
    if acc_sep < 0.0:
        target += e * acc_sep
        if target < 0.0:
            target = 0.0
    return target


@njit(cache=True, inline="always")
def push(vel, ca, cb, n, wa, wb, c, j):
    """Apply the normal impulse j [N·s] to contact c: a along +n, b along -n, by inverse mass.

    The hot stages (impacts, solve_velocities) write these lines out in their loops: an
    array-writing helper costs ~4× per contact visit there, even inlined (measured)."""
    a = ca[c]
    b = cb[c]
    ja = j * wa[c]
    vel[a, 0] += n[c, 0] * ja
    vel[a, 1] += n[c, 1] * ja
    vel[a, 2] += n[c, 2] * ja
    if b >= 0:
        jb = j * wb[c]
        vel[b, 0] -= n[c, 0] * jb
        vel[b, 1] -= n[c, 1] * jb
        vel[b, 2] -= n[c, 2] * jb


@njit(cache=True, inline="always")
def _move(vel, disp, i, vx, vy, vz, dt):
    """Change particle i's velocity by (vx, vy, vz) and its displacement by that × dt."""
    vel[i, 0] += vx
    vel[i, 1] += vy
    vel[i, 2] += vz
    disp[i, 0] += vx * dt
    disp[i, 1] += vy * dt
    disp[i, 2] += vz * dt


@njit(cache=True, inline="always")
def slide(vel, disp, ca, cb, wa, wb, c, dx, dy, dz, dt):
    """Apply the tangential impulse (dx, dy, dz) [N·s] to contact c (b gets the opposite), and
    move the particles by the velocity change × dt: the integrator already moved them with their
    pre-contact velocity, and projection corrects only along n, so without this a sphere held
    still on a slope would creep down by g·sinθ·dt² a step (Box2D solves, then integrates).
    The contact's ends and masses are read before any store (read after one, each is loaded
    again: the frictional ball-pit demo's passes cost 15 % more)."""
    a = ca[c]
    b = cb[c]
    w_a = wa[c]
    w_b = wb[c]
    _move(vel, disp, a, dx * w_a, dy * w_a, dz * w_a, dt)
    if b >= 0:
        _move(vel, disp, b, -dx * w_b, -dy * w_b, -dz * w_b, dt)


@njit(cache=True, inline="always")
def tangential(vel, ca, cb, n, c):
    """The relative tangential velocity v_t = v_rel - (v_rel·n)·n of contact c [m/s]."""
    a = ca[c]
    b = cb[c]
    rx = vel[a, 0]
    ry = vel[a, 1]
    rz = vel[a, 2]
    if b >= 0:
        rx -= vel[b, 0]
        ry -= vel[b, 1]
        rz -= vel[b, 2]
    vn = rx * n[c, 0] + ry * n[c, 1] + rz * n[c, 2]
    return rx - vn * n[c, 0], ry - vn * n[c, 1], rz - vn * n[c, 2]


@njit(cache=True, inline="always")
def clamp_length(x, y, z, limit):
    """(x, y, z) scaled into the ball of radius ``limit`` ≥ 0 (unchanged if inside).

    Without a branch (the scale computed always and kept where the ball is exceeded, so where
    it is, t2 > 0): in a sliding pile whether a row's friction is at its limit flips from row
    to row, and the processor guessed wrong (see ``coulomb_disc``)."""
    t2 = x ** 2 + y ** 2 + z ** 2
    over = t2 > limit * limit
    s = limit / math.sqrt(max(t2, 1e-300))
    return (x * s if over else x), (y * s if over else y), (z * s if over else z)


@njit(cache=True, inline="always")
def clamp_disc(tangent, c, limit):
    """Scale ``tangent[c]`` into the disc of radius ``limit`` ≥ 0 (the Coulomb cone)."""
    tangent[c, 0], tangent[c, 1], tangent[c, 2] = clamp_length(tangent[c, 0], tangent[c, 1],
                                                               tangent[c, 2], limit)


@njit(cache=True, inline="always")
def friction_once(vel, disp, ca, cb, n, wa, wb, k, mu, c, j, dt):
    """Coulomb friction for one impact of normal impulse j: stop the tangential velocity, with
    at most μ·j (the book's resolver and the impact stage: no accumulation)."""
    if mu[c] <= 0.0 or j <= 0.0:
        return
    tx, ty, tz = tangential(vel, ca, cb, n, c)
    speed = math.sqrt(tx * tx + ty * ty + tz * tz)
    if speed > 0.0:
        jt = min(speed * k[c], mu[c] * j)
        s = -jt / speed
        slide(vel, disp, ca, cb, wa, wb, c, tx * s, ty * s, tz * s, dt)


@njit(cache=True, inline="always")
def coulomb_disc(rx, ry, rz, nx, ny, nz, ox, oy, oz, k, limit):
    """One sequential-impulse friction step (Box2D-lite's, with a disc), on scalars: the
    accumulated friction impulse (ox, oy, oz) [N·s] less k × the relative tangential velocity
    of (rx, ry, rz) [m/s] about the normal n (aiming to stop it), scaled into the disc of radius
    ``limit`` (μ × the accumulated normal impulse). Returns the new accumulated impulse; the
    caller applies its difference to the old (``sweeps.velocity_rows``, which keeps the row's
    velocities in locals: 61-63 -> 40-42 ns a frictional row with the clamp branch-free)."""
    vn = rx * nx + ry * ny + rz * nz
    return clamp_length(ox - (rx - vn * nx) * k, oy - (ry - vn * ny) * k,
                        oz - (rz - vn * nz) * k, limit)


@njit(cache=True, inline="always")
def project(disp, ca, cb, n, depth0, bil, wa, wb, k, c):
    """Remove contact c's penetration: move each particle along n in proportion to its inverse
    mass (positions only; velocities unchanged); a bilateral contact that is too short (d < 0)
    is pushed apart the same way. Returns the depth removed [m] (its size). (The book's
    worst-first loop calls it; ``stages.project_positions`` writes it out, for speed.)"""
    d = depth0[c] - relative(disp, ca, cb, n, c)
    if k[c] == 0.0 or (d <= PENETRATION_EPSILON and not (bil[c] and d < -PENETRATION_EPSILON)):
        return 0.0
    share = d * k[c]
    a = ca[c]
    b = cb[c]
    for i in range(3):
        disp[a, i] += n[c, i] * share * wa[c]
        if b >= 0:
            disp[b, i] -= n[c, i] * share * wb[c]
    return abs(d)


@njit(cache=True, inline="always")
def solve_symmetric3(a, b):
    """x with a·x = b for a symmetric 3×3 ``a`` (0 where it is singular)."""
    c00 = a[1, 1] * a[2, 2] - a[1, 2] * a[2, 1]
    c01 = a[1, 2] * a[2, 0] - a[1, 0] * a[2, 2]
    c02 = a[1, 0] * a[2, 1] - a[1, 1] * a[2, 0]
    det = a[0, 0] * c00 + a[0, 1] * c01 + a[0, 2] * c02
    out = np.zeros(3)
    scale = a[0, 0] + a[1, 1] + a[2, 2]
    if not abs(det) > 1e-14 * scale * scale * scale:
        return out
    c10 = a[0, 2] * a[2, 1] - a[0, 1] * a[2, 2]
    c11 = a[0, 0] * a[2, 2] - a[0, 2] * a[2, 0]
    c12 = a[0, 1] * a[2, 0] - a[0, 0] * a[2, 1]
    c20 = a[0, 1] * a[1, 2] - a[0, 2] * a[1, 1]
    c21 = a[0, 2] * a[1, 0] - a[0, 0] * a[1, 2]
    c22 = a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
    out[0] = (c00 * b[0] + c10 * b[1] + c20 * b[2]) / det
    out[1] = (c01 * b[0] + c11 * b[1] + c21 * b[2]) / det
    out[2] = (c02 * b[0] + c12 * b[1] + c22 * b[2]) / det
    return out
