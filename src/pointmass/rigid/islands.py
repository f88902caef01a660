"""Islands of rigid bodies and the decision to put them to sleep (rigid-notes §1.1, R6).

An island is a set of movable bodies joined by touching contact points (a gap of at most
``TOUCH_GAP``: a speculative point further apart does not join them) or by an extra list of
body pairs that must share one (joints). Immovable bodies (inv_mass 0) and planes join nothing,
so two piles on one floor are two islands. The islands are rebuilt every step by union–find.

A body counts as still when |v| + |ω|·extent stays below ``SLEEP_SPEED`` [m/s], its extent being
the distance from its centre of mass to its furthest surface point (so the angular part is the
speed of its fastest point, in the same unit: Cyclone mixed m²/s² with rad²/s²). Its
``sleep_time`` adds up the seconds it has been still; an island falls asleep when every body in
it has been still for ``TIME_TO_SLEEP`` — all together, so the bottom of a stack never sleeps
while the top moves. Box2D v3's defaults (``sleepThreshold`` 0.05 m/s, ``b2_timeToSleep``
0.5 s); Jolt's are 0.03 m/s and 0.5 s.

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
def _root(parent, i):
    """Root of i's set, halving the path on the way (sets are rooted at their lowest index)."""
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


@njit(cache=True, nogil=True, inline="always")
def _union(parent, i, j):
    ri = _root(parent, i)
    rj = _root(parent, j)
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
        parent[i] = _root(parent, i)


@njit(cache=True, nogil=True)
def still_timers(vel, ang, extent, movable, awake, sleep_time, dt, speed):
    """Add ``dt`` [s] to the ``sleep_time`` of each awake movable body slower than ``speed``
    [m/s] (its fastest point: |v| + |ω|·extent); zero it for a faster one."""
    for i in range(vel.shape[0]):
        if not (movable[i] and awake[i]):
            continue
        v = math.sqrt(vel[i, 0] ** 2 + vel[i, 1] ** 2 + vel[i, 2] ** 2)
        w = math.sqrt(ang[i, 0] ** 2 + ang[i, 1] ** 2 + ang[i, 2] ** 2)
        if v + w * extent[i] > speed:
            sleep_time[i] = 0.0
        else:
            sleep_time[i] += dt


@njit(cache=True, nogil=True)
def fall_asleep(parent, movable, awake, sleep_time, vel, ang, island, time_to_sleep):
    """Put to sleep every island (``parent`` from ``build_islands``) whose awake movable bodies
    have all been still for ``time_to_sleep`` [s]: ``awake`` False, velocities zeroed,
    ``island`` set to the island's name. An island that holds a body already asleep (one the
    user put to sleep by hand, touching) waits: it wakes with the rest at the next contact.
    Returns the bodies put to sleep."""
    n = parent.shape[0]
    ready = np.ones(n, np.bool_)
    for i in range(n):
        if movable[i] and (not awake[i] or sleep_time[i] < time_to_sleep):
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
def touched_sleepers(n, ca, cb, awake, out):
    """Mark in ``out`` (n,) each sleeping body with a contact row this substep: rows are made
    only for pairs with an awake side, so such a body is touched (or about to be) by a body
    that moves. Rows to particles (index ≥ n) and planes are skipped. Returns how many."""
    count = 0
    for c in range(ca.shape[0]):
        if ca[c] >= n:
            continue  # a particle row: ``hit_by_particles`` judges it
        for side in range(2):
            i = ca[c] if side == 0 else cb[c]
            if 0 <= i < n and not awake[i] and not out[i]:
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
