"""The contact resolver: Millington's iterative algorithm, compiled with numba.

For one contact (a, b, normal n from b to a, penetration d, restitution e):

1. *Velocity.* The separating velocity is vs = (v_a - v_b)·n. If vs < 0 they are closing; the
   target is -e·vs. A *speculative* contact (a gap g = -d > 0 inside the collision margin) is
   treated the same way only if it would close within this step (-vs·dt > g); otherwise the pair
   is left alone, so nothing is stopped before it arrives. The **resting-contact trick**: the
   part of the closing speed that this step's acceleration alone produced, ((acc_a - acc_b)·n)·dt,
   is not bounced back, so objects resting under gravity do not jitter. An impulse along n,
   shared by inverse mass, reaches the target.
2. *Interpenetration.* Each particle moves along n in proportion to its inverse mass until the
   overlap is gone (a projection: positions change, velocities do not).

**Worst-first** (the book's loop): each iteration resolves the single contact with the most
negative separating velocity among those closing or penetrating, up to ``iterations`` (default
2 × contacts), and stops early when nothing qualifies.

**Sweep** is sequential impulses (Box2D-lite's solver) on the same contacts: velocity passes over
every contact in order (Gauss–Seidel, linear per pass where worst-first is quadratic), each
keeping an accumulated impulse clamped at ≥ 0, then projection passes. Each contact with a key
(sphere pairs, planes) starts from the impulse it needed in the previous step (warm starting).
Without it a resting pile is never solved within a step's passes: measured, a 5-sphere stack
kept closing at 0.1 m/s after 10 cold passes and needed ~70 passes per step to rest; warm
started, it rests with one resolution per contact per step.

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
#: Most sweep passes when ``iterations`` is None; the sweep stops earlier once converged.
DEFAULT_SWEEP_PASSES = 10
#: Projection passes allowed per velocity pass (projection is cheaper and sets penetration).
PROJECTION_PASSES_PER_PASS = 3
#: Projection has converged when no penetration exceeds this × dt [m/s × s]: at 60 Hz, 1.7 µm.
#: (Looser values do not save passes in a jammed pile: there it converges slowly anyway.)
PROJECTION_TOLERANCE = 1e-4
#: The sweep has converged when no contact changed its separating velocity by more than this
#: [m/s] in a pass (nor its penetration by more than this × dt).
SWEEP_TOLERANCE = 1e-4


@njit(cache=True, inline="always")
def _dot_rel(v, a, b, n, c):
    """(v[a] - v[b])·n[c], with b = -1 meaning a static body."""
    if b >= 0:
        return ((v[a, 0] - v[b, 0]) * n[c, 0] + (v[a, 1] - v[b, 1]) * n[c, 1]
                + (v[a, 2] - v[b, 2]) * n[c, 2])
    return v[a, 0] * n[c, 0] + v[a, 1] * n[c, 1] + v[a, 2] * n[c, 2]


@njit(cache=True)
def _resolve_one(c, pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, disp, dt, threshold):
    """Resolve contact ``c``: its velocity, then its interpenetration. Returns how much it
    changed: the larger of the separating-velocity change [m/s] and the projected depth / dt."""
    a = ca[c]
    b = cb[c]
    wa = inv_mass[a]
    wb = inv_mass[b] if b >= 0 else 0.0
    total = wa + wb
    if total <= 0.0:
        return 0.0  # two immovable particles: nothing we do here matters
    changed = 0.0

    # --- velocity --------------------------------------------------------------------------
    vs = _dot_rel(vel, a, b, normal, c)
    depth = pen0[c] - _dot_rel(disp, a, b, normal, c)
    if vs < -VELOCITY_EPSILON and depth - vs * dt > 0.0:  # closing, and touching within dt
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
        changed = target - vs

    # --- interpenetration --------------------------------------------------------------------
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
        changed = max(changed, depth / dt)
    return changed


@njit(cache=True)
def _worst_first(pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, disp, dt, threshold,
                 iterations):
    """The book's loop: resolve the worst contact, one at a time. "Worst" is the most negative
    separating velocity, as in the book, less depth/dt for a penetrating contact: a deep
    contact that is not closing still needs fixing, and the book's order (closing speed alone)
    leaves it until every closing contact is done, which a pile never reaches."""
    m = ca.shape[0]
    used = 0
    while used < iterations:
        worst = -1
        worst_key = np.inf
        for c in range(m):
            vs = _dot_rel(vel, ca[c], cb[c], normal, c)
            depth = pen0[c] - _dot_rel(disp, ca[c], cb[c], normal, c)
            closing = vs < -VELOCITY_EPSILON and depth - vs * dt > 0.0
            if closing or depth > PENETRATION_EPSILON:
                key = vs - max(depth, 0.0) / dt
                if key < worst_key:
                    worst_key = key
                    worst = c
        if worst < 0:
            break  # nothing closing or penetrating: done early
        _resolve_one(worst, pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, disp, dt,
                     threshold)
        used += 1
    return used


@njit(cache=True)
def _sweep_setup(vel, acc, inv_mass, ca, cb, normal, pen0, rest, dt, threshold, target, wa, wb,
                 inv_total):
    """Per contact: the lowest allowed separating velocity [m/s] this step, and the inverse
    masses (``wb`` = 0 for scenery; ``inv_total`` = 0 when both ends are immovable)."""
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        wa[c] = inv_mass[a]
        wb[c] = inv_mass[b] if b >= 0 else 0.0
        total = wa[c] + wb[c]
        inv_total[c] = 1.0 / total if total > 0.0 else 0.0
        vs = _dot_rel(vel, a, b, normal, c)
        depth = pen0[c]
        if vs < -VELOCITY_EPSILON and depth - vs * dt > 0.0:
            # A collision (touching now or within the step): bounce, with the resting trick.
            e = rest[c] if -vs > threshold else 0.0
            t = -e * vs
            acc_sep = _dot_rel(acc, a, b, normal, c) * dt
            if acc_sep < 0.0:
                t += e * acc_sep
                if t < 0.0:
                    t = 0.0
            target[c] = t
        elif depth < 0.0:
            target[c] = depth / dt  # a gap: it may close by the gap within the step, not more
        else:
            target[c] = 0.0  # touching: must not close


@njit(cache=True)
def _sweep(pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, disp, dt, threshold, passes,
           tolerance, impulse, target, wa, wb, inv_total, projection_passes,
           projection_tolerance):
    """Sequential impulses over all contacts (Gauss–Seidel), then projection passes.

    ``impulse`` holds each contact's accumulated impulse [N·s], warm-started from the previous
    step; the accumulated impulse is clamped at ≥ 0 (contacts push, never pull), so a warm
    start that was too strong is taken back. Velocity passes stop once no contact's separating
    velocity changes by more than ``tolerance`` [m/s]; projection passes once no penetration
    exceeds ``projection_tolerance·dt`` [m]. Returns the contact resolutions that changed
    something.
    """
    m = ca.shape[0]
    _sweep_setup(vel, acc, inv_mass, ca, cb, normal, pen0, rest, dt, threshold, target, wa, wb,
                 inv_total)
    for c in range(m):  # warm start
        j = impulse[c]
        if j != 0.0:
            a = ca[c]
            b = cb[c]
            for k in range(3):
                vel[a, k] += normal[c, k] * j * wa[c]
                if b >= 0:
                    vel[b, k] -= normal[c, k] * j * wb[c]
    used = 0
    for _ in range(passes):
        largest = 0.0
        for c in range(m):
            a = ca[c]
            b = cb[c]
            nx = normal[c, 0]
            ny = normal[c, 1]
            nz = normal[c, 2]
            if b >= 0:
                vs = ((vel[a, 0] - vel[b, 0]) * nx + (vel[a, 1] - vel[b, 1]) * ny
                      + (vel[a, 2] - vel[b, 2]) * nz)
            else:
                vs = vel[a, 0] * nx + vel[a, 1] * ny + vel[a, 2] * nz
            old = impulse[c]
            accumulated = old + (target[c] - vs) * inv_total[c]
            if accumulated < 0.0:
                accumulated = 0.0
            step = accumulated - old
            if step != 0.0:
                impulse[c] = accumulated
                ja = step * wa[c]
                vel[a, 0] += nx * ja
                vel[a, 1] += ny * ja
                vel[a, 2] += nz * ja
                if b >= 0:
                    jb = step * wb[c]
                    vel[b, 0] -= nx * jb
                    vel[b, 1] -= ny * jb
                    vel[b, 2] -= nz * jb
                change = abs(step) * (wa[c] + wb[c])
                if change > largest:
                    largest = change
                used += 1
        if largest <= tolerance:
            break
    for _ in range(projection_passes):
        largest = 0.0
        for c in range(m):
            a = ca[c]
            b = cb[c]
            depth = pen0[c] - _dot_rel(disp, a, b, normal, c)
            if depth <= PENETRATION_EPSILON or inv_total[c] == 0.0:
                continue
            share = depth * inv_total[c]
            for k in range(3):
                move_a = normal[c, k] * share * wa[c]
                pos[a, k] += move_a
                disp[a, k] += move_a
                if b >= 0:
                    move_b = -normal[c, k] * share * wb[c]
                    pos[b, k] += move_b
                    disp[b, k] += move_b
            if depth > largest:
                largest = depth
        if largest <= projection_tolerance * dt:
            break
    return used


@njit(cache=True)
def _current_penetration(ca, cb, normal, pen0, disp, out):
    for c in range(ca.shape[0]):
        out[c] = pen0[c] - _dot_rel(disp, ca[c], cb[c], normal, c)


@njit(cache=True)
def _lookup_impulses(old_keys, old_impulse, keys, out):
    """out[c] = the impulse kept for keys[c] in the sorted ``old_keys``, or 0.

    The keys come in long sorted runs (each generator emits them in order), so this walks
    both lists together, and binary-searches only where a new run starts.
    """
    n_old = old_keys.shape[0]
    j = 0
    last = -1
    for c in range(keys.shape[0]):
        key = keys[c]
        out[c] = 0.0
        if key < 0:
            continue
        if key < last:  # a new run: find its place
            lo = 0
            hi = n_old
            while lo < hi:
                mid = (lo + hi) >> 1
                if old_keys[mid] < key:
                    lo = mid + 1
                else:
                    hi = mid
            j = lo
        while j < n_old and old_keys[j] < key:
            j += 1
        if j < n_old and old_keys[j] == key:
            out[c] = old_impulse[j]
        last = key


def _warm_impulses(contacts: ContactBuffer, keys: np.ndarray) -> np.ndarray:
    """The impulses the same contacts (same keys) needed last step, else 0; shape (M,)."""
    impulse = np.zeros(keys.shape[0])
    warm = contacts._warm
    if warm is not None and warm[0].size:
        _lookup_impulses(warm[0], warm[1], keys, impulse)
    return impulse


def resolve_contacts(particles: Particles, contacts: ContactBuffer, dt: float, *,
                     mode: str = "worst-first", iterations: int | None = None,
                     restitution_threshold: float = 0.0, warm_start: bool = True) -> int:
    """Resolve ``contacts`` in place (velocities and positions of ``particles``).

    Args:
        mode: "worst-first" or "sweep".
        iterations: Worst-first: single-contact resolutions (None: 2 × contacts). Sweep: most
            velocity passes over all contacts (None: 10), and 3 × as many projection passes;
            each phase ends early once converged (``SWEEP_TOLERANCE``).
        restitution_threshold: Closing speeds below this [m/s] get restitution 0.
        warm_start: Sweep only: start each keyed contact from the impulse it needed in the
            previous call on the same ``contacts`` buffer.

    Returns the number of single-contact resolutions performed. Afterwards
    ``contacts.penetration`` holds each contact's remaining penetration.
    """
    m = contacts.count
    if m == 0:
        contacts.clear_history()
        return 0
    p = particles
    disp = np.zeros((p.count, 3))
    pen0 = contacts.penetration.copy()
    args = (p.position, p.velocity, p.acceleration, p.inv_mass, contacts.a, contacts.b,
            contacts.normal, pen0, contacts.restitution, disp, float(dt),
            float(restitution_threshold))
    if mode == "worst-first":
        contacts.clear_history()  # the book's resolver keeps no impulses between steps
        used = _worst_first(*args, 2 * m if iterations is None else int(iterations))
    elif mode == "sweep":
        keys = contacts.key
        impulse = _warm_impulses(contacts, keys) if warm_start else np.zeros(m)
        passes = DEFAULT_SWEEP_PASSES if iterations is None else int(iterations)
        used = _sweep(*args, passes, SWEEP_TOLERANCE, impulse, np.empty(m), np.empty(m),
                      np.empty(m), np.empty(m), PROJECTION_PASSES_PER_PASS * passes,
                      PROJECTION_TOLERANCE)
        keep = keys >= 0
        kept = keys[keep]
        order = np.argsort(kept, kind="stable")  # nearly sorted already: timsort is fast
        contacts._warm = (kept[order], impulse[keep][order])
    else:
        raise ValueError(f"mode must be 'worst-first' or 'sweep', got {mode!r}")
    _current_penetration(contacts.a, contacts.b, contacts.normal, pen0, disp, contacts.penetration)
    return int(used)
