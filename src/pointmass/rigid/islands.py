"""Islands of rigid bodies and the decision to put them to sleep (rigid-notes §1.1, R6).

An island is a set of movable bodies joined by touching contact points (a gap of at most
``TOUCH_GAP``: a speculative point further apart does not join them) or by an extra list of
body pairs that must share one (joints). Immovable bodies (inv_mass 0) and planes join nothing,
so two piles on one floor are two islands. The islands are rebuilt every step by union–find.

A body counts as still while none of its points gets further than ``SLEEP_SPEED`` ×
``TIME_TO_SLEEP`` (2.5 cm) from where it was when it last moved: the bound |Δx| + extent·θ, its
extent being the distance from its centre of mass to its furthest surface point and θ the angle
it has turned (so turning counts in metres too: Cyclone mixed m²/s² with rad²/s²). Its
``sleep_time`` adds up the seconds it has been still; an island falls asleep when every body in
it has been still for ``TIME_TO_SLEEP`` — all together, so the bottom of a stack never sleeps
while the top moves. The thresholds are Box2D v3's (``sleepThreshold`` 0.05 m/s,
``b2_timeToSleep`` 0.5 s; Jolt's are 0.03 m/s and 0.5 s); the test on how far the points went
rather than on their speed each step is Jolt's (``Body::UpdateSleepStateInternal`` keeps three
points of the body within ``mPointVelocitySleepThreshold`` × ``mTimeBeforeSleep``). Measured
on the 300-box pit at rest: the speed test never put the heap to sleep (somewhere among 287
touching boxes the solver's jitter lifts one point above 0.05 m/s for a step every ~0.1 s,
while the heap moves 0.01 m/s on average); the distance test ignores a jitter that goes
nowhere.

Kernels here are plain loops; ``sleep.py`` drives them from the world.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .shapes import BOX, SPHERE

#: Speed [m/s] of a body's fastest point below which it counts as still.
SLEEP_SPEED = 0.05
#: Seconds every body of an island must have been still before the island sleeps.
TIME_TO_SLEEP = 0.5
#: Largest gap [m] at which a contact point still joins two bodies into one island (the
#: solver leaves resting points at 0 to +0.15 mm of overlap; float noise can leave −1e-17).
TOUCH_GAP = 1e-4


@njit(cache=True, nogil=True)
def extents(shape, size, inv_mass, inv_inertia, out):
    """Each body's extent [m] into ``out`` (N,): a sphere's radius, a box's half-diagonal; a
    body without a shape gets its largest radius of gyration √(I_max/m) (0 if immovable)."""
    for i in range(shape.shape[0]):
        if shape[i] == SPHERE:
            out[i] = size[i, 0]
        elif shape[i] == BOX:
            out[i] = math.sqrt(size[i, 0] ** 2 + size[i, 1] ** 2 + size[i, 2] ** 2)
        else:
            smallest = 0.0
            for k in range(3):
                w = inv_inertia[i, k]
                if w > 0.0 and (smallest == 0.0 or w < smallest):
                    smallest = w
            out[i] = math.sqrt(inv_mass[i] / smallest) if smallest > 0.0 else 0.0


@njit(cache=True, nogil=True, inline="always")
def find_root(parent, i):
    """Root of i's set, halving the path on the way (sets are rooted at their lowest index)."""
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


@njit(cache=True, nogil=True, inline="always")
def _union(parent, i, j):
    ri = find_root(parent, i)
    rj = find_root(parent, j)
    if ri < rj:
        parent[rj] = ri
    elif rj < ri:
        parent[ri] = rj


@njit(cache=True, nogil=True)
def build_islands(n, ca, cb, depth, movable, link_a, link_b, parent):
    """Union–find over ``n`` bodies: ``parent`` (n,) ends as each body's island, named by its
    lowest body index. Joined: the two bodies of a row (``ca``, ``cb``; cb < 0 a plane, an
    index ≥ n a particle) with ``depth`` ≥ −``TOUCH_GAP``, and each ``link_a``/``link_b`` pair
    (joints) — when both bodies are ``movable``."""
    for i in range(n):
        parent[i] = i
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        if b < 0 or a >= n or b >= n or depth[c] < -TOUCH_GAP:
            continue
        if movable[a] and movable[b]:
            _union(parent, a, b)
    for k in range(link_a.shape[0]):
        a = link_a[k]
        b = link_b[k]
        if movable[a] and movable[b]:
            _union(parent, a, b)
    for i in range(n):
        parent[i] = find_root(parent, i)


@njit(cache=True, nogil=True)
def still_timers(pos, quat, extent, movable, awake, still_pos, still_quat, sleep_time, dt,
                 reach, window):
    """Add ``dt`` [s] to the ``sleep_time`` of each awake movable body whose points all stay
    within ``reach`` [m] of where they were at ``still_pos``, ``still_quat`` (bound: |Δx| +
    extent·θ, θ the angle turned); else restart it from 0 at the current pose. The pose it
    counts from moves on to the current one every ``window`` [s] of stillness, so what is
    tested is the distance gone in one window (a creep slower than reach/window never adds up
    to a reset), not since the body first stopped."""
    for i in range(pos.shape[0]):
        if not (movable[i] and awake[i]):
            continue
        dx = pos[i, 0] - still_pos[i, 0]
        dy = pos[i, 1] - still_pos[i, 1]
        dz = pos[i, 2] - still_pos[i, 2]
        dot = abs(quat[i, 0] * still_quat[i, 0] + quat[i, 1] * still_quat[i, 1]
                  + quat[i, 2] * still_quat[i, 2] + quat[i, 3] * still_quat[i, 3])
        turned = 2.0 * math.acos(min(dot, 1.0))
        if math.sqrt(dx * dx + dy * dy + dz * dz) + extent[i] * turned > reach:
            sleep_time[i] = 0.0
            for k in range(3):
                still_pos[i, k] = pos[i, k]
            for k in range(4):
                still_quat[i, k] = quat[i, k]
        else:
            before = sleep_time[i]
            sleep_time[i] = before + dt
            if math.floor(sleep_time[i] / window) > math.floor(before / window):
                for k in range(3):
                    still_pos[i, k] = pos[i, k]
                for k in range(4):
                    still_quat[i, k] = quat[i, k]


