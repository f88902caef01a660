"""A direct solve for small, badly conditioned contact sets (heavy loads on light links).

Gauss–Seidel converges at a rate set by mass ratios: a 1 kg particle on a rod carrying a
1000 kg load on a cable reduces its error by a factor 1 - 1/1000 per pass, so no affordable
number of passes holds the chain (measured: the rod stretched 35 % at dt = 1/32). When the passes
end without converging and the set is small, the solver instead solves the linear
complementarity problem exactly:

    find λ ≥ 0 with w = A·λ + q ≥ 0 and λ·w = 0,    A = J·M⁻¹·Jᵀ,

where J holds each contact's normal (a row per contact, +n on a, −n on b) and M⁻¹ the inverse
mass of each particle (a 3×3 block per particle: w·I, or the inverse of the *geometric
stiffness* metric the re-measured projection uses, ``remeasure.py``).
For velocities q = (J·v − target) − A·λ₀ (λ₀: the impulses so far, λ the final ones); for
positions q = −depth (λ: the mass-weighted pushes that remove every penetration, to first order).
The solution minimises the same convex energy that Gauss–Seidel descends, so it adds no kinetic
energy either. The active-set method below is exact for the small sets it is used on (links
and a few contacts); Gauss–Seidel passes follow, for friction and the non-linear remainder.

Everything here is plain loops compiled with numba, in a fixed order, with no BLAS or LAPACK
call: numpy's matrix products and ``linalg.solve`` go through OpenBLAS, whose work split may
depend on its thread count (a ball pit was reported to differ by 3e-16 after 55 frames between
the default BLAS threads and one, issue 28; not reproduced on the 2-core machine here), so the
bits now cannot depend on it. A (m × m) is built from the rows' incidence (each row touches at
most two particles), not as a dense J·M⁻¹·Jᵀ.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: Contact sets up to this size get the direct solve when Gauss–Seidel has not converged.
DIRECT_MAX_CONTACTS = 384
#: Regularisation of A (relative to its largest diagonal): an over-constrained truss makes A
#: singular; this keeps the solve well defined without changing the answer beyond float noise.
_REGULARISE = 1e-12
#: Cap on the active-set changes of one LCP solve (each is one factorisation).
_MAX_ACTIVE_SET_CHANGES = 100


@njit(cache=True, nogil=True)
def columns(ca, cb, count):
    """(col (count,): each particle's column or -1, the particles of the columns in order of
    first appearance, a then b row by row)."""
    col = np.full(count, -1, np.int64)
    parts = np.empty(2 * ca.shape[0], np.int64)
    k = 0
    for c in range(ca.shape[0]):
        for p in (ca[c], cb[c]):
            if p >= 0 and col[p] < 0:
                col[p] = k
                parts[k] = p
                k += 1
    return col, parts[:k]


@njit(cache=True, nogil=True)
def diagonal_metric(parts, inv_mass):
    """The inverse-mass blocks w·I of the columns' particles, (K, 3, 3)."""
    out = np.zeros((parts.shape[0], 3, 3))
    for k in range(parts.shape[0]):
        w = inv_mass[parts[k]]
        for i in range(3):
            out[k, i, i] = w
    return out


@njit(cache=True, nogil=True)
def _matrix(ca, cb, n, col, metric):
    """A = J·M⁻¹·Jᵀ (m × m), from the rows that share a particle: row r's ends (a: +n, b: −n),
    A[r, s] = Σ over shared particles p of ±n_r·M⁻¹_p·n_s."""
    m = ca.shape[0]
    k = metric.shape[0]
    # The rows incident on each column, by counting sort (in row order: fixed sums).
    count = np.zeros(k + 1, np.int64)
    for c in range(m):
        count[col[ca[c]] + 1] += 1
        if cb[c] >= 0:
            count[col[cb[c]] + 1] += 1
    for i in range(k):
        count[i + 1] += count[i]
    rows = np.empty(count[k], np.int64)
    signs = np.empty(count[k])
    fill = count[:k].copy()
    for c in range(m):
        p = col[ca[c]]
        rows[fill[p]] = c
        signs[fill[p]] = 1.0
        fill[p] += 1
        if cb[c] >= 0:
            p = col[cb[c]]
            rows[fill[p]] = c
            signs[fill[p]] = -1.0
            fill[p] += 1
    a_mat = np.zeros((m, m))
    for p in range(k):
        g = metric[p]
        for i in range(count[p], count[p + 1]):
            r = rows[i]
            # M⁻¹_p · n_r, then its dot with every row at p
            gx = g[0, 0] * n[r, 0] + g[0, 1] * n[r, 1] + g[0, 2] * n[r, 2]
            gy = g[1, 0] * n[r, 0] + g[1, 1] * n[r, 1] + g[1, 2] * n[r, 2]
            gz = g[2, 0] * n[r, 0] + g[2, 1] * n[r, 1] + g[2, 2] * n[r, 2]
            for j in range(count[p], count[p + 1]):
                s = rows[j]
                a_mat[r, s] += signs[i] * signs[j] * (gx * n[s, 0] + gy * n[s, 1]
                                                       + gz * n[s, 2])
    return a_mat


@njit(cache=True, nogil=True)
def _apply(ca, cb, n, col, parts, metric, lam, out):
    """out[p] += M⁻¹_p · Jᵀλ for every particle p of the rows (out is (N, 3), by particle)."""
    force = np.zeros((parts.shape[0], 3))
    for c in range(ca.shape[0]):
        p = col[ca[c]]
        for i in range(3):
            force[p, i] += n[c, i] * lam[c]
        if cb[c] >= 0:
            p = col[cb[c]]
            for i in range(3):
                force[p, i] -= n[c, i] * lam[c]
    for k in range(parts.shape[0]):
        g = metric[k]
        p = parts[k]
        for i in range(3):
            out[p, i] += g[i, 0] * force[k, 0] + g[i, 1] * force[k, 1] + g[i, 2] * force[k, 2]


