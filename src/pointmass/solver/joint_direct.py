"""The exact solve of the joints' point blocks on a forest (``joint_tree``): factor once per
substep, then each velocity pass solves for the impulses that make every DIRECT joint's point
velocity Ċ meet its target at once (Baraff's block LDLᵀ of the saddle-point system, O(nodes)).

Why. Gauss–Seidel moves an impulse one joint per pass, so a hanging chain of n links needs
~n² passes to converge; at the 30-pass cap a 50-box chain was left with its joints' targets
unmet, and the drift bias then fed it until it blew up (measured: a 50-box chain at the
defaults reached 18 kJ of spurious energy in 1 s, a 20-box one 17 kJ in 5 s). Solved exactly,
each joint meets Ċ = −β·C/dt, so its gap falls by (1 − β) a step whatever the chain's length.

Geometric stiffness. The impulses are found for the arms at the start of the step, so the
torque a tense joint exerts as its body turns (the body's alignment with the pull) is
integrated explicitly: a body pulled at arm r by a force F has a mode of stiffness k ≈ F·|r|,
unstable once ω·dt = √(k/I)·dt passes 2. A 0.1 × 0.2 × 0.1 m link under the 490 N at the top of
a hanging 50-box chain has ω·dt ≈ 2.5 at 60 Hz (30 boxes: 1.97). As Tournier et al. (2015,
"Stable constrained dynamics") do, the tree solve treats that stiffness implicitly: the
body's angular block gains dt²·k, here only as much as holds ω·dt at 1 (``geometric``), so
the light loads of a ragdoll or a top get nothing and their motion is unchanged. The point
blocks it solves are not warm-started: an exact solve finds the whole impulse, and an
impulse found with the stiffened inertia, replayed through the true one, would kick the
bodies it was meant to calm.

Blocks: a body's is M = diag(m·1, I_world) (6×6); a joint's own block is 0 (3×3); the block
between joint j and a body is that body's part of the point velocity Ċ = vB + ωB×rB − vA −
ωA×rA: [−1, [rA]×] for A, [1, −[rB]×] for B (3×6).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .joint_tree import DIRECT


@njit(cache=True, nogil=True)
def _invert(m, size, out):
    """``out[:size, :size]`` = inverse of ``m[:size, :size]`` (Gauss–Jordan, partial pivots);
    False when singular."""
    work = np.zeros((6, 12))
    for i in range(size):
        for k in range(size):
            work[i, k] = m[i, k]
        work[i, size + i] = 1.0
    for col in range(size):
        best = col
        for r in range(col + 1, size):
            if abs(work[r, col]) > abs(work[best, col]):
                best = r
        if work[best, col] == 0.0:
            return False
        if best != col:
            for k in range(2 * size):
                work[col, k], work[best, k] = work[best, k], work[col, k]
        pivot = 1.0 / work[col, col]
        for k in range(2 * size):
            work[col, k] *= pivot
        for r in range(size):
            if r != col and work[r, col] != 0.0:
                f = work[r, col]
                for k in range(2 * size):
                    work[r, k] -= f * work[col, k]
    for i in range(size):
        for k in range(size):
            out[i, k] = work[i, size + k]
    return True


@njit(cache=True, nogil=True)
def _coupling(ja, ra, rb, j, body, out):
    """The 3×6 block of joint j on ``body`` into ``out`` (module docstring)."""
    for u in range(3):
        for v in range(6):
            out[u, v] = 0.0
    if body == ja[j]:
        s, rx, ry, rz = -1.0, ra[j, 0], ra[j, 1], ra[j, 2]
    else:
        s, rx, ry, rz = 1.0, rb[j, 0], rb[j, 1], rb[j, 2]
    for u in range(3):
        out[u, u] = s
    # −s·[r]× (A: s = −1 gives +[rA]×; B: −[rB]×)
    out[0, 4], out[0, 5] = s * rz, -s * ry
    out[1, 3], out[1, 5] = -s * rz, s * rx
    out[2, 3], out[2, 4] = s * ry, -s * rx


@njit(cache=True, nogil=True)
def _edge(nodes, n, ja, ra, rb, child, parent_node, out):
    """H's block (rows: the child node, columns: its parent) into ``out``; returns (rows,
    cols)."""
    if child < n:  # a body below a joint: the joint's block transposed (6×3)
        block = np.empty((3, 6))
        _coupling(ja, ra, rb, parent_node - n, child, block)
        for u in range(6):
            for v in range(3):
                out[u, v] = block[v, u]
        return 6, 3
    _coupling(ja, ra, rb, child - n, parent_node, out)
    return 3, 6


@njit(cache=True, nogil=True)
def _across(m, ux, uy, uz):
    """Largest u·M·u over the unit vectors u across the unit ``(ux, uy, uz)`` (M symmetric,
    3×3): the largest eigenvalue of P·M·P, P = 1 − ûûᵀ, whose third one is 0."""
    u = (ux, uy, uz)
    p = np.empty((3, 3))
    for a in range(3):
        for b in range(3):
            p[a, b] = (1.0 if a == b else 0.0) - u[a] * u[b]
    pm = np.zeros((3, 3))
    for a in range(3):
        for b in range(3):
            x = 0.0
            for c in range(3):
                for d in range(3):
                    x += p[a, c] * m[c, d] * p[d, b]
            pm[a, b] = x
    trace = pm[0, 0] + pm[1, 1] + pm[2, 2]
    square = 0.0
    for a in range(3):
        for b in range(3):
            square += pm[a, b] * pm[a, b]
    return 0.5 * (trace + np.sqrt(max(2.0 * square - trace * trace, 0.0)))


@njit(cache=True, nogil=True)
def geometric(ja, jb, mode, ra, rb, point, inv_i, dt, extra):
    """The inertia [kg·m²] each body's angular block gains from its joints' tension, into
    ``extra`` (N, 3, 3) (module docstring, "Geometric stiffness"), for the DIRECT joints
    (``mode`` 2): per joint end pulled outward along its arm r by the impulse t = p·r̂ > 0
    [N·s] (last step's, ``point``), g·(1 − r̂r̂ᵀ) with g = dt·t·|r|, scaled by
    max(0, 1 − 1/ρ) where ρ = Σ g·(largest u·I⁻¹_world·u across r̂) is (ω·dt)² of the
    body's alignment mode, so that a body whose mode has ω·dt ≤ 1 gains nothing and a faster
    one is held at 1. (Across the arm: a slender link pulled along its length turns against
    its large moments; measured with its smallest, the links of a double pendulum of 0.5 m
    boxes were stiffened at 12 rad/s and lost 23 % of their energy in 20 s.)"""
    extra[:] = 0.0
    load = np.zeros(extra.shape[0])
    for j in range(ja.shape[0]):
        if mode[j] < DIRECT:  # DIRECT and LOOP joints
            continue
        for side in range(2):
            i = ja[j] if side == 0 else jb[j]
            if i < 0:
                continue
            sign = -1.0 if side == 0 else 1.0
            rx, ry, rz = (ra[j, 0], ra[j, 1], ra[j, 2]) if side == 0 else \
                (rb[j, 0], rb[j, 1], rb[j, 2])
            size = np.sqrt(rx * rx + ry * ry + rz * rz)
            if size == 0.0:
                continue
            ux, uy, uz = rx / size, ry / size, rz / size
            pull = sign * (point[j, 0] * ux + point[j, 1] * uy + point[j, 2] * uz)
            if pull <= 0.0:
                continue  # compression: its stiffness does not restore
            g = dt * pull * size
            load[i] += g * _across(inv_i[i], ux, uy, uz)
            u = (ux, uy, uz)
            for a in range(3):
                for b in range(3):
                    extra[i, a, b] += g * ((1.0 if a == b else 0.0) - u[a] * u[b])
    for i in range(extra.shape[0]):
        rho = load[i]
        scale = 1.0 - 1.0 / rho if rho > 1.0 else 0.0
        for a in range(3):
            for b in range(3):
                extra[i, a, b] *= scale


@njit(cache=True, nogil=True)
def factor(nodes, parent, count, n, ja, ra, rb, inv_mass, inv_i, extra, dinv, low):
    """Factor H = L·D·Lᵀ over the ``count`` nodes in postorder: ``dinv`` (P, 6, 6) each D⁻¹,
    ``low`` (P, 6, 6) each node's D⁻¹·H(node, parent); a body's angular block is its world
    inertia plus ``extra`` (N, 3, 3). Returns False if a pivot is singular (a body without
    full inertia, joints that repeat one another)."""
    acc = np.zeros((count, 6, 6))
    block = np.empty((6, 6))
    for p in range(count):
        node = nodes[p]
        if node < n:
            inertia = np.empty((3, 3))
            if not _invert(inv_i[node], 3, inertia):
                return False
            m = 1.0 / inv_mass[node]
            for u in range(3):
                acc[p, u, u] += m
                for v in range(3):
                    acc[p, 3 + u, 3 + v] += inertia[u, v] + extra[node, u, v]
    for p in range(count):
        size = 6 if nodes[p] < n else 3
        if not _invert(acc[p], size, dinv[p]):
            return False
        q = parent[p]
        if q < 0:
            continue
        rows, cols = _edge(nodes, n, ja, ra, rb, nodes[p], nodes[q], block)
        for u in range(rows):
            for v in range(cols):
                x = 0.0
                for k in range(rows):
                    x += dinv[p, u, k] * block[k, v]
                low[p, u, v] = x
        # the parent's pivot loses H(q, p)·D⁻¹·H(p, q) = blockᵀ·low
        for u in range(cols):
            for v in range(cols):
                x = 0.0
                for k in range(rows):
                    x += block[k, u] * low[p, k, v]
                acc[q, u, v] -= x
    return True


@njit(cache=True, nogil=True)
def rate(ja, jb, ra, rb, vel, ang, j):
    """Ċ of joint j's point block now [m/s] (module docstring)."""
    a = ja[j]
    b = jb[j]
    rax, ray, raz = ra[j, 0], ra[j, 1], ra[j, 2]
    cx = -(vel[a, 0] + ang[a, 1] * raz - ang[a, 2] * ray)
    cy = -(vel[a, 1] + ang[a, 2] * rax - ang[a, 0] * raz)
    cz = -(vel[a, 2] + ang[a, 0] * ray - ang[a, 1] * rax)
    if b >= 0:
        rbx, rby, rbz = rb[j, 0], rb[j, 1], rb[j, 2]
        cx += vel[b, 0] + ang[b, 1] * rbz - ang[b, 2] * rby
        cy += vel[b, 1] + ang[b, 2] * rbx - ang[b, 0] * rbz
        cz += vel[b, 2] + ang[b, 0] * rby - ang[b, 1] * rbx
    return cx, cy, cz


@njit(cache=True, nogil=True)
def substitute(nodes, parent, count, n, dinv, low, z, y):
    """Solve H·y = z with the factors (``factor``): ``z`` (P, 6) is overwritten by the forward
    elimination, ``y`` (P, 6) gets the solution."""
    for p in range(count):  # forward: z ← L⁻¹·z
        q = parent[p]
        if q >= 0:
            rows = 6 if nodes[p] < n else 3
            cols = 6 if nodes[q] < n else 3
            for v in range(cols):
                x = 0.0
                for k in range(rows):
                    x += low[p, k, v] * z[p, k]
                z[q, v] -= x
    for p in range(count - 1, -1, -1):  # D⁻¹, then back: y = L⁻ᵀ·D⁻¹·z
        rows = 6 if nodes[p] < n else 3
        q = parent[p]
        cols = 6 if q >= 0 and nodes[q] < n else 3
        for u in range(rows):
            x = 0.0
            for k in range(rows):
                x += dinv[p, u, k] * z[p, k]
            if q >= 0:
                for k in range(cols):
                    x -= low[p, u, k] * y[q, k]
            y[p, u] = x


@njit(cache=True, nogil=True)
def apply(nodes, count, n, y, vel, ang, point):
    """Give each body node its Δv, Δω (y's rows) and each joint node its impulse −y."""
    for p in range(count):
        node = nodes[p]
        if node < n:
            for k in range(3):
                vel[node, k] += y[p, k]
                ang[node, k] += y[p, 3 + k]
        else:
            for k in range(3):
                point[node - n, k] -= y[p, k]


@njit(cache=True, nogil=True)
def solve(nodes, parent, count, n, ja, jb, ra, rb, bias, dinv, low, vel, ang, point):
    """One exact solve: the impulses that bring every DIRECT joint's Ċ to its target ``bias``
    (J, 3) [m/s] given the velocities now, applied to ``vel``, ``ang`` and added to ``point``
    (J, 3) [N·s]. Returns the largest |target − Ċ| met [m/s] (the pass's change)."""
    z = np.zeros((count, 6))
    largest = 0.0
    for p in range(count):
        node = nodes[p]
        if node >= n:
            j = node - n
            cx, cy, cz = rate(ja, jb, ra, rb, vel, ang, j)
            ex, ey, ez = bias[j, 0] - cx, bias[j, 1] - cy, bias[j, 2] - cz
            z[p, 0] = ex
            z[p, 1] = ey
            z[p, 2] = ez
            largest = max(largest, np.sqrt(ex * ex + ey * ey + ez * ez))
    y = np.zeros((count, 6))
    substitute(nodes, parent, count, n, dinv, low, z, y)
    apply(nodes, count, n, y, vel, ang, point)
    return largest
