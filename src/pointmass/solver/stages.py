"""The solver's stages, in the order a step runs them (Box2D v3's contact solver names them the
same way): prepare → impacts → warm start → solve velocities → project positions; the impulse
history is stored by the caller. ``worst_first`` is the book's loop on the same kernels.

Each stage is a plain loop over the contacts, compiled with numba. It takes the ``Bodies`` and
``ContactSet`` namedtuples and unpacks them once into local arrays (see ``kernels.py``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .kernels import (
    PENETRATION_EPSILON,
    VELOCITY_EPSILON,
    bounce_target,
    clamp_disc,
    closing_within_step,
    friction_once,
    project,
    push,
    relative,
    slide,
)
from .sweeps import has_friction, projection_rows, velocity_rows


@njit(cache=True, nogil=True)
def prepare(bod, con, dt):
    """Per contact: inverse masses, effective mass k = 1/(wa + wb) (0 when both ends are
    immovable), the closing speed this step's accelerations could have produced (acc_sep ≤ 0,
    for the resting-contact trick) and the lowest separating velocity the sweep allows
    (target): 0 for a touching contact and a rod, a gap/dt for a speculative one (it may close
    by its gap, not more)."""
    ca, cb, n, depth0, bil = con.a, con.b, con.n, con.depth0, con.bil
    wa, wb, k, acc_sep, target = con.wa, con.wb, con.k, con.acc_sep, con.target
    inv_mass, acc, vel = bod.inv_mass, bod.acc, bod.vel
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        w_a = inv_mass[a]  # kept in locals, not read back from the arrays just written
        w_b = inv_mass[b] if b >= 0 else 0.0
        wa[c] = w_a
        wb[c] = w_b
        total = w_a + w_b
        k[c] = 1.0 / total if total > 0.0 else 0.0
        # The closing speed this step's accelerations could have built up, end by end: in a
        # stack both spheres fall with g (their relative acceleration is 0), yet once the
        # floor stops the lower one the upper closes on it by g·dt; that is resting, not an
        # impact, so each end's own acceleration counts (for scenery this is the book's term).
        along = abs(acc[a, 0] * n[c, 0] + acc[a, 1] * n[c, 1] + acc[a, 2] * n[c, 2])
        if b >= 0:
            along += abs(acc[b, 0] * n[c, 0] + acc[b, 1] * n[c, 1] + acc[b, 2] * n[c, 2])
        acc_sep[c] = -along * dt
        # The depth before this step's move (depth0 is measured after it): the sweep's
        # impulses move the positions too (``follow_impulses``), so a contact ends the step
        # at depth ``before - vs·dt``: a gap may close by itself, no more (a rod: held).
        before = depth0[c] + relative(vel, ca, cb, n, c) * dt
        # Whether the row has a gap, multiplied in: as a conditional expression it compiled
        # to a branch, guessed wrong on the settled 10 000-sphere pit, where ~40 % of the rows
        # are gaps in no pattern (the stage 0.51 -> 0.24 ms, the same values).
        gap = np.float64((before < 0.0) & (not bil[c]))
        target[c] = before / dt * gap


@njit(cache=True, nogil=True)
def impacts(bod, con, dt, threshold, tolerance, max_passes):
    """Collisions, by Millington's sequential propagation: pass over the contacts in order; a
    contact closing faster than this step's acceleration explains (an impact, not a resting
    contact) bounces at once to its target -e·vs, taken from its separating velocity *when it
    is visited*. So the impulse that stops the first ball of Newton's cradle makes the second
    contact close, which then bounces in turn, and the last ball leaves with all the momentum
    (a simultaneous solve would move balls 2–5 as one block). Pairwise impulses with e ≤ 1
    never add kinetic energy. Passes repeat until no contact closes by more than
    ``tolerance`` [m/s] beyond its acceleration, at most ``max_passes``.

    A contact that pushed last step (its remembered impulse, ``con.impulse``, is > 0) is
    resting, not colliding: it is left to the sweep, so the small closing speeds a loaded pile
    is always left with do not bounce it back to life (measured: a frictional pile kept
    creeping at 2 cm/s, and came to exact rest once its pressed contacts no longer bounced).

    After the first pass, a contact neither of whose particles was hit in this pass or the last
    is not looked at again: nothing it would see has changed since it was last found not to
    close, so the answer is the one a full pass gives (a settled 10 000-sphere pit runs ~3
    passes a step, a few hundred hits among 35 000 rows).

    Returns (passes, resolutions)."""
    ca, cb, n, depth0, e, mu = con.a, con.b, con.n, con.depth0, con.e, con.mu
    wa, wb, k, acc_sep, pressed = con.wa, con.wb, con.k, con.acc_sep, con.impulse
    vel, disp = bod.vel, bod.disp
    hit_in = np.zeros(vel.shape[0], np.int64)  # the last pass that changed each particle
    # The rows that may collide (not immovable, not pressed: a row that carried load last
    # step is resting, the sweep's), listed once in order and visited by every pass (the
    # settled 10 000-sphere pit: ~4 900 of 33 000 rows; a later pass 0.07 -> ~0.01 ms). The
    # list is written without a branch: whether a row is pressed changes from row to row.
    live = np.empty(ca.shape[0], np.int64)
    candidates = 0
    for c in range(ca.shape[0]):
        live[candidates] = c
        candidates += (k[c] != 0.0) & (not pressed[c] > 0.0)
    passes = 0
    used = 0
    while passes < max_passes:
        passes += 1
        hits = 0
        for r in range(candidates):
            c = live[r]
            a = ca[c]
            b = cb[c]
            if passes > 1 and hit_in[a] < passes - 1 and (b < 0 or hit_in[b] < passes - 1):
                continue  # unchanged since its last look
            vs = relative(vel, ca, cb, n, c)
            if not closing_within_step(vs, depth0[c], dt):
                continue
            accel = acc_sep[c] if acc_sep[c] < 0.0 else 0.0
            if vs - accel >= -tolerance:
                continue  # resting: the sweep holds it, with its warm start
            j = (bounce_target(vs, acc_sep[c], e[c], threshold) - vs) * k[c]
            for i in range(3):  # kernels.push written out (see solve_velocities)
                vel[a, i] += n[c, i] * j * wa[c]
                if b >= 0:
                    vel[b, i] -= n[c, i] * j * wb[c]
            if mu[c] > 0.0:
                friction_once(vel, disp, ca, cb, n, wa, wb, k, mu, c, j, dt)
            hit_in[a] = passes
            if b >= 0:
                hit_in[b] = passes
            hits += 1
        used += hits
        if hits == 0:
            break
    return passes, used


@njit(cache=True, nogil=True)
def warm_start(bod, con, dt):
    """Apply each contact's remembered impulses (normal, then friction kept in this step's
    contact plane and friction disc), so a resting pile starts out solved."""
    ca, cb, n, mu, wa, wb = con.a, con.b, con.n, con.mu, con.wa, con.wb
    impulse, t = con.impulse, con.tangent
    vel, disp = bod.vel, bod.disp
    for c in range(ca.shape[0]):
        # kernels.push written out, without branches, as in ``sweeps.velocity_rows``: a row
        # with scenery writes particle a back in b's place, with b's inverse mass 0 (the
        # settled pit: 0.69 -> 0.19 ms a step written out, 0.16 without the branches).
        j = impulse[c]
        a = ca[c]
        b = cb[c]
        scenery = b < 0
        other = a if scenery else b
        nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
        ja = j * wa[c]
        jb = j * wb[c]
        ox, oy, oz = vel[other, 0], vel[other, 1], vel[other, 2]
        vel[other, 0] = ox - nx * jb
        vel[other, 1] = oy - ny * jb
        vel[other, 2] = oz - nz * jb
        vel[a, 0] += nx * ja
        vel[a, 1] += ny * ja
        vel[a, 2] += nz * ja
        if t[c, 0] != 0.0 or t[c, 1] != 0.0 or t[c, 2] != 0.0:
            if mu[c] > 0.0:
                tn = t[c, 0] * n[c, 0] + t[c, 1] * n[c, 1] + t[c, 2] * n[c, 2]
                for i in range(3):
                    t[c, i] -= tn * n[c, i]
                clamp_disc(t, c, mu[c] * j)
                slide(vel, disp, ca, cb, wa, wb, c, t[c, 0], t[c, 1], t[c, 2], dt)
            else:  # friction switched off since: nothing to warm start
                t[c, 0] = 0.0
                t[c, 1] = 0.0
                t[c, 2] = 0.0


@njit(cache=True, nogil=True)
def solve_velocities(bod, con, dt, tolerance, max_passes, relaxation):
    """Sequential impulses over every contact in row order (``sweeps.velocity_rows``),
    passes until no contact's velocity changes by more than ``tolerance`` [m/s] in a pass,
    at most ``max_passes``; each row's step over-relaxed by ``relaxation`` (1: plain).

    Returns (passes, resolutions)."""
    passes = 0
    used = 0
    friction = has_friction(con)
    while passes < max_passes:
        passes += 1
        largest, hits = velocity_rows(bod, con, None, 0, con.a.shape[0], dt, friction,
                                      relaxation)
        used += hits
        if largest <= tolerance:
            break
    return passes, used


@njit(cache=True, nogil=True)
def follow_impulses(bod, con, dt):
    """Move the particles by the velocity the sweep's normal impulses gave them, × dt (its
    friction impulses already did, in ``kernels.slide``): the integration moved them with the
    velocities before the contacts, so a resting sphere sank g·dt² each step for projection to
    lift again, through the whole pile (measured: a 10 000-sphere pit never converged in 15
    projection passes). Box2D solves velocities, then integrates; this is the same order."""
    ca, cb, n, wa, wb, impulse = con.a, con.b, con.n, con.wa, con.wb, con.impulse
    disp = bod.disp
    for c in range(ca.shape[0]):
        # Written out, with no branch on j = 0 (a row without impulse moves nothing): the
        # settled 10 000-sphere pit 0.21 -> 0.17 ms, the same bits.
        j = impulse[c] * dt
        a = ca[c]
        b = cb[c]
        nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
        w = wa[c]
        disp[a, 0] += nx * j * w
        disp[a, 1] += ny * j * w
        disp[a, 2] += nz * j * w
        if b >= 0:
            w = wb[c]
            disp[b, 0] -= nx * j * w
            disp[b, 1] -= ny * j * w
            disp[b, 2] -= nz * j * w


@njit(cache=True, nogil=True)
def project_positions(bod, con, tolerance, max_passes):
    """Interpenetration: passes of mass-weighted projection over every contact in row order
    (``sweeps.projection_rows``) until no penetration exceeds ``tolerance`` [m], at most
    ``max_passes``. Positions only: no velocity changes, so projection adds no energy.

    Returns (passes, largest depth left)."""
    passes = 0
    largest = 0.0
    while passes < max_passes:
        passes += 1
        largest = projection_rows(bod, con, None, 0, con.a.shape[0])
        if largest <= tolerance:
            break
    return passes, largest


@njit(cache=True, nogil=True)
def slop_depths(position, anchor, ca, cb, n, depth0, bil, pressed, slop, out, given):
    """Each row's depth as the projection sees it (``out``): a resting contact's generated
    depth less ``slop`` (``SolverSettings.projection_slop``: a penetration that small is left
    where it is, Box2D's linear slop; resting: it pushed last step, its remembered impulse
    ``pressed`` > 0, the impact stage's test), any other row's as generated: a contact that
    only got there (a sphere moved in by hand, an impact) is pushed out entirely, and a link
    (a rod, a row from an anchor point, or one whose normal points from a to b: farther apart
    is deeper, as ``remeasure.has_links`` tells them) is held at its length.

    Why: a resting pile's velocity passes leave µm of sinking here and there, each step
    somewhere else; projected out at once, it moved the contacts every step and the warm start
    never caught up (the frictionless pits jittered at 0.02-0.03 m/s). Left within the slop,
    the pile keeps its contacts and comes to rest. ``given``: the slop each row got.
    Returns how many rows got it. (Arrays, not the ``ContactSet``, and the geometry read only
    for rows that pushed: over the 10 000 pit's first 300 steps, 0.93 ms a call with the
    namedtuple, 0.75 with arrays, 0.58 reading positions only where pushed.)"""
    anchored = anchor.shape[0] > 0
    count = 0
    for c in range(ca.shape[0]):
        # only a row that pushed last step can rest: the others skip the geometry below
        resting = pressed[c] > 0.0 and not bil[c]
        if resting and anchored:
            resting = math.isnan(anchor[c, 0])
        b = cb[c]
        if resting and b >= 0:
            a = ca[c]
            resting = ((position[a, 0] - position[b, 0]) * n[c, 0]
                       + (position[a, 1] - position[b, 1]) * n[c, 1]
                       + (position[a, 2] - position[b, 2]) * n[c, 2]) >= 0.0
        given[c] = slop if resting else 0.0
        out[c] = depth0[c] - given[c]
        count += resting
    return count


@njit(cache=True, nogil=True)
def current_depths(bod, con, out):
    """Each contact's penetration after solving [m]."""
    ca, cb, n, depth0, disp = con.a, con.b, con.n, con.depth0, bod.disp
    for c in range(ca.shape[0]):
        out[c] = depth0[c] - relative(disp, ca, cb, n, c)


@njit(cache=True, nogil=True)
def worst_first(bod, con, dt, threshold, iterations):
    """The book's loop: resolve the single worst contact, up to ``iterations`` times; stop early
    when none is closing or penetrating. "Worst" is the most negative separating velocity, as
    in the book, less depth/dt for a penetrating contact (a deep contact that is not closing
    still needs fixing; the book's order leaves it until every closing contact is done, which a
    pile never reaches). Each resolution: bounce (with the resting-contact trick) and friction
    once, then remove that contact's penetration. Returns the resolutions made."""
    ca, cb, n, depth0, e, mu = con.a, con.b, con.n, con.depth0, con.e, con.mu
    wa, wb, k, acc_sep, bil = con.wa, con.wb, con.k, con.acc_sep, con.bil
    vel, disp = bod.vel, bod.disp
    used = 0
    while used < iterations:
        worst = -1
        worst_key = 1e300
        for c in range(ca.shape[0]):
            if k[c] == 0.0:
                continue
            vs = relative(vel, ca, cb, n, c)
            d = depth0[c] - relative(disp, ca, cb, n, c)
            if bil[c] and d < 0.0:  # a rod too short: as bad as one too long
                d = -d
                vs = -vs
            if closing_within_step(vs, d, dt) or d > PENETRATION_EPSILON:
                key = vs - max(d, 0.0) / dt
                if key < worst_key:
                    worst_key = key
                    worst = c
        if worst < 0:
            break
        c = worst
        vs = relative(vel, ca, cb, n, c)
        d = depth0[c] - relative(disp, ca, cb, n, c)
        if closing_within_step(vs, d, dt):
            j = (bounce_target(vs, acc_sep[c], e[c], threshold) - vs) * k[c]
            push(vel, ca, cb, n, wa, wb, c, j)
            friction_once(vel, disp, ca, cb, n, wa, wb, k, mu, c, j, dt)
        elif bil[c] and vs > VELOCITY_EPSILON and -d + vs * dt > 0.0:
            push(vel, ca, cb, n, wa, wb, c, -vs * k[c])  # a rod closing up: stop it
        project(disp, ca, cb, n, depth0, bil, wa, wb, k, c)
        used += 1
    return used
