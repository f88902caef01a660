"""Contact rows split into batches that share no particle, so the sweep's passes run on every
core (issue 9).

Particles are cut into ``SLABS`` slabs along the widest axis of the scene, each holding an
equal share of them. A row with both ends in one slab (or one end and scenery) belongs to that
slab's group; a row between neighbouring slabs s and s + 1 to the boundary group s; anything
else to the overflow. Groups in one *phase* share no particle: the slabs (phase 0), the
boundaries after even slabs (phase 1), after odd slabs (phase 2), the overflow (phase 3, one
group). A pass runs the phases in turn, the groups of a phase in parallel, and each group's
rows serially in row order: Gauss–Seidel within a group, almost the serial sweep's order.

This is Box2D v3's constraint graph colouring (``constraint_graph.c``: 24 colours and an
overflow solved serially) on blocks instead of single rows. Greedy colouring of single rows
was built first and measured (commit 9395620): 15 colours on the 10 000-sphere pit, so 15
parallel regions a pass where this has 3, and numba starts each region anew; with 2 threads on
a loaded 2-core machine its velocity pass took 4.7–12 ms against 3.6–5.4 ms on one thread.

Determinism: the grouping depends on the positions and the rows' order only, never on the
number of threads, and the groups of a phase touch disjoint particles, so the result is the
same bits for any number of threads (tests/physics/test_parallel_solver.py).
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np
from numba import njit

from .._sort import counting_sort

#: Slabs of particles for ``block_rows``: a fixed number, so the grouping (and so the result)
#: does not depend on the number of threads; enough for 16 threads at one slab each.
SLABS = 16

#: Rows grouped for parallel passes: group g is ``order[spans[g, 0]:spans[g, 1]]``, solved
#: serially in that order; phase p is the groups ``phase_starts[p]:phase_starts[p + 1]``,
#: which share no particle and run in parallel; the phases run one after the other.
Phases = namedtuple("Phases", "order spans phase_starts")


@njit(cache=True, nogil=True)
def _slab_groups(ca, cb, slab, slabs, group):
    """group[c] for each row: its slab s if both ends lie in s (scenery: a's slab), slabs + s
    for a row between slab s and s + 1, and 2·slabs for anything else (the overflow)."""
    for c in range(ca.shape[0]):
        s = slab[ca[c]]
        t = slab[cb[c]] if cb[c] >= 0 else s
        if s == t:
            group[c] = s
        elif abs(s - t) == 1:
            group[c] = slabs + min(s, t)
        else:
            group[c] = 2 * slabs


#: Bins per slab of the histogram that places the slab boundaries (``_slab_of``).
_BINS_PER_SLAB = 64


@njit(cache=True, nogil=True)
def _slab_of(position, slabs, slab):
    """slab[i] for each particle: slabs along the widest axis of ``position``, each holding
    about an equal share of the particles (a histogram of ``_BINS_PER_SLAB`` bins a slab
    places the boundaries: linear time, where ranking the particles sorted them)."""
    n = position.shape[0]
    axis = 0
    width = -1.0
    low = 0.0
    for c in range(3):
        lo = np.inf
        hi = -np.inf
        for i in range(n):
            lo = min(lo, position[i, c])
            hi = max(hi, position[i, c])
        if hi - lo > width:
            axis, width, low = c, hi - lo, lo
    bins = _BINS_PER_SLAB * slabs
    scale = bins / width if width > 0.0 else 0.0
    count = np.zeros(bins + 1, np.int64)
    for i in range(n):
        count[min(int((position[i, axis] - low) * scale), bins - 1) + 1] += 1
    for b in range(bins):
        count[b + 1] += count[b]  # count[b]: particles in bins before b
    for i in range(n):
        b = min(int((position[i, axis] - low) * scale), bins - 1)
        slab[i] = min(count[b] * slabs // n, slabs - 1)


def block_rows(ca: np.ndarray, cb: np.ndarray, position: np.ndarray,
               slabs: int = SLABS) -> Phases:
    """Group the rows (a, b) (M,) for parallel passes by slabs of particles along the widest
    axis of ``position`` (N, 3), each slab holding about an equal share of the particles: the
    rows inside each slab (phase 0, a slab per group), those between slabs s and s + 1 for
    even s (phase 1), for odd s (phase 2), and the rest (phase 3, one group, serial)."""
    if not 1 <= slabs:
        raise ValueError(f"slabs must be an integer >= 1, got {slabs!r}")
    n = position.shape[0]
    slab = np.zeros(n, np.int64)
    if n:
        _slab_of(position, slabs, slab)
    group = np.empty(ca.shape[0], np.int64)
    _slab_groups(ca, cb, slab, slabs, group)
    order, group_starts = counting_sort(group, 2 * slabs + 1)  # row order kept within a group
    # Phases over the groups: inside slabs; boundaries 0-1, 2-3, ...; 1-2, 3-4, ...; overflow.
    # The boundary groups are listed even first, then odd (a permutation of groups).
    even = list(range(slabs, 2 * slabs - 1, 2))
    odd = list(range(slabs + 1, 2 * slabs - 1, 2))
    listed = list(range(slabs)) + even + odd + [2 * slabs]
    spans = np.column_stack([group_starts[listed], group_starts[np.array(listed) + 1]])
    phase_starts = np.array([0, slabs, slabs + len(even), slabs + len(even) + len(odd),
                             len(listed)], np.int64)
    return Phases(order, np.ascontiguousarray(spans), phase_starts)
