"""Joint friction (``Joint(friction=τ)``): each joint resists its two bodies' relative turning
with at most τ [N·m], as Box2D's joint friction does (a motor aimed at zero relative speed whose
torque is capped; Box2D v3's ragdoll sample gives every joint one).

Why: the joints themselves keep energy (an undamped pendulum swings for ever: issue 26 point 6
asks for ±0.5 % over 20 s), so a ragdoll whose shin comes to hang off a propped knee swings
on it for as long as one cares to watch (the ragdoll demo's seed 2: 0.12 m/s at 8 s). A real
knee has friction; this is it, and nothing else in the solve damps joints.

How: once per (sub)step, before the joints' own solve, one Gauss–Seidel pass over the joints:
the angular impulse λ = −K⁻¹·(ω_a − ω_b), K = I_a⁻¹ + I_b⁻¹ (world), that would stop their
relative turning, clamped to |λ| ≤ τ·h, applied as a couple (+λ on A, −λ on B). A couple
changes neither body's linear momentum nor the pair's angular momentum about any point, and
it only takes kinetic energy out (it is the impulse of a dissipative row, clamped). On a hinge
the relative turning off its axis is what its locks hold at zero, so the whole relative ω is
the axis' in practice; on a ball joint every direction is resisted alike (isotropic, as a
ball-and-socket's friction)."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .kernels import solve_symmetric3


@njit(cache=True, nogil=True)
def _apply(a, b, friction, inv_inertia_world, ang, awake, h):
    k = np.empty((3, 3))
    for j in range(a.shape[0]):
        limit = friction[j] * h
        if limit <= 0.0:
            continue
        ia = a[j]
        ib = b[j]
        if not awake[ia] and (ib < 0 or not awake[ib]):
            continue
        w0 = ang[ia, 0]
        w1 = ang[ia, 1]
        w2 = ang[ia, 2]
        for r in range(3):
            for c in range(3):
                k[r, c] = inv_inertia_world[ia, r, c]
        if ib >= 0:
            w0 -= ang[ib, 0]
            w1 -= ang[ib, 1]
            w2 -= ang[ib, 2]
            for r in range(3):
                for c in range(3):
                    k[r, c] += inv_inertia_world[ib, r, c]
        if w0 == 0.0 and w1 == 0.0 and w2 == 0.0:
            continue
        # λ = −K⁻¹·w (0 where K is singular: both bodies' rotation fixed, static or locked)
        lam = solve_symmetric3(k, np.array((-w0, -w1, -w2)))
        size = math.sqrt(lam[0] ** 2 + lam[1] ** 2 + lam[2] ** 2)
        if size > limit:
            lam *= limit / size
        for r in range(3):
            da = 0.0
            for c in range(3):
                da += inv_inertia_world[ia, r, c] * lam[c]
            ang[ia, r] += da
        if ib >= 0:
            for r in range(3):
                db = 0.0
                for c in range(3):
                    db += inv_inertia_world[ib, r, c] * lam[c]
                ang[ib, r] -= db


def apply(view, joints, h: float) -> None:
    """One pass of joint friction over ``h`` on ``view``'s angular velocities (module
    docstring); nothing when no joint has friction. ``view``: the bodies, or the packed view
    (bodies first, as the joints index them)."""
    if not joints:
        return
    j = joints.arrays()
    if not j.friction.any():
        return
    _apply(j.a, j.b, j.friction, view.inv_inertia_world, view.angular_velocity, view.awake, h)
