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

**Friction** (Coulomb, per contact coefficient μ ≥ 0; 0 by default, frictionless as in the book).
In the sweep, right after a contact's normal impulse, a tangential impulse opposes the relative
tangential velocity v_t = v_rel - (v_rel·n) n: as in Box2D-lite, each contact keeps an
*accumulated* tangential impulse (here a 3-vector in the contact plane rather than Box2D-lite's
one 2-D tangent), the step aims to stop v_t (Δ = -v_t / (w_a + w_b)), and the accumulated vector
is clamped to the disc of radius μ × the accumulated normal impulse (the Coulomb cone) — so
friction can hold a contact still (static) or slide it at exactly μ × the normal impulse
(kinetic), and a contact that pushes nothing (a speculative gap) has no friction. It is
warm-started with the normal impulse (same keys), projected onto the contact plane and clamped
again. The pass order is fixed, so it stays deterministic.

Friction also moves positions: the integrator has already moved each particle by its
pre-contact velocity × dt (semi-implicit Euler), and projection only corrects along the normal,
so a sphere held still on a slope would otherwise creep down by g·sinθ·dt² per step. Each
tangential velocity change Δv therefore also moves the particle by Δv·dt, as if the friction
had acted before the position update (Box2D's order: solve velocities, then integrate).

**Worst-first** applies friction once per resolution, without accumulation: after the normal
impulse j, a tangential impulse of at most μ·j opposes v_t (stopping it if that is enough), with
the same Δv·dt position correction.

After every single resolution, the penetration of every contact that shares a moved particle
must be updated. We keep, per particle, the displacement it has received since the contacts were
generated; a contact's current penetration is its generated penetration minus
(disp_a - disp_b)·n. That is exactly the book's per-contact patching (d -= Δp_a·n, d += Δp_b·n),
applied lazily, so no movement is ever stale (Cyclone's resolver forgets to clear its stored
movement on an early return and applies the previous contact's move instead).
"""

from __future__ import annotations

import math

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


@njit(cache=True, inline="always")
def _bounce_target(vs, acc_sep, restitution, threshold):
    """The separating velocity a closing contact (vs < 0) should leave with [m/s].

    -e·vs, where e is 0 below the restitution threshold; and the resting-contact trick: the
    closing speed that this step's acceleration alone built up (acc_sep = Δa·n·dt < 0) is not
    bounced back, so objects resting under gravity do not jitter.
    """
    e = restitution if -vs > threshold else 0.0
    target = -e * vs
    if acc_sep < 0.0:
        target += e * acc_sep
        if target < 0.0:
            target = 0.0
    return target


@njit(cache=True)
def _resolve_one(c, pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, fric, disp, dt,
                 threshold):
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
        target = _bounce_target(vs, _dot_rel(acc, a, b, normal, c) * dt, rest[c], threshold)
        impulse = (target - vs) / total
        for k in range(3):
            vel[a, k] += normal[c, k] * impulse * wa
            if b >= 0:
                vel[b, k] -= normal[c, k] * impulse * wb
        changed = target - vs
        if fric[c] > 0.0:
            # Coulomb friction, once: stop the tangential velocity, at most μ × the impulse.
            vt = np.empty(3)
            vn = _dot_rel(vel, a, b, normal, c)
            for k in range(3):
                rel = vel[a, k] - vel[b, k] if b >= 0 else vel[a, k]
                vt[k] = rel - vn * normal[c, k]
            speed = math.sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2])
            if speed > 0.0:
                jt = min(speed / total, fric[c] * impulse)
                scale = -jt / speed
                for k in range(3):
                    d = vt[k] * scale
                    vel[a, k] += d * wa
                    pos[a, k] += d * wa * dt
                    disp[a, k] += d * wa * dt
                    if b >= 0:
                        vel[b, k] -= d * wb
                        pos[b, k] -= d * wb * dt
                        disp[b, k] -= d * wb * dt

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
def _worst_first(pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, fric, disp, dt, threshold,
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
        _resolve_one(worst, pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, fric, disp, dt,
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
            target[c] = _bounce_target(vs, _dot_rel(acc, a, b, normal, c) * dt, rest[c],
                                       threshold)
        elif depth < 0.0:
            target[c] = depth / dt  # a gap: it may close by the gap within the step, not more
        else:
            target[c] = 0.0  # touching: must not close


@njit(cache=True, inline="always")
def _clamp_disc(tangent, c, limit):
    """Scale ``tangent[c]`` into the disc of radius ``limit`` (≥ 0)."""
    t2 = tangent[c, 0] * tangent[c, 0] + tangent[c, 1] * tangent[c, 1] \
        + tangent[c, 2] * tangent[c, 2]
    if t2 > limit * limit:
        s = limit / math.sqrt(t2) if t2 > 0.0 else 0.0
        tangent[c, 0] *= s
        tangent[c, 1] *= s
        tangent[c, 2] *= s


@njit(cache=True, inline="always")
def _apply_tangent(c, dx, dy, dz, pos, vel, disp, ca, cb, wa, wb, dt):
    """Apply the tangential impulse (dx, dy, dz) to contact ``c``'s particles (``b`` gets the
    opposite), with the matching position correction Δv·dt (see the module docstring)."""
    a = ca[c]
    b = cb[c]
    ja = wa[c]
    vel[a, 0] += dx * ja
    vel[a, 1] += dy * ja
    vel[a, 2] += dz * ja
    ja *= dt
    pos[a, 0] += dx * ja
    pos[a, 1] += dy * ja
    pos[a, 2] += dz * ja
    disp[a, 0] += dx * ja
    disp[a, 1] += dy * ja
    disp[a, 2] += dz * ja
    if b >= 0:
        jb = wb[c]
        vel[b, 0] -= dx * jb
        vel[b, 1] -= dy * jb
        vel[b, 2] -= dz * jb
        jb *= dt
        pos[b, 0] -= dx * jb
        pos[b, 1] -= dy * jb
        pos[b, 2] -= dz * jb
        disp[b, 0] -= dx * jb
        disp[b, 1] -= dy * jb
        disp[b, 2] -= dz * jb


@njit(cache=True, inline="always")
def _friction_step(c, pos, vel, disp, ca, cb, normal, impulse, tangent, fric, wa, wb, inv_total,
                   dt):
    """One sequential-impulse friction step on contact ``c`` (Box2D-lite's, with a disc):
    aim to stop the relative tangential velocity, clamp the accumulated tangential impulse to
    radius μ × the accumulated normal impulse, apply the difference. Returns the change in
    relative tangential velocity [m/s]."""
    a = ca[c]
    b = cb[c]
    nx = normal[c, 0]
    ny = normal[c, 1]
    nz = normal[c, 2]
    if b >= 0:
        rx = vel[a, 0] - vel[b, 0]
        ry = vel[a, 1] - vel[b, 1]
        rz = vel[a, 2] - vel[b, 2]
    else:
        rx = vel[a, 0]
        ry = vel[a, 1]
        rz = vel[a, 2]
    vn = rx * nx + ry * ny + rz * nz
    it = inv_total[c]
    ox = tangent[c, 0]
    oy = tangent[c, 1]
    oz = tangent[c, 2]
    tangent[c, 0] = ox - (rx - vn * nx) * it
    tangent[c, 1] = oy - (ry - vn * ny) * it
    tangent[c, 2] = oz - (rz - vn * nz) * it
    _clamp_disc(tangent, c, fric[c] * impulse[c])
    dx = tangent[c, 0] - ox
    dy = tangent[c, 1] - oy
    dz = tangent[c, 2] - oz
    if dx == 0.0 and dy == 0.0 and dz == 0.0:
        return 0.0
    _apply_tangent(c, dx, dy, dz, pos, vel, disp, ca, cb, wa, wb, dt)
    return math.sqrt(dx * dx + dy * dy + dz * dz) * (wa[c] + wb[c])


@njit(cache=True)
def _sweep(pos, vel, acc, inv_mass, ca, cb, normal, pen0, rest, fric, disp, dt, threshold,
           passes, tolerance, impulse, tangent, target, wa, wb, inv_total, projection_passes,
           projection_tolerance):
    """Sequential impulses over all contacts (Gauss–Seidel), then projection passes.

    ``impulse`` holds each contact's accumulated impulse [N·s], warm-started from the previous
    step; the accumulated impulse is clamped at ≥ 0 (contacts push, never pull), so a warm
    start that was too strong is taken back. ``tangent`` (M, 3) holds each contact's
    accumulated friction impulse [N·s], warm-started too, kept in the contact plane and inside
    the disc of radius ``fric`` × ``impulse`` (see the module docstring). Velocity passes stop
    once no contact's separating (or tangential) velocity changes by more than ``tolerance``
    [m/s]; projection passes once no penetration exceeds ``projection_tolerance·dt`` [m].
    Returns the contact resolutions that changed something.
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
        if fric[c] > 0.0:
            # The kept friction impulse, in this step's contact plane and friction disc.
            tn = (tangent[c, 0] * normal[c, 0] + tangent[c, 1] * normal[c, 1]
                  + tangent[c, 2] * normal[c, 2])
            for k in range(3):
                tangent[c, k] -= tn * normal[c, k]
            _clamp_disc(tangent, c, fric[c] * j)
            _apply_tangent(c, tangent[c, 0], tangent[c, 1], tangent[c, 2], pos, vel, disp, ca,
                           cb, wa, wb, dt)
        else:
            tangent[c, 0] = 0.0
            tangent[c, 1] = 0.0
            tangent[c, 2] = 0.0
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
            if fric[c] > 0.0:
                change = _friction_step(c, pos, vel, disp, ca, cb, normal, impulse, tangent,
                                        fric, wa, wb, inv_total, dt)
                if change > largest:
                    largest = change
                if change > 0.0 and step == 0.0:
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
def _lookup_impulses(old_keys, keys, out):
    """out[c] = the row of keys[c] in the sorted ``old_keys``, or -1.

    The keys come in long sorted runs (each generator emits them in order), so this walks
    both lists together, and binary-searches only where a new run starts.
    """
    n_old = old_keys.shape[0]
    j = 0
    last = -1
    for c in range(keys.shape[0]):
        key = keys[c]
        out[c] = -1
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
            out[c] = j
        last = key


def _warm_impulses(contacts: ContactBuffer, keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The normal impulses (M,) and friction impulses (M, 3) the same contacts (same keys)
    needed last step, else 0."""
    m = keys.shape[0]
    impulse = np.zeros(m)
    tangent = np.zeros((m, 3))
    warm = contacts._warm
    if warm is not None and warm[0].size:
        row = np.empty(m, np.int64)
        _lookup_impulses(warm[0], keys, row)
        found = row >= 0
        impulse[found] = warm[1][row[found]]
        if warm[2] is not None:
            tangent[found] = warm[2][row[found]]
    return impulse, tangent


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
            contacts.normal, pen0, contacts.restitution, contacts.friction, disp, float(dt),
            float(restitution_threshold))
    if mode == "worst-first":
        contacts.clear_history()  # the book's resolver keeps no impulses between steps
        used = _worst_first(*args, 2 * m if iterations is None else int(iterations))
    elif mode == "sweep":
        keys = contacts.key
        if warm_start:
            impulse, tangent = _warm_impulses(contacts, keys)
        else:
            impulse, tangent = np.zeros(m), np.zeros((m, 3))
        passes = DEFAULT_SWEEP_PASSES if iterations is None else int(iterations)
        used = _sweep(*args, passes, SWEEP_TOLERANCE, impulse, tangent, np.empty(m),
                      np.empty(m), np.empty(m), np.empty(m), PROJECTION_PASSES_PER_PASS * passes,
                      PROJECTION_TOLERANCE)
        keep = keys >= 0
        kept = keys[keep]
        order = np.argsort(kept, kind="stable")  # nearly sorted already: timsort is fast
        kept_tangent = tangent[keep][order] if contacts.friction.any() else None
        contacts._warm = (kept[order], impulse[keep][order], kept_tangent)
    else:
        raise ValueError(f"mode must be 'worst-first' or 'sweep', got {mode!r}")
    _current_penetration(contacts.a, contacts.b, contacts.normal, pen0, disp, contacts.penetration)
    return int(used)
