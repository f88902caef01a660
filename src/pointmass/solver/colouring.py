"""Graph colouring of the contact rows, so the sweep's passes run on every core.

Two rows that share no particle can be solved at the same time: each writes only its own two
particles. A greedy colouring in row order (Box2D v3's ``constraint_graph.c`` does the same
with 24 colours and an overflow set solved serially) puts every row in the lowest colour that
neither of its particles has used yet; a row finding none of the ``MAX_COLOURS`` goes to the
overflow group. The rows of one colour are then solved with ``prange``; the colours one after
the other. Scenery (b = -1) takes no colour, so a sphere's floor and wall contacts colour with
its pair contacts freely.

Determinism: the colouring depends only on the rows' order and particles, and within a colour
no two rows touch the same particle, so the result is the same bits for any thread count. The
order differs from the serial sweep's row order, so it is used only where it pays (the solver's
``PARALLEL_MIN_CONTACTS``): Gauss–Seidel in another order converges to the same solution, but
impacts (Newton's cradle's sequential propagation) never run coloured.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np
from numba import njit

#: Colours before the overflow group (Box2D v3: 24). A sphere in a pile has at most 12
#: neighbours, so greedy colouring needs at most 23; the overflow is for unusual sets.
MAX_COLOURS = 24

#: Rows grouped by colour: ``order`` (M,) the rows, colour by colour (row order kept within a
#: colour), ``starts`` (colours + 2,) where each colour begins in ``order``, the overflow
#: group last (``starts[-2]:starts[-1]``, solved serially).
Colouring = namedtuple("Colouring", "order starts")


@njit(cache=True, nogil=True)
def _colour_rows(ca, cb, n_particles, max_colours, colour):
    """colour[c] for each row, greedy in row order (``max_colours``: the overflow).
    Returns how many rows each colour has, shape (max_colours + 1,)."""
    used = np.zeros(n_particles, np.int64)  # a bit per colour already taken at each particle
    counts = np.zeros(max_colours + 1, np.int64)
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        taken = used[a]
        if b >= 0:
            taken |= used[b]
        pick = max_colours
        for k in range(max_colours):
            if not (taken >> k) & 1:
                pick = k
                break
        colour[c] = pick
        counts[pick] += 1
        if pick < max_colours:
            used[a] |= 1 << pick
            if b >= 0:
                used[b] |= 1 << pick
    return counts


@njit(cache=True, nogil=True)
def _group(colour, counts, order, starts):
    """Counting sort of the rows by colour, stable (row order kept within a colour)."""
    starts[0] = 0
    for k in range(counts.shape[0]):
        starts[k + 1] = starts[k] + counts[k]
    fill = starts[:-1].copy()
    for c in range(colour.shape[0]):
        order[fill[colour[c]]] = c
        fill[colour[c]] += 1


def colour_rows(ca: np.ndarray, cb: np.ndarray, n_particles: int,
                max_colours: int = MAX_COLOURS) -> Colouring:
    """Colour the rows (a, b) (M,) of contacts between ``n_particles`` particles (b = -1:
    scenery) greedily in row order; see the module docstring."""
    if not 1 <= max_colours <= 62:
        raise ValueError(f"max_colours must be an integer in [1, 62], got {max_colours!r}")
    m = ca.shape[0]
    colour = np.empty(m, np.int64)
    counts = _colour_rows(ca, cb, int(n_particles), int(max_colours), colour)
    order = np.empty(m, np.int64)
    starts = np.empty(max_colours + 2, np.int64)
    _group(colour, counts, order, starts)
    return Colouring(order, starts)