@njit(cache=True, nogil=True)
def _solve_active(a_reg, q, idx, out):
    """out[idx] = the solution of A[idx, idx]·x = −q[idx] (A symmetric positive definite), by
    Cholesky; returns False if the factorisation broke down (not positive)."""
    k = idx.shape[0]
    low = np.zeros((k, k))
    for i in range(k):
        for j in range(i + 1):
            s = a_reg[idx[i], idx[j]]
            for t in range(j):
                s -= low[i, t] * low[j, t]
            if i == j:
                if s <= 0.0:
                    return False
                low[i, i] = np.sqrt(s)
            else:
                low[i, j] = s / low[j, j]
    y = np.empty(k)
    for i in range(k):
        s = -q[idx[i]]
        for t in range(i):
            s -= low[i, t] * y[t]
        y[i] = s / low[i, i]
    for i in range(k - 1, -1, -1):
        s = y[i]
        for t in range(i + 1, k):
            s -= low[t, i] * y[t]
        y[i] = s / low[i, i]
    for i in range(k):
        out[idx[i]] = y[i]
    return True


@njit(cache=True, nogil=True)
def solve_lcp(a_mat, q, start, free):
    """λ with w = A·λ + q, λ ≥ 0, w ≥ 0, λ·w = 0 for the unilateral rows and w = 0 for the
    ``free`` (bilateral) ones, by an active-set method from the guess ``start`` (the contacts
    thought to push). Returns the best λ found."""
    m = q.shape[0]
    scale = 1e-300
    qmax = 0.0
    for i in range(m):
        scale = max(scale, abs(a_mat[i, i]))
        qmax = max(qmax, abs(q[i]))
    a_reg = a_mat.copy()
    for i in range(m):
        a_reg[i, i] += _REGULARISE * scale
    tol = 1e-12 * (1.0 + qmax)
    # A row whose ends are both immovable (A[i, i] = 0) can do nothing: it stays out (solving
    # for it would divide by the regularisation alone and throw inf into the products).
    movable = np.empty(m, np.bool_)
    for i in range(m):
        movable[i] = a_mat[i, i] > _REGULARISE * scale
    free = free & movable
    active = (start | free) & movable
    lam = np.zeros(m)
    for _ in range(_MAX_ACTIVE_SET_CHANGES):
        lam[:] = 0.0
        idx = np.flatnonzero(active)
        if idx.shape[0]:
            if not _solve_active(a_reg, q, idx, lam):
                lam[:] = 0.0
                break
            worst = -1
            for i in idx:  # a contact that would pull: let the one pulling most go
                if not free[i] and lam[i] < -tol and (worst < 0 or lam[i] < lam[worst]):
                    worst = i
            if worst >= 0:
                active[worst] = False
                continue
        worst = -1
        worst_w = -tol
        for i in range(m):  # the most violated contact left out joins
            if active[i] or not movable[i]:
                continue
            w = q[i]
            for j in idx:
                w += a_mat[i, j] * lam[j]
            if w < worst_w:
                worst_w = w
                worst = i
        if worst < 0:
            break
        active[worst] = True
    for i in range(m):
        if not free[i] and lam[i] < 0.0:
            lam[i] = 0.0
    return lam


@njit(cache=True, nogil=True)
def _velocities(ca, cb, n, bil, target, impulse, vel, inv_mass):
    col, parts = columns(ca, cb, inv_mass.shape[0])
    metric = diagonal_metric(parts, inv_mass)
    a_mat = _matrix(ca, cb, n, col, metric)
    m = ca.shape[0]
    q = np.empty(m)
    start = np.empty(m, np.bool_)
    for c in range(m):
        a = ca[c]
        b = cb[c]
        vs = 0.0
        for i in range(3):
            vs += (vel[a, i] - (vel[b, i] if b >= 0 else 0.0)) * n[c, i]
        s = vs - target[c]
        start[c] = impulse[c] > 0.0 or s < 0.0
        for j in range(m):
            s -= a_mat[c, j] * impulse[j]
        q[c] = s
    lam = solve_lcp(a_mat, q, start, bil)
    change = lam - impulse
    _apply(ca, cb, n, col, parts, metric, change, vel)
    impulse[:] = lam


def solve_velocities(bod, con) -> None:
    """Replace the accumulated normal impulses by the exact ones and apply the difference."""
    _velocities(con.a, con.b, con.n, con.bil, con.target, con.impulse, bod.vel, bod.inv_mass)


@njit(cache=True, nogil=True)
def project_metric(ca, cb, n, bil, depths, col, parts, metric, disp):
    """Remove every penetration at once (to first order), each particle moved by its block of
    ``metric`` (M⁻¹, or the inverse of a stiffer metric). Returns the pushes μ."""
    a_mat = _matrix(ca, cb, n, col, metric)
    lam = solve_lcp(a_mat, -depths, depths > 0.0, bil)
    _apply(ca, cb, n, col, parts, metric, lam, disp)
    return lam


def project_positions(bod, con, depths: np.ndarray) -> None:
    """Remove every penetration at once (to first order), by inverse mass."""
    col, parts = columns(con.a, con.b, bod.inv_mass.shape[0])
    project_metric(con.a, con.b, con.n, con.bil, depths, col, parts,
                   diagonal_metric(parts, bod.inv_mass), bod.disp)
