"""Sleeping islands in the world's step: what wakes a body, when an island falls asleep, and
the warm start a sleeping island keeps (the kernels are in ``islands.py``).

Wakes an island (all of it, its still-time back to 0):
- a contact row with an awake body (a pair is narrow-phased when either body is awake) that
  touches it, or whose speculative gap closes within the step: a ball about to hit a sleeping
  stack wakes it before the solver sees the pair, so the stack takes the blow;
- a particle that hits one of its bodies faster than ``SLEEP_SPEED`` (one resting on it leaves
  it asleep and pushes against it as against scenery);
- a force or torque in the accumulators (``add_force`` and friends wake at once; a body force
  generator that pushes — an Explosion within its radius, a spring — wakes what it pushes);
- assigning a pose or velocity through ``Body``, or ``Body.awake = True``.

When an island falls asleep, the impulses its contact points needed are moved aside
(``SleepingImpulses``) and given back to the solver's history when it wakes, so a woken pile
starts from the impulses that held it up instead of from zero.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..impulse_history import ImpulseHistory
from ..keys import bodies_of_keys
from . import islands as isl


class SleepingImpulses:
    """The warm start of the contact points of sleeping bodies, keyed as in the history."""

    def __init__(self) -> None:
        self.kept = ImpulseHistory()

    def clear(self) -> None:
        self.kept = ImpulseHistory()

    def snapshot(self) -> ImpulseHistory:
        return self.kept

    def restore(self, snap: ImpulseHistory) -> None:
        self.kept = snap

    def put_away(self, history: ImpulseHistory, asleep: np.ndarray) -> None:
        """Keep the entries of ``history`` that name a body of the mask ``asleep`` (N,)."""
        mine = _names(history.keys, asleep)
        if mine.any():
            self.kept.merge(history.pick(mine))

    def give_back(self, history: ImpulseHistory, woken: np.ndarray) -> None:
        """Return to ``history`` the entries that name a body of the mask ``woken`` (N,)."""
        mine = _names(self.kept.keys, woken)
        if mine.any():
            history.merge(self.kept.pick(mine))
            self.kept = self.kept.pick(~mine)


def _names(keys: np.ndarray, bodies: np.ndarray) -> np.ndarray:
    """Mask of the keys whose contact involves a body of the mask ``bodies`` (N,)."""
    a, b = bodies_of_keys(keys)
    n = bodies.shape[0]
    hit = np.zeros(keys.shape[0], dtype=bool)
    for side in (a, b):
        ok = (side >= 0) & (side < n)
        hit[ok] |= bodies[side[ok]]
    return hit


def wake_pushed(bodies) -> None:
    """Wake every body with a force or torque in its accumulators (after the body force
    generators added theirs), and restart the still-time of those already awake."""
    b = bodies
    pushed = (b.force != 0.0).any(axis=1) | (b.torque != 0.0).any(axis=1)
    if pushed.any():
        b.sleep_time[pushed] = 0.0
        asleep = pushed & ~b.awake
        if asleep.any():
            b.wake_islands(np.unique(b.island[asleep]))


def active(bodies) -> np.ndarray:
    """Bodies that can disturb others this substep: awake movable ones, and immovable ones that
    move (kinematic). Sleeping bodies and still scenery are not."""
    b = bodies
    moving = (b.velocity != 0.0).any(axis=1) | (b.angular_velocity != 0.0).any(axis=1)
    return b.awake & ((b.inv_mass > 0.0) | moving)


def any_active(bodies) -> bool:
    """Whether any body is ``active`` (one kernel: numpy's masks cost a sleeping world's step
    ~4 µs)."""
    b = bodies
    return bool(_any_active(b.awake, b.inv_mass, b.velocity, b.angular_velocity))


@njit(cache=True, nogil=True)
def _any_active(awake, inv_mass, vel, ang):
    for i in range(awake.shape[0]):
        if not awake[i]:
            continue
        if inv_mass[i] > 0.0:
            return True
        for u in range(3):
            if vel[i, u] != 0.0 or ang[i, u] != 0.0:
                return True
    return False


def touched(bodies, contacts, packed, acceleration, dt: float, links: np.ndarray,
            live: np.ndarray) -> np.ndarray:
    """Mask (N,) of the sleeping bodies that this substep's rows wake: a row with a moving
    body, or a particle that hits (``islands.touched_sleepers``, ``hit_by_particles``), or a
    link (``links`` (K, 2)) to an ``active`` body (``live``); ``packed`` is the particle–body
    view or None, ``acceleration`` (N + particles, 3) what this substep's forces gave each of
    its rows [m/s²]."""
    b = bodies
    n = b.count
    out = np.zeros(n, dtype=bool)
    for one, other in ((links[:, 0], links[:, 1]), (links[:, 1], links[:, 0])):
        out[other[live[one] & ~b.awake[other]]] = True
    c = contacts
    isl.touched_sleepers(n, c.a, c.b, c.normal, c.r_a, c.r_b, c.depth, b.velocity,
                         b.angular_velocity, b.awake, float(dt), out)
    if packed is not None:
        isl.hit_by_particles(n, c.a, c.b, c.normal, packed.velocity, acceleration, b.awake,
                             float(dt), isl.SLEEP_SPEED, out)
    return out


def leave_sleepers_out(bodies, contacts, packed) -> None:
    """After the wakes: drop the body rows that reach a sleeping body (speculative gaps that
    stay open this step: they would only jostle it), and make the sleeping bodies that
    particles rest on immovable in the packed view (they push as on scenery)."""
    b = bodies
    asleep = ~b.awake
    c = contacts
    n = b.count
    ends = np.where((c.a < n), c.a, 0), np.where((c.b >= 0) & (c.b < n), c.b, 0)
    body_row = (c.a < n) & (c.b >= 0)
    near = body_row & (asleep[ends[0]] | asleep[ends[1]])
    if near.any():
        c.keep(~near)
    if packed is not None:
        packed.freeze(asleep)


def fall_asleep(bodies, contacts, links: np.ndarray, dt: float) -> np.ndarray | None:
    """After a step of ``dt`` [s]: advance the still-times, build the islands from the last
    substep's ``contacts`` and the (K, 2) body pairs ``links``, and put to sleep the islands
    that have been still for ``islands.TIME_TO_SLEEP``. Returns the mask of the bodies that
    fell asleep, or None when none did."""
    b = bodies
    n = b.count
    movable = b.inv_mass > 0.0
    extent = np.empty(n)
    isl.extents(b.shape, b.size, b.inv_mass, b.inv_inertia, extent)
    isl.still_timers(b.position, b.orientation, extent, movable, b.awake, b.still_position,
                     b.still_orientation, b.sleep_time, float(dt),
                     isl.SLEEP_SPEED * isl.TIME_TO_SLEEP, isl.TIME_TO_SLEEP)
    parent = np.empty(n, np.int64)
    c = contacts
    # Contiguous copies: a column of two or more links is a strided view, of none or one a
    # contiguous one, and numba compiled build_islands once for each layout.
    isl.build_islands(n, c.a, c.b, c.depth, movable, np.ascontiguousarray(links[:, 0]),
                      np.ascontiguousarray(links[:, 1]), parent)
    was = b.awake.copy()
    slept = isl.fall_asleep(parent, movable, b.awake, b.sleep_time, b.velocity,
                            b.angular_velocity, extent, b.island, isl.TIME_TO_SLEEP,
                            isl.SLEEP_SPEED)
    return (was & ~b.awake) if slept else None


def check_links(links, count: int) -> np.ndarray:
    """``links`` as a (K, 2) int64 array of body indices in [0, count), else an error."""
    arr = np.asarray(links)
    if arr.size == 0:
        return np.zeros((0, 2), np.int64)
    if arr.ndim != 2 or arr.shape[1] != 2 or not np.issubdtype(arr.dtype, np.integer):
        raise ValueError(f"island_links must be a (K, 2) array of body indices, got shape "
                         f"{arr.shape} of {arr.dtype}")
    if arr.min() < 0 or arr.max() >= count:
        raise IndexError(f"island_links: body indices must be in [0, {count - 1}], got "
                         f"{int(arr.min())} to {int(arr.max())}")
    return arr.astype(np.int64)
