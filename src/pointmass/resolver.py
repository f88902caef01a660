"""The contact resolver: Millington's iterative algorithm, compiled with numba.

For one contact (a, b, normal n from b to a, penetration d, restitution e):

1. *Velocity.* The separating velocity is vs = (v_a - v_b)·n. If vs < 0 they are closing; the
   target is -e·vs. The **resting-contact trick**: the part of the closing speed that this step's
   acceleration alone produced, ((acc_a - acc_b)·n)·dt, is not bounced back, so objects resting
   under gravity do not jitter. An impulse along n, shared by inverse mass, reaches the target.
2. *Interpenetration.* Each particle moves along n in proportion to its inverse mass until the
   overlap is gone (a projection: positions change, velocities do not).

**Worst-first** (the book's loop): each iteration resolves the single contact with the most
negative separating velocity among those closing or penetrating, up to ``iterations`` (default
2 × contacts), and stops early when nothing qualifies. **Sweep** resolves every contact in order,
pass after pass (Gauss–Seidel), which is linear per pass where worst-first is quadratic.

After every single resolution, the penetration of every contact that shares a moved particle
must be updated. We keep, per particle, the displacement it has received since the contacts were
generated; a contact's current penetration is its generated penetration minus
(disp_a - disp_b)·n. That is exactly the book's per-contact patching (d -= Δp_a·n, d += Δp_b·n),
applied lazily, so no movement is ever stale (Cyclone's resolver forgets to clear its stored
movement on an early return and applies the previous contact's move instead).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .contacts import ContactBuffer
from .particles import Particles

RESOLVER_MODES = ("worst-first", "sweep")

#: Penetrations smaller than this [m] count as resolved (float noise after a projection).
PENETRATION_EPSILON = 1e-9
#: Separating velocities above -this [m/s] count as not closing (float noise).
VELOCITY_EPSILON = 1e-9
#: Default number of sweep passes when ``iterations`` is None.
DEFAULT_SWEEP_PASSES = 10


@njit(cache=True, inline="always")
def _dot_rel(v, a, b, n, c):
    """(v[a] - v[b])·n[c], with b = -1 meaning a static body."""
    if b >= 0:
        return ((v[a, 0] - v[b, 0]) * n[c, 0] + (v[a, 1] - v[b, 1]) * n[c, 1]
                + (v[a, 2] - v[b, 2]) * n[c, 2])
    return v[a, 0] * n[c, 0] + v[a, 1] * n[c, 1] + v[a, 2] * n[c, 2]


@njit(cache=True)
def _resolve_one(c, pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, disp, dt, threshold):
    """Resolve contact ``c``: its velocity, then its interpenetration. Returns True if it moved
    or changed anything."""
    a = ca[c]
    b = cb[c]
    wa = inv_mass[a]
    wb = inv_mass[b] if b >= 0 else 0.0
    total = wa + wb
    if total <= 0.0:
        return False  # two immovable particles: nothing we do here matters
    changed = False

    # --- velocity --------------------------------------------------------------------------
    vs = _dot_rel(vel, a, b, normal, c)
    if vs < -VELOCITY_EPSILON:
        e = rest[c] if -vs > threshold else 0.0
        target = -e * vs
        # Resting-contact trick: do not bounce the closing speed built up by this step's
        # acceleration alone.
        acc_sep = _dot_rel(acc, a, b, normal, c) * dt
        if acc_sep < 0.0:
            target += e * acc_sep
            if target < 0.0:
                target = 0.0
        impulse = (target - vs) / total
        for k in range(3):
            vel[a, k] += normal[c, k] * impulse * wa
            if b >= 0:
                vel[b, k] -= normal[c, k] * impulse * wb
        changed = True

    # --- interpenetration --------------------------------------------------------------------
    depth = pen0[c] - _dot_rel(disp, a, b, normal, c)
    if depth > PENETRATION_EPSILON:
        share = depth / total
        for k in range(3):
            move_a = normal[c, k] * share * wa
            pos[a, k] += move_a
            disp[a, k] += move_a
            if b >= 0:
                move_b = -normal[c, k] * share * wb
                pos[b, k] += move_b
                disp[b, k] += move_b
        changed = True
    return changed


@njit(cache=True)
def _worst_first(pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, disp, dt, threshold,
                 iterations):
    m = ca.shape[0]
    used = 0
    while used < iterations:
        worst = -1
        worst_vs = np.inf
        for c in range(m):
            vs = _dot_rel(vel, ca[c], cb[c], normal, c)
            if vs < worst_vs:
                depth = pen0[c] - _dot_rel(disp, ca[c], cb[c], normal, c)
                if vs < -VELOCITY_EPSILON or depth > PENETRATION_EPSILON:
                    worst_vs = vs
                    worst = c
        if worst < 0:
            break  # nothing closing or penetrating: done early
        _resolve_one(worst, pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, disp, dt,
                     threshold)
        used += 1
    return used


@njit(cache=True)
def _sweep(pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, disp, dt, threshold, passes):
    m = ca.shape[0]
    used = 0
    for _ in range(passes):
        any_change = False
        for c in range(m):
            if _resolve_one(c, pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, disp, dt,
                            threshold):
                used += 1
                any_change = True
        if not any_change:
            break
    return used


@njit(cache=True)
def _current_penetration(ca, cb, normal, pen0, disp, out):
    for c in range(ca.shape[0]):
        out[c] = pen0[c] - _dot_rel(disp, ca[c], cb[c], normal, c)


def resolve_contacts(particles: Particles, contacts: ContactBuffer, dt: float, *,
                     mode: str = "worst-first", iterations: int | None = None,
                     restitution_threshold: float = 0.0) -> int:
    """Resolve ``contacts`` in place (velocities and positions of ``particles``).

    Args:
        mode: "worst-first" or "sweep".
        iterations: Worst-first: single-contact resolutions (None: 2 × contacts). Sweep: passes
            over all contacts (None: 10, ending early once a pass changes nothing).
        restitution_threshold: Closing speeds below this [m/s] get restitution 0.

    Returns the number of single-contact resolutions performed. Afterwards
    ``contacts.penetration`` holds each contact's remaining penetration.
    """
    m = contacts.count
    if m == 0:
        return 0
    p = particles
    disp = np.zeros((p.count, 3))
    pen0 = contacts.penetration.copy()
    args = (p.position, p.velocity, p.acceleration, p.inv_mass, contacts.a, contacts.b,
            contacts.normal, pen0, contacts.restitution, disp, float(dt),
            float(restitution_threshold))
    if mode == "worst-first":
        used = _worst_first(*args, 2 * m if iterations is None else int(iterations))
    elif mode == "sweep":
        used = _sweep(*args, DEFAULT_SWEEP_PASSES if iterations is None else int(iterations))
    else:
        raise ValueError(f"mode must be 'worst-first' or 'sweep', got {mode!r}")
    _current_penetration(contacts.a, contacts.b, contacts.normal, pen0, disp, contacts.penetration)
    return int(used)
