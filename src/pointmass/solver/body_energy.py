"""The body stage's energy guard: contacts and joints never add kinetic energy.

A contact with e ≤ 1, friction and a joint can only take kinetic energy out of the bodies
they touch, so the velocity half of the body stage (``body_solver.solve_velocities``) is
measured: the kinetic energy of the bodies it solved after the passes against before them
(after this substep's kick, so whatever the forces gave is allowed). A solve that gained more
than ``SLACK`` of it is redone by the method below, which cannot gain any.

Why the fast solve can gain energy. Its targets are not all ≤ 0: a bounce aims at −e·vs taken
from the velocity *before* the passes, which other rows change. A 12.5 g sphere between two
7 t spheres, frictionless, e = 1 (issue 31): the heavy sphere behind it may let it close by its
gap, 41 m/s, while the one ahead wants it to leave at 147 m/s; the two rows push the heavy
spheres apart every pass: 139 J became 1.99e7 J in one step. A spinning box landing on two
points with μ = 1: friction changes the points' normal velocities after their bounce targets
were set, 141 J → 355 J. A joint's drift bias Ċ = −β·C/dt adds energy by design, and a warm
start can (a loaded row whose direction turned), and the exact tree solve adds geometric
stiffness to the inertia it solves with (it is not a projection in the bodies' mass metric).

The redo (Moreau's inelastic impact plus Poisson's restitution):

1. From the velocities before the passes, cold (no warm start), with every target clipped to
   ≤ 0 (no bounce, no joint bias; a speculative gap may still close by its gap, an open limit
   by its opening), joints on the plain Gauss–Seidel rows. Projected Gauss–Seidel from λ = 0
   then decreases f(λ) = KE(λ) − KE₀ − λ·target at every row update (each is an exact
   minimisation over that row or 3-row block, within its bounds), so KE − KE₀ ≤ λ·target ≤ 0
   whatever the mass ratios, arms and number of passes. Friction's bound μ·λn moves as λn
   does, which can break this: if the passes still gained, they are run once more without
   friction (normal rows and joints alone: a convex problem, so it holds).
2. Restitution: each point that would have bounced gets e·λ more along its normal (Poisson's
   hypothesis: the restitution impulse is e times the compression impulse). For one contact
   that is exactly Newton's −e·vs; for several it keeps energy only when they all have the same
   e, so the added impulse is scaled by the largest s ∈ [0, 1] that keeps the kinetic energy at
   most where it was (it is a quadratic in s, measured at s = ½ and 1).

The position half then removes what is left of the overlaps and joint gaps by moving positions
only (``body_stages.project_positions``, ``joint_project``), keeping each body's angular
velocity in its own frame (``keep_spin``), so it changes no kinetic energy either.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..rigid.bodies import _kinetic_energy
from ..rigid.joint_rows import EQUAL
from ..rigid.scalar import qrot, qrot_inv
from . import body_stages as st
from . import joint_tree as jt

#: A solve may gain at most this fraction of the kinetic energy (round-off) before it is
#: redone: well below the 1e-9 a step may gain in the fuzz suite (tests/physics/
#: test_fuzz_rigid.py), well above the ~1e-15 of summing the energy.
SLACK = 1e-11


def kinetic_energy(bodies) -> float:
    """Kinetic energy [J] of ``bodies`` (a ``Bodies`` or the packed view with particles)."""
    return float(_kinetic_energy(bodies.velocity, bodies.angular_velocity, bodies.orientation,
                                 bodies.inv_mass, bodies.inv_inertia))


def gained(before: float, after: float) -> bool:
    """Whether ``after`` exceeds ``before`` by more than the round-off allowed (or is not a
    number: a solve that overflowed is redone too)."""
    return not after <= before * (1.0 + SLACK) + 1e-300


def redo(solver, b, c, rows, joints, v0, w0, energy0: float, max_passes: int) -> None:
    """Redo the velocity passes of ``rows`` the way that adds no energy (module docstring).
    ``solver`` is ``body_solver``'s module (its pass loops), ``v0``, ``w0`` the velocities
    before the passes, ``energy0`` their kinetic energy."""
    bounce = rows.target > 0.0
    rows.target[bounce] = 0.0
    if rows.joints is not None:
        r = rows.joints
        r.bias[:] = 0.0
        r.predict = False
        r.target[r.row == EQUAL] = 0.0  # an equality row's λ has either sign
        np.minimum(r.target, 0.0, out=r.target)  # a limit's never pulls: −C/dt may stay
        r.mode[r.mode >= jt.DIRECT] = jt.ITERATIVE
        r.tree = ()
    for friction in (True, False):
        b.velocity[:] = v0
        b.angular_velocity[:] = w0
        rows.impulse[:] = 0.0
        rows.jt1[:] = 0.0
        rows.jt2[:] = 0.0
        rows.jtw[:] = 0.0
        if not friction:
            rows.mu[:] = 0.0
        if rows.joints is not None:
            rows.joints.lam[:] = 0.0
            joints.point[:] = 0.0
            rows.velocity_passes += solver._interleaved(b, c, rows, joints, max_passes)
        else:
            rows.velocity_passes += solver._passes(b, c, rows, max_passes)
        if not gained(energy0, kinetic_energy(b)):
            break
    else:  # round-off on a huge energy: nothing at all is the one answer surely safe
        b.velocity[:] = v0
        b.angular_velocity[:] = w0
        return
    if c.count and bounce.any():
        _restitution(b, c, rows, bounce, energy0)


def _restitution(b, c, rows, bounce: np.ndarray, energy0: float) -> None:
    """Poisson's restitution impulse e·λ at the points that bounce, scaled down as far as the
    energy needs (module docstring, 2)."""
    extra = np.where(bounce, c.restitution * rows.impulse, 0.0)
    if not extra.any():
        return
    v1 = b.velocity.copy()
    w1 = b.angular_velocity.copy()
    k0 = kinetic_energy(b)

    def energy_at(s: float) -> float:
        b.velocity[:] = v1
        b.angular_velocity[:] = w1
        _apply(b, c, rows, s * extra)
        return kinetic_energy(b)

    k1 = energy_at(1.0)
    if gained(energy0, k1):
        kh = energy_at(0.5)
        quad = 2.0 * (k1 - 2.0 * kh + k0)  # K(s) = k0 + lin·s + quad·s²
        lin = k1 - k0 - quad
        s = _largest_within(k0, lin, quad, energy0)
        k1 = energy_at(s)
        tries = 0  # round-off at the root: step back thrice, then give up the bounce
        while s > 0.0 and gained(energy0, k1):
            tries += 1
            s = s * 0.99 if tries < 4 else 0.0
            k1 = energy_at(s)
        extra = s * extra
    rows.impulse += extra


def _largest_within(k0: float, lin: float, quad: float, limit: float) -> float:
    """The largest s in [0, 1] with k0 + lin·s + quad·s² ≤ limit (k0 ≤ limit)."""
    room = limit - k0
    if quad > 0.0:
        root = (-lin + math.sqrt(max(lin * lin + 4.0 * quad * room, 0.0))) / (2.0 * quad)
    elif lin > 0.0:
        root = room / lin if quad == 0.0 else 1.0
    else:
        return 1.0
    return min(max(root * (1.0 - 1e-9), 0.0), 1.0)


def _apply(b, c, rows, impulse: np.ndarray) -> None:
    """Apply a normal impulse per point (nothing else) to the bodies' velocities."""
    zero = np.zeros(rows.t1.shape[0])
    st.warm_start(rows.start, c.a, c.b, c.normal, c.r_a, c.r_b, rows.fa, rows.fb, rows.t1,
                  rows.t2, b.inv_mass, b.inv_inertia_world, b.velocity, b.angular_velocity,
                  impulse, zero, zero, zero)


@njit(cache=True, nogil=True)
def keep_spin(before, after, ang):
    """Turn each body's world angular velocity by the rotation from orientation ``before`` to
    ``after`` (N, 4): a projection that turned a body leaves its spin in the body's own frame
    unchanged, so ½ω·Iω stays what it was (turned with the body, world ω would meet a
    different world inertia)."""
    for i in range(ang.shape[0]):
        if before[i, 0] == after[i, 0] and before[i, 1] == after[i, 1] \
                and before[i, 2] == after[i, 2] and before[i, 3] == after[i, 3]:
            continue
        bx, by, bz = qrot_inv(before[i, 0], before[i, 1], before[i, 2], before[i, 3],
                              ang[i, 0], ang[i, 1], ang[i, 2])
        ang[i, 0], ang[i, 1], ang[i, 2] = qrot(after[i, 0], after[i, 1], after[i, 2],
                                               after[i, 3], bx, by, bz)

