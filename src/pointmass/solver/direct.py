"""A direct solve for small, badly conditioned contact sets (heavy loads on light links).

Gauss–Seidel converges at a rate set by mass ratios: a 1 kg particle on a rod carrying a
1000 kg load on a cable reduces its error by a factor 1 - 1/1000 per pass, so no affordable
number of passes holds the chain (measured: the rod stretched 35 % at dt = 1/32). When the passes
end without converging and the set is small, the solver instead solves the linear
complementarity problem exactly:

    find λ ≥ 0 with w = A·λ + q ≥ 0 and λ·w = 0,    A = J·W·Jᵀ,

where J holds each contact's normal (a row per contact, +n on a, −n on b), W the inverse masses.
For velocities q = (J·v − target) − A·λ₀ (λ₀: the impulses so far, λ the final ones); for
positions q = −depth (λ: the mass-weighted pushes that remove every penetration, to first order).
The solution minimises the same convex energy that Gauss–Seidel descends, so it adds no kinetic
energy either. The active-set method below is exact for the small sets it is used on (links
and a few contacts); Gauss–Seidel passes follow, for friction and the non-linear remainder.
"""

from __future__ import annotations

import numpy as np

#: Contact sets up to this size get the direct solve when Gauss–Seidel has not converged.
DIRECT_MAX_CONTACTS = 384
#: Regularisation of A (relative to its largest diagonal): an over-constrained truss makes A
#: singular; this keeps the solve well defined without changing the answer beyond float noise.
_REGULARISE = 1e-12


def _system(con, inv_mass: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(J (m, 3K), W (3K,), the particles of the K columns)."""
    a = np.asarray(con.a)
    b = np.asarray(con.b)
    ends = np.concatenate([a, b[b >= 0]])
    particles, cols = np.unique(ends, return_inverse=True)
    col_a = cols[: a.shape[0]]
    col_b = np.full(b.shape[0], -1)
    col_b[b >= 0] = cols[a.shape[0]:]
    m = a.shape[0]
    jac = np.zeros((m, 3 * particles.shape[0]))
    rows = np.arange(m)
    for k in range(3):
        jac[rows, 3 * col_a + k] = con.n[:, k]
        has_b = col_b >= 0
        jac[rows[has_b], 3 * col_b[has_b] + k] = -con.n[has_b, k]
    w = np.repeat(inv_mass[particles], 3)
    return jac, w, particles


def solve_lcp(a_mat: np.ndarray, q: np.ndarray, start: np.ndarray, free: np.ndarray, *,
              max_iterations: int = 100) -> np.ndarray:
    """λ with w = A·λ + q, λ ≥ 0, w ≥ 0, λ·w = 0 for the unilateral rows and w = 0 for the
    ``free`` (bilateral) ones, by an active-set method from the guess ``start`` (the contacts
    thought to push). Returns the best λ found."""
    m = q.shape[0]
    scale = max(float(np.abs(np.diag(a_mat)).max()), 1e-300)
    a_reg = a_mat + _REGULARISE * scale * np.eye(m)
    tol = 1e-12 * (1.0 + float(np.abs(q).max()))
    active = start | free
    lam = np.zeros(m)
    for _ in range(max_iterations):
        lam[:] = 0.0
        idx = np.flatnonzero(active)
        if idx.size:
            lam[idx] = np.linalg.solve(a_reg[np.ix_(idx, idx)], -q[idx])
            negative = (lam[idx] < -tol) & ~free[idx]
            if negative.any():  # a contact that would pull: let it go
                worst = np.flatnonzero(negative)[np.argmin(lam[idx][negative])]
                active[idx[worst]] = False
                continue
        w = a_mat @ lam + q
        violated = (~active) & (w < -tol)
        if not violated.any():
            break
        candidates = np.flatnonzero(violated)
        active[candidates[np.argmin(w[candidates])]] = True  # the most violated joins
    return np.where(free, lam, np.maximum(lam, 0.0))


def solve_velocities(bod, con) -> None:
    """Replace the accumulated normal impulses by the exact ones and apply the difference."""
    jac, w, particles = _system(con, bod.inv_mass)
    v = bod.vel[particles].reshape(-1)
    a_mat = (jac * w) @ jac.T
    lam0 = np.asarray(con.impulse)
    q = jac @ v - np.asarray(con.target) - a_mat @ lam0
    free = np.asarray(con.bil)
    lam = solve_lcp(a_mat, q, (lam0 > 0) | (q + a_mat @ lam0 < 0), free)
    dv = (w * (jac.T @ (lam - lam0))).reshape(-1, 3)
    bod.vel[particles] += dv
    con.impulse[:] = lam


def project_positions(bod, con, depths: np.ndarray) -> None:
    """Remove every penetration at once (to first order), by inverse mass."""
    jac, w, particles = _system(con, bod.inv_mass)
    a_mat = (jac * w) @ jac.T
    mu = solve_lcp(a_mat, -depths, depths > 0, np.asarray(con.bil))
    dx = (w * (jac.T @ mu)).reshape(-1, 3)
    bod.disp[particles] += dx