@njit(cache=True, nogil=True)
def fall_asleep(parent, movable, awake, sleep_time, vel, ang, extent, island, time_to_sleep,
                speed):
    """Put to sleep every island (``parent`` from ``build_islands``) whose awake movable bodies
    have all been still for ``time_to_sleep`` [s] and none of whose points moves faster than
    ``speed`` [m/s] now (|v| + |ω|·extent: a calm moment, so a body that has only begun to
    tip or slide is not frozen in mid-move; a jitter spike only delays the sleep by a step):
    ``awake`` False, velocities zeroed, ``island`` set to the island's name. An island that
    holds a body already asleep (one the user put to sleep by hand, touching) waits: it wakes
    with the rest at the next contact. Returns the bodies put to sleep."""
    n = parent.shape[0]
    ready = np.ones(n, np.bool_)
    for i in range(n):
        if not movable[i]:
            continue
        if not awake[i] or sleep_time[i] < time_to_sleep:
            ready[parent[i]] = False
            continue
        v = math.sqrt(vel[i, 0] ** 2 + vel[i, 1] ** 2 + vel[i, 2] ** 2)
        w = math.sqrt(ang[i, 0] ** 2 + ang[i, 1] ** 2 + ang[i, 2] ** 2)
        if v + w * extent[i] > speed:
            ready[parent[i]] = False
    slept = 0
    for i in range(n):
        if not (movable[i] and awake[i] and ready[parent[i]]):
            continue
        awake[i] = False
        island[i] = parent[i]
        for k in range(3):
            vel[i, k] = 0.0
            ang[i, k] = 0.0
        slept += 1
    return slept


@njit(cache=True, nogil=True)
def touched_sleepers(n, ca, cb, normal, ra, rb, depth, vel, ang, awake, dt, out):
    """Mark in ``out`` (n,) each sleeping body that a contact row touches (``depth`` ≥
    −``TOUCH_GAP``: the two will be one island) or closes on within the step ``dt`` (the
    relative normal velocity of the point [m/s] covers the gap: an impact is coming). A
    speculative row between bodies that are not closing wakes nothing: two islands a hair
    apart would otherwise wake each other in turn forever. Rows are made only for pairs with
    an awake side; rows to particles (index ≥ n) and planes are skipped. Returns how many."""
    count = 0
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        if a >= n or b < 0 or b >= n or (awake[a] and awake[b]):
            continue
        d = depth[c]
        if d < -TOUCH_GAP:
            vs = 0.0
            for k in range(3):
                va = vel[a, k]
                vb = vel[b, k]
                if k == 0:
                    va += ang[a, 1] * ra[c, 2] - ang[a, 2] * ra[c, 1]
                    vb += ang[b, 1] * rb[c, 2] - ang[b, 2] * rb[c, 1]
                elif k == 1:
                    va += ang[a, 2] * ra[c, 0] - ang[a, 0] * ra[c, 2]
                    vb += ang[b, 2] * rb[c, 0] - ang[b, 0] * rb[c, 2]
                else:
                    va += ang[a, 0] * ra[c, 1] - ang[a, 1] * ra[c, 0]
                    vb += ang[b, 0] * rb[c, 1] - ang[b, 1] * rb[c, 0]
                vs += (va - vb) * normal[c, k]
            if d - vs * dt < -TOUCH_GAP:
                continue  # a gap that stays open this step
        for i in (a, b):
            if not awake[i] and not out[i]:
                out[i] = True
                count += 1
    return count


@njit(cache=True, nogil=True)
def hit_by_particles(n, ca, cb, normal, vel, acc, awake, dt, speed, out):
    """Mark in ``out`` (n,) each sleeping body that a particle row hits: the particle (packed
    index ``ca`` ≥ n, normal from the body to it) closes faster than ``speed`` [m/s] beyond
    what its own acceleration ``acc`` built up in this step (the solver's resting-contact
    trick), so a particle resting on a sleeping body leaves it asleep. Returns how many."""
    count = 0
    for c in range(ca.shape[0]):
        p = ca[c]
        b = cb[c]
        if p < n or b < 0 or b >= n or awake[b] or out[b]:
            continue
        closing = -(vel[p, 0] * normal[c, 0] + vel[p, 1] * normal[c, 1]
                    + vel[p, 2] * normal[c, 2])
        built = abs(acc[p, 0] * normal[c, 0] + acc[p, 1] * normal[c, 1]
                    + acc[p, 2] * normal[c, 2]) * dt
        if closing - built > speed:
            out[b] = True
            count += 1
    return count
