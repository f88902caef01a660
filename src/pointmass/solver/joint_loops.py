"""The joints that close a loop of the tree solve (``joint_tree.LOOP``: a ring's last joint, a
rope bridge's second anchor), solved through the tree: each one's impulse λ is found with
the effective mass the whole tree shows it, S = J_l·H⁻¹·J_lᵀ (three solves with the tree's
factors, ``joint_direct.substitute``), and applied as a load on the tree's bodies that the
tree's joints take up (H·y = (J_lᵀλ, 0)). With one loop the pass is exact; several are swept
one after another, each exact given the others.

Why. Swept against the tree with only its own bodies' mass (Gauss–Seidel), the second anchor
of a 50-plank rope bridge never converged in 30 passes: its gap stayed at 4.4 mm after 10 s
and the bridge never came to rest.

In the soft step (``joint_soft``) a loop joint is the same rigid row, aimed at closing its gap
within the substep (Ċ = −C/h) rather than at the end pose: as Box2D's soft row, sprung with
its own two bodies' mass (K⁻¹), the bridge's second anchor, pulled by the weight of 50 planks
but sprung with one plank's mass, opened 2.7 mm (at 60 Hz); sprung with the tree's mass S⁻¹
(S 0.013 against K 0.5 1/kg) 0.085 mm; rigid, 3.5e-7 m (``joint_soft``, "Loops").

The angular rows of the tree's joints (a hinge's locks, the limits) are solved the same way in
the soft step (``row_masses``, ``row_solve``), as rigid rows: one row's mass through the tree
is 1/S with S = u·(ΔωB − ΔωA) for a unit angular impulse about its axis u, and its impulse is a
load the tree's joints take up, so each row is exact given the tree and the others
(``joint_soft``, "Angular rows").
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..rigid.joint_rows import relative_spin
from .joint_direct import _coupling, _invert, apply, rate, substitute


@njit(cache=True, nogil=True)
def _load(z, where, ja, jb, ra, rb, j, lx, ly, lz):
    """z ← (J_jᵀ·λ on each of joint j's tree bodies, 0 elsewhere)."""
    z[:] = 0.0
    block = np.empty((3, 6))
    for side in range(2):
        body = ja[j] if side == 0 else jb[j]
        if body < 0 or where[body] < 0:
            continue
        _coupling(ja, ra, rb, j, body, block)
        p = where[body]
        for v in range(6):
            z[p, v] += block[0, v] * lx + block[1, v] * ly + block[2, v] * lz


@njit(cache=True, nogil=True)
def _response(where, ja, jb, ra, rb, j, y):
    """J_j·Δv for the tree's solution y (the change of joint j's Ċ)."""
    out = np.zeros(3)
    block = np.empty((3, 6))
    for side in range(2):
        body = ja[j] if side == 0 else jb[j]
        if body < 0 or where[body] < 0:
            continue
        _coupling(ja, ra, rb, j, body, block)
        p = where[body]
        for u in range(3):
            for v in range(6):
                out[u] += block[u, v] * y[p, v]
    return out


@njit(cache=True, nogil=True)
def masses(loops, nodes, parent, count, n, where, ja, jb, ra, rb, dinv, low, sinv):
    """Each loop joint's S⁻¹ (L, 3, 3) [kg]; False if one is singular (a redundant joint)."""
    z = np.zeros((count, 6))
    y = np.zeros((count, 6))
    s = np.zeros((3, 3))
    for k in range(loops.shape[0]):
        j = loops[k]
        for c in range(3):
            _load(z, where, ja, jb, ra, rb, j, 1.0 if c == 0 else 0.0, 1.0 if c == 1 else 0.0,
                  1.0 if c == 2 else 0.0)
            substitute(nodes, parent, count, n, dinv, low, z, y)
            column = _response(where, ja, jb, ra, rb, j, y)
            for u in range(3):
                s[u, c] = column[u]
        if not _invert(s, 3, sinv[k]):
            return False
    return True


@njit(cache=True, nogil=True)
def solve(loops, nodes, parent, count, n, where, ja, jb, ra, rb, bias, dinv, low, sinv, vel,
          ang, point):
    """One pass over the loop joints (module docstring), each a rigid row: the impulse
    S⁻¹·(target − Ċ) that meets its target ``bias`` with the tree's mass, applied as a load
    the tree's joints take up (their impulses, and its own, go to ``point``). Returns the
    largest |target − Ċ| met [m/s]."""
    z = np.zeros((count, 6))
    y = np.zeros((count, 6))
    largest = 0.0
    for k in range(loops.shape[0]):
        j = loops[k]
        cx, cy, cz = rate(ja, jb, ra, rb, vel, ang, j)
        ex, ey, ez = bias[j, 0] - cx, bias[j, 1] - cy, bias[j, 2] - cz
        largest = max(largest, np.sqrt(ex * ex + ey * ey + ez * ez))
        m = sinv[k]
        lx = m[0, 0] * ex + m[0, 1] * ey + m[0, 2] * ez
        ly = m[1, 0] * ex + m[1, 1] * ey + m[1, 2] * ez
        lz = m[2, 0] * ex + m[2, 1] * ey + m[2, 2] * ez
        _load(z, where, ja, jb, ra, rb, j, lx, ly, lz)
        substitute(nodes, parent, count, n, dinv, low, z, y)
        apply(nodes, count, n, y, vel, ang, point)
        point[j, 0] += lx
        point[j, 1] += ly
        point[j, 2] += lz
    return largest


@njit(cache=True, inline="always")
def _turn_load(z, where, a, b, ux, uy, uz, x):
    """z ← the angular impulse x·u on body b and −x·u on body a (their tree rows)."""
    z[:] = 0.0
    for side in range(2):
        body = b if side == 0 else a
        if body < 0 or where[body] < 0:
            continue
        p = where[body]
        sign = x if side == 0 else -x
        z[p, 3] += sign * ux
        z[p, 4] += sign * uy
        z[p, 5] += sign * uz


@njit(cache=True, inline="always")
def _turn_rate(where, a, b, ux, uy, uz, ang):
    """u·(ωB − ωA) from per-node angular velocities ``ang`` (a tree solution's rows)."""
    out = 0.0
    for side in range(2):
        body = b if side == 0 else a
        if body < 0 or where[body] < 0:
            continue
        p = where[body]
        d = ang[p, 3] * ux + ang[p, 4] * uy + ang[p, 5] * uz
        out += d if side == 0 else -d
    return out


@njit(cache=True, nogil=True)
def row_masses(nodes, parent, count, n, where, ja, jb, mode, tree, axis, row, dinv, low, mass,
               through):
    """For every angular row (a hinge's locks, a limit) of a joint whose ``mode`` is
    ``tree`` or above (DIRECT, LOOP): its mass through the tree, 1/S with S = u·(ΔωB − ΔωA)
    for a unit angular impulse on the row (the tree's joints held), into ``mass`` (J, 3),
    and ``through`` (J, 3) set. A row the tree cannot turn (S not > 0) keeps its own."""
    z = np.zeros((count, 6))
    y = np.zeros((count, 6))
    for j in range(ja.shape[0]):
        if mode[j] < tree:
            continue
        a, b = ja[j], jb[j]
        for s in range(3):
            if row[j, s] == 0 or mass[j, s] == 0.0:
                continue
            ux, uy, uz = axis[j, s, 0], axis[j, s, 1], axis[j, s, 2]
            _turn_load(z, where, a, b, ux, uy, uz, 1.0)
            substitute(nodes, parent, count, n, dinv, low, z, y)
            k = _turn_rate(where, a, b, ux, uy, uz, y)
            if k > 0.0 and np.isfinite(k):
                mass[j, s] = 1.0 / k
                through[j, s] = True


@njit(cache=True, nogil=True)
def row_solve(nodes, parent, count, n, where, ja, jb, axis, row, mass, target, through, dinv,
              low, vel, ang, point, lam, limit):
    """One Gauss–Seidel pass over the angular rows ``through`` the tree (``row_masses``),
    each a rigid row exact given the others and the tree: the impulse that brings its Ċ to its
    target with the tree's mass (a ``limit`` row never pulls), applied as a load the tree's
    joints take up (their impulses go to ``point``). Returns the largest change of a row's Ċ
    [rad/s]."""
    z = np.zeros((count, 6))
    y = np.zeros((count, 6))
    largest = 0.0
    for j in range(ja.shape[0]):
        a, b = ja[j], jb[j]
        for s in range(3):
            if not through[j, s]:
                continue
            ux, uy, uz = axis[j, s, 0], axis[j, s, 1], axis[j, s, 2]
            rel = relative_spin(ang, a, b, ux, uy, uz)
            total = lam[j, s] + (target[j, s] - rel) * mass[j, s]
            if row[j, s] == limit and total < 0.0:
                total = 0.0
            d = total - lam[j, s]
            if d == 0.0:
                continue
            lam[j, s] = total
            largest = max(largest, abs(d) / mass[j, s])
            _turn_load(z, where, a, b, ux, uy, uz, d)
            substitute(nodes, parent, count, n, dinv, low, z, y)
            apply(nodes, count, n, y, vel, ang, point)
    return largest
