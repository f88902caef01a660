"""Sphere–sphere pairs: a grid finds the candidates, a list keeps them between steps.

**Candidates** (``_candidates``): every pair closer than its radii plus its margin plus both
spheres' *budgets* (below), found on a uniform grid (cell = largest diameter + margin + twice
a typical sphere's budget, so a pair of typical spheres is at most one cell apart; the few
faster ones search as far around themselves as they need): dense over the spheres' bounding
box when that is small, a spatial hash when they are spread far apart, so the search costs
O(N) for evenly spread spheres instead of the O(N²) pair loop of Cyclone's demos.

**The list** (``PairList``; a Verlet list, as molecular dynamics keeps its neighbours): the
candidates of the last search and the positions it saw. A step needs the pairs closer than their
radii plus margin plus how far each sphere may travel in the step (its sweep, |v|·dt); since the
search, a pair has come closer by at most its two spheres' displacements. Each sphere gets a
budget at the search (its sweep then for ``SKIN_STEPS`` steps, plus half the skin) and the list
holds the pairs within radii + margin + both budgets; it serves while every sphere's
displacement plus sweep stays within its budget, and the grid is searched again when one does
not. Budgets are per sphere so that a fast one (a ball in flight) does not widen every pair's
reach. A scene whose list is searched again every step anyway (a pour: something always falls
fast) goes without the skin, which would only lengthen the list, and tries it again every few
searches. Measured on the 10 000-sphere pit between 5 and 10 s: a search ~2 ms, checking the
listed pairs ~0.55 ms, a search every ~3 steps (the pile still flows); the pairs' share of a
step 2.5 -> 1.6 ms. (Searching again only the spheres that used up their budgets was measured
and not kept: the others' budgets then run out one by one, and in a landing or a pour a thousand
are late every step; benchmarks/RESULTS.md, session 22.)

**Contacts** (``pair_contacts``): each step checks every listed pair exactly and writes the
contacts in key order (lower index, then higher). So the contacts are the same whether the list
is fresh or old: a trajectory does not depend on when the list was last rebuilt (tested).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._sort import counting_sort
from .keys import pair_key

#: The list's skin beyond what the sweeps need at the search, as a fraction of the largest
#: radius: the room spheres have to move before the grid is searched again.
SKIN_FRACTION = 0.2
#: ... and each sphere may travel this many steps at its speed of the search, the steps after
#: the first within another half skin: one whose budget is its sweep of one step has used it
#: up after a few steps of steady motion, and the whole list is searched again (measured on
#: the settled 10 000-sphere pit, steps 300-600: 317 searches with 1, 185 with 3, 120 with 6;
#: the pairs stage 2.2-2.7 -> 1.7-2.2 ms a step with 3 or 6). The cap keeps a fast ball from
#: widening the grid's cells, which the fastest sphere's budget sets for all (a pour).
SKIN_STEPS = 3
#: While every list is searched again at its next step, searches go without the skin; every
#: this many such searches the skin is tried again.
SKIN_RETRY = 8

#: The grid's cells are sized for the budgets of all but the fastest spheres, this quantile of
#: them; the faster ones search as far around themselves as they need (``_candidates``).
SLOW_QUANTILE = 0.97
#: ... where the cells shrink to at most this fraction of the cells for the fastest sphere.
SLOW_CELL_GAIN = 0.8

#: The grid is dense (a slot for every cell of the spheres' bounding box, so the three cells
#: along z next to a cell are one run of the sorted spheres) when the box has at most this many
#: cells per sphere; spheres spread wider go to the spatial hash (a bucket per neighbour cell,
#: each checked for other cells sharing it). An empty cell costs a few ns (its slot is cleared
#: and summed), a hashed sphere ~300 ns more than a dense one (the settled 10 000-sphere pit:
#: 5.5 against 2.3 ms a search). Measured on the 10 000-ball pour, whose waiting balls are
#: parked 20 m below the box: with cells for its fastest ball (21 cells a sphere) 12.0 ms a
#: search hashed, 7.3 dense; with cells for its typical ball (~48 cells a sphere) 13.2 hashed,
#: 5.0 dense.
DENSE_CELLS_PER_SPHERE = 64


@njit(cache=True, inline="always")
def _cell_hash(ix, iy, iz, mask):
    h = (ix * 92837111) ^ (iy * 689287499) ^ (iz * 283923481)
    return h & mask


@njit(cache=True, nogil=True)
def _grid(pos, idx, cell_size):
    """Bin the spheres ``idx`` into cells of side ``cell_size``: their cells (n, 3), each
    one's slot in the cell-sorted order (a stable counting sort: in a cell, index order), the
    sorted order itself, the slot ranges per bucket (``starts``), and the grid's shape
    (``low`` corner and ``span`` cells per axis; span[0] == 0: hashed, not dense)."""
    n = idx.shape[0]
    inv = 1.0 / cell_size
    cells = np.empty((n, 3), np.int64)
    low = np.empty(3, np.int64)
    high = np.empty(3, np.int64)
    for c in range(3):
        low[c] = np.iinfo(np.int64).max
        high[c] = np.iinfo(np.int64).min
    for k in range(n):
        i = idx[k]
        for c in range(3):
            cell = math.floor(pos[i, c] * inv)
            cells[k, c] = cell
            low[c] = min(low[c], cell)
            high[c] = max(high[c], cell)
    span = np.zeros(3, np.int64)
    volume = 1.0
    for c in range(3):
        volume *= float(high[c] - low[c] + 1)
    keys = np.empty(n, np.int64)
    if volume <= DENSE_CELLS_PER_SPHERE * n + 64:
        for c in range(3):
            span[c] = high[c] - low[c] + 1
        table = span[0] * span[1] * span[2]
        for k in range(n):
            keys[k] = (((cells[k, 0] - low[0]) * span[1] + cells[k, 1] - low[1]) * span[2]
                       + cells[k, 2] - low[2])
    else:
        table = 1
        while table < 2 * n:
            table *= 2
        for k in range(n):
            keys[k] = _cell_hash(cells[k, 0], cells[k, 1], cells[k, 2], table - 1)
    order, starts = counting_sort(keys, table)
    slot = np.empty(n, np.int64)
    for s in range(n):
        slot[order[s]] = s
    return cells, slot, order, starts, low, span


@njit(cache=True, nogil=True)
def _neighbour_runs(cells, slot, starts, low, span, k, runs):
    """The runs of sorted slots holding sphere k's own cell (the spheres after k in it) and
    its 13 "forward" neighbour cells, into ``runs`` rows (first, stop, cx, cy, cz); returns
    how many. Dense: five runs (a cell's z neighbours are adjacent slots), cell column
    unused; hashed: a bucket per cell, with the cell to check its spheres against."""
    cx, cy, cz = cells[k, 0], cells[k, 1], cells[k, 2]
    count = 0
    if span[0] > 0:
        x, y, z = cx - low[0], cy - low[1], cz - low[2]
        # Own cell after k, then the cell at z + 1: adjacent slots.
        base = (x * span[1] + y) * span[2] + z
        runs[count, 0] = slot[k] + 1
        runs[count, 1] = starts[base + 2] if z + 1 < span[2] else starts[base + 1]
        count += 1
        z0 = max(z - 1, 0)
        z1 = min(z + 1, span[2] - 1)
        for dx, dy in ((0, 1), (1, -1), (1, 0), (1, 1)):
            if x + dx >= span[0] or y + dy < 0 or y + dy >= span[1]:
                continue
            row = ((x + dx) * span[1] + y + dy) * span[2]
            runs[count, 0] = starts[row + z0]
            runs[count, 1] = starts[row + z1 + 1]
            count += 1
        return count
    mask = starts.shape[0] - 2
    for dx in range(-1, 2):
        for dy in range(-1, 2):
            for dz in range(-1, 2):
                forward = dx > 0 or (dx == 0 and (dy > 0 or (dy == 0 and dz > 0)))
                own = dx == 0 and dy == 0 and dz == 0
                if not (forward or own):
                    continue
                bucket = _cell_hash(cx + dx, cy + dy, cz + dz, mask)
                runs[count, 0] = slot[k] + 1 if own else starts[bucket]
                runs[count, 1] = starts[bucket + 1]
                runs[count, 2] = cx + dx
                runs[count, 3] = cy + dy
                runs[count, 4] = cz + dz
                count += 1
    return count


@njit(cache=True, inline="always")
def _margin_of(ri, rj, margin, margin_fraction):
    """A pair's contact margin [m]: ``margin`` when ≥ 0, else the fraction of the larger radius."""
    return margin if margin >= 0.0 else margin_fraction * max(ri, rj)


@njit(cache=True, inline="always")
def _with_room(lo, hi, found, more):
    """(lo, hi) with room for ``more`` pairs after the first ``found`` (doubled as needed)."""
    if found + more > lo.shape[0]:
        grow = max(lo.shape[0], more)
        lo = np.concatenate((lo, np.empty(grow, np.int64)))
        hi = np.concatenate((hi, np.empty(grow, np.int64)))
    return lo, hi


@njit(cache=True, nogil=True)
def _fast_pairs(pos, radius, idx, budget, slow, cell_size, margin, margin_fraction, cells,
                starts, low, span, order, sj, sp, sr, sb, ss, lo, hi, found):
    """``_candidates``' pairs of its fast spheres (budget above ``slow``): each searches every
    cell within its reach around it (the largest radius, margin and budget on the other side),
    keeping slow partners and fast ones of a higher index. Appends to (lo, hi) from ``found``;
    returns them and the new count."""
    n = idx.shape[0]
    largest_r = 0.0
    largest_b = 0.0
    for k in range(n):
        largest_r = max(largest_r, radius[idx[k]])
        largest_b = max(largest_b, budget[k])
    dense = span[0] > 0
    mask = starts.shape[0] - 2
    for k in range(n):
        bi = budget[k]
        if bi <= slow:
            continue
        i = idx[k]
        px, py, pz = pos[i, 0], pos[i, 1], pos[i, 2]
        ri = radius[i]
        extent = ri + largest_r + _margin_of(ri, largest_r, margin, margin_fraction) \
            + bi + largest_b
        near = math.ceil(extent / cell_size)  # cells each way
        cx, cy, cz = cells[k, 0], cells[k, 1], cells[k, 2]
        for dx in range(-near, near + 1):
            for dy in range(-near, near + 1):
                if dense:
                    x, y = cx + dx - low[0], cy + dy - low[1]
                    if x < 0 or x >= span[0] or y < 0 or y >= span[1]:
                        continue
                    row = (x * span[1] + y) * span[2]
                    z0 = max(cz - near - low[2], 0)
                    z1 = min(cz + near - low[2], span[2] - 1)
                    if z0 > z1:
                        continue
                    bands = 1
                else:
                    bands = 2 * near + 1
                for band in range(bands):
                    if dense:
                        first, stop = starts[row + z0], starts[row + z1 + 1]
                    else:
                        bucket = _cell_hash(cx + dx, cy + dy, cz - near + band, mask)
                        first, stop = starts[bucket], starts[bucket + 1]
                    lo, hi = _with_room(lo, hi, found, stop - first)
                    for s in range(first, stop):
                        if not dense:  # only the bucket's spheres of this very cell
                            m = order[s]
                            if (cells[m, 0] != cx + dx or cells[m, 1] != cy + dy
                                    or cells[m, 2] != cz - near + band):
                                continue
                        j = sj[s]
                        ddx = px - sp[s, 0]
                        ddy = py - sp[s, 1]
                        ddz = pz - sp[s, 2]
                        reach = ri + sr[s] + _margin_of(ri, sr[s], margin, margin_fraction) \
                            + bi + sb[s]
                        lo[found] = min(i, j)
                        hi[found] = max(i, j)
                        found += ((ddx * ddx + ddy * ddy + ddz * ddz < reach * reach)
                                  & (ss[s] | (j > i)))
    return lo, hi, found


@njit(cache=True, nogil=True)
def _candidates(pos, radius, idx, count, cell_size, margin, margin_fraction, budget, slow):
    """The pairs of ``idx`` closer than their radii + margin + both spheres' ``budget`` (n,)
    [m], as (lo, hi) index arrays in key order; ``count`` is the number of particles (the
    keys' range).

    The cells are sized for spheres whose budget is at most ``slow`` [m]: a pair of those is
    at most one cell apart and found from the 13 forward neighbour cells of one of them. A
    faster sphere looks for all its partners itself, as far around as its reach needs (a
    pair of two fast ones from the lower index): in a pour a few falling balls would
    otherwise widen every cell (the 10 000-ball pour: cells for the fastest ball hold ~4×
    the candidates of cells for the typical one).

    The spheres are copied in cell order, so a neighbour cell's spheres are read from adjacent
    memory (measured on the settled 10 000-sphere pit, without a skin: 2.3 ms, against 5.5 for
    a hashed bucket per neighbour cell and reads through the index; 1.7 ms once the candidate
    test lost its branch)."""
    n = idx.shape[0]
    cells, slot, order, starts, low, span = _grid(pos, idx, cell_size)
    dense = span[0] > 0
    sj = np.empty(n, np.int64)
    sp = np.empty((n, 3))
    sr = np.empty(n)
    sb = np.empty(n)
    ss = np.empty(n, np.bool_)  # slow: found by the forward cells
    for s in range(n):
        j = idx[order[s]]
        sj[s] = j
        sp[s, 0] = pos[j, 0]
        sp[s, 1] = pos[j, 1]
        sp[s, 2] = pos[j, 2]
        sr[s] = radius[j]
        sb[s] = budget[order[s]]
        ss[s] = budget[order[s]] <= slow
    runs = np.empty((14, 5), np.int64)
    lo = np.empty(8 * n + 16, np.int64)
    hi = np.empty(8 * n + 16, np.int64)
    found = 0
    fast = 0
    for k in range(n):
        bi = budget[k]
        if bi > slow:
            fast += 1
            continue  # its pairs are its own search's (below)
        i = idx[k]
        px, py, pz = pos[i, 0], pos[i, 1], pos[i, 2]
        ri = radius[i]
        # Own cell (later spheres only) and the 13 "forward" neighbour cells: each pair once.
        for r in range(_neighbour_runs(cells, slot, starts, low, span, k, runs)):
            first, stop = runs[r, 0], runs[r, 1]
            lo, hi = _with_room(lo, hi, found, stop - first)
            for s in range(first, stop):
                if not dense:  # a hashed bucket may hold other cells: only the run's own
                    m = order[s]
                    if (cells[m, 0] != runs[r, 2] or cells[m, 1] != runs[r, 3]
                            or cells[m, 2] != runs[r, 4]):
                        continue
                ddx = px - sp[s, 0]
                ddy = py - sp[s, 1]
                ddz = pz - sp[s, 2]
                reach = ri + sr[s] + _margin_of(ri, sr[s], margin, margin_fraction) + bi + sb[s]
                # Written always, kept by the count: no branch to mispredict on the ~1 in 5
                # candidates that are near (the settled pit's search: 2.4 -> 1.7 ms). A fast
                # partner is left to its own search.
                j = sj[s]
                lo[found] = min(i, j)
                hi[found] = max(i, j)
                found += (ddx * ddx + ddy * ddy + ddz * ddz < reach * reach) & ss[s]
    if fast:
        # np.int64: ``found`` starts as the constant 0, which would give _fast_pairs a second
        # compiled copy for Literal[int](0) (see rigid.box_box.box_box_into).
        lo, hi, found = _fast_pairs(pos, radius, idx, budget, slow, cell_size, margin,
                                    margin_fraction, cells, starts, low, span, order, sj, sp,
                                    sr, sb, ss, lo, hi, np.int64(found))
    # Key order: by hi, then stably by lo (two counting sorts, linear in pairs + particles).
    by_hi, _ = counting_sort(hi[:found], count)
    lo_sorted = lo[by_hi]
    by_lo, _ = counting_sort(lo_sorted, count)
    final = by_hi[by_lo]
    return lo[final], hi[final]


@njit(cache=True, nogil=True)
def _within_budgets(pos, idx, seen, sweep, budget):
    """Whether every sphere of ``idx`` has moved from ``seen`` (n, 3) plus may travel in the
    step (``sweep`` [m] per particle) at most its ``budget`` (n,) [m] (False for a position
    that is not finite)."""
    for k in range(idx.shape[0]):
        i = idx[k]
        dx = pos[i, 0] - seen[k, 0]
        dy = pos[i, 1] - seen[k, 1]
        dz = pos[i, 2] - seen[k, 2]
        if not math.sqrt(dx * dx + dy * dy + dz * dz) + sweep[i] <= budget[k]:
            return False
    return True


@njit(cache=True, nogil=True)
def pair_contacts(pos, vel, radius, inv_mass, lo, hi, restitution, margin, margin_fraction,
                  sweep, dt, out_a, out_b, out_n, out_pen, out_rest, out_key, start):
    """Check the listed pairs (lo, hi) exactly: a contact where the pair is closer than its
    radii plus margin, or beyond it but touching within the step (``sweep`` [m] per particle,
    |v|·dt, with the normal at the moment of touching); written from ``start`` in list order
    (the buffer must have room for every pair). Returns the new count."""
    count = start
    for c in range(lo.shape[0]):
        i = lo[c]
        j = hi[c]
        if inv_mass[i] == 0.0 and inv_mass[j] == 0.0:
            continue
        ddx = pos[i, 0] - pos[j, 0]
        ddy = pos[i, 1] - pos[j, 1]
        ddz = pos[i, 2] - pos[j, 2]
        ri = radius[i]
        rj = radius[j]
        reach = ri + rj
        catch = reach + _margin_of(ri, rj, margin, margin_fraction)
        d2 = ddx * ddx + ddy * ddy + ddz * ddz
        if d2 >= (catch + sweep[i] + sweep[j]) ** 2:
            continue
        nx, ny, nz = ddx, ddy, ddz
        if d2 >= catch * catch:
            # Beyond the margin but fast: a contact only if the pair would touch within the
            # step, with the normal at that moment (a pair that passes by is not deflected by
            # a ghost contact).
            nx, ny, nz = _impact_direction(ddx, ddy, ddz, vel, i, j, reach, dt)
            if nx == 0.0 and ny == 0.0 and nz == 0.0:
                continue
        dist = math.sqrt(nx * nx + ny * ny + nz * nz)
        if dist > 0.0:  # from b (hi) to a (lo)
            out_n[count, 0] = nx / dist
            out_n[count, 1] = ny / dist
            out_n[count, 2] = nz / dist
        else:  # same centre: any direction separates them; pick up
            out_n[count, 0] = 0.0
            out_n[count, 1] = 1.0
            out_n[count, 2] = 0.0
        # The gap along that normal (the separation it must not close).
        along = ddx * out_n[count, 0] + ddy * out_n[count, 1] + ddz * out_n[count, 2]
        out_pen[count] = reach - along
        out_rest[count] = restitution
        out_a[count] = i
        out_b[count] = j
        out_key[count] = pair_key(i, j)
        count += 1
    return count


@njit(cache=True, inline="always")
def _impact_direction(dx, dy, dz, vel, i, j, reach, dt):
    """Where i is relative to j when they first touch within the next step, moving apart by
    d = (dx, dy, dz) + u·t with u = v_i - v_j; (0, 0, 0) if they do not touch by t = dt."""
    ux = vel[i, 0] - vel[j, 0]
    uy = vel[i, 1] - vel[j, 1]
    uz = vel[i, 2] - vel[j, 2]
    uu = ux * ux + uy * uy + uz * uz
    du = dx * ux + dy * uy + dz * uz
    if uu == 0.0 or du >= 0.0:
        return 0.0, 0.0, 0.0  # not approaching
    # |d + u·t|² = reach²: uu·t² + 2·du·t + (d·d - reach²) = 0, the first root.
    c = dx * dx + dy * dy + dz * dz - reach * reach
    disc = du * du - uu * c
    if disc < 0.0:
        return 0.0, 0.0, 0.0  # the closest approach stays wider than the radii
    t = (-du - math.sqrt(disc)) / uu
    if t > dt:
        return 0.0, 0.0, 0.0  # touches only after this step: found next step
    return dx + ux * t, dy + uy * t, dz + uz * t


@njit(cache=True, nogil=True)
def sweep_lengths(velocity, dt):
    """|v|·dt per particle [m]: how far each may travel in the coming step."""
    out = np.empty(velocity.shape[0])
    for i in range(velocity.shape[0]):
        out[i] = math.sqrt(velocity[i, 0] ** 2 + velocity[i, 1] ** 2 + velocity[i, 2] ** 2) * dt
    return out


class PairList:
    """The candidate pairs of the last grid search and what it saw (see the module docstring).

    ``pairs`` returns the list, searching again only when it may be missing a pair; ``clear``
    forgets it (the next call searches)."""

    def __init__(self) -> None:
        #: Grid searches so far (for benchmarks and tests).
        self.searches = 0
        self.clear()

    def clear(self) -> None:
        self.lo = np.zeros(0, np.int64)
        self.hi = np.zeros(0, np.int64)
        self._idx: np.ndarray | None = None
        self._radius = np.zeros(0)
        self._seen = np.zeros((0, 3))
        self._budget = np.zeros(0)  # how far each sphere may move + travel [m] (see pairs)
        self._margin = (0.0, 0.0)
        self._served = SKIN_RETRY  # steps the list has served
        self._misses = 0  # searches in a row whose list served only its own step

    def pairs(self, position, radius, idx, margin: float, margin_fraction: float,
              sweep: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The candidate pairs (lo, hi) of the spheres ``idx`` for a step whose spheres may
        travel ``sweep`` [m] each; ``margin`` ≥ 0 [m], or < 0 for ``margin_fraction`` × the
        larger radius of each pair."""
        if self._fits(position, radius, idx, margin, margin_fraction, sweep):
            self._served += 1
            return self.lo, self.hi
        # Each sphere's budget: its own sweep now, for ``SKIN_STEPS`` steps (a fast one does
        # not widen every pair's reach), plus half the skin. A scene whose list is searched
        # again every step anyway (a pour: something always falls fast) gets neither, which
        # would only lengthen the list, trying them again every ``SKIN_RETRY`` searches.
        self._misses = self._misses + 1 if self._served <= 1 else 0
        largest = float(radius[idx].max())
        skin = SKIN_FRACTION * largest if self._misses % SKIN_RETRY == 0 else 0.0
        own = sweep[idx]
        budget = own
        if skin > 0.0:  # the travel of the steps after this one, at most another half skin
            budget = own + np.minimum((SKIN_STEPS - 1) * own, 0.5 * skin) + 0.5 * skin
        reach = margin if margin >= 0.0 else margin_fraction * largest
        # Cells for the typical sphere's budget (``SLOW_QUANTILE``): a pair of two such is at
        # most one cell apart; the faster ones search around themselves (``_candidates``).
        # Only where that shrinks the cells by a fifth: the fast ones' searches cost more than
        # slightly smaller cells save (the 10 000-sphere pit's landing: pairs 2.4-2.6 -> 2.7-3.0
        # ms a step with cells 13 % smaller; the 10 000-ball pour's search 6.6 -> 5.0 ms with
        # cells 24 % smaller).
        # Nor where the smaller cells would take the grid from dense to hashed.
        def cell_for(b: float) -> float:  # the whole reach of a pair of budgets ≤ b
            return 2.0 * (largest + b) + reach

        fastest = float(budget.max())
        slow = float(np.quantile(budget, SLOW_QUANTILE))
        if cell_for(slow) > SLOW_CELL_GAIN * cell_for(fastest):
            slow = fastest
        elif slow < fastest:
            box = np.ptp(position[idx], axis=0)
            limit = DENSE_CELLS_PER_SPHERE * idx.shape[0]
            slow_cells = np.prod(box / cell_for(slow) + 1.0)
            if slow_cells > limit >= np.prod(box / cell_for(fastest) + 1.0):
                slow = fastest
        cell = cell_for(slow)
        self.lo, self.hi = _candidates(position, radius, idx, position.shape[0], cell,
                                       float(margin), float(margin_fraction), budget, slow)
        self._idx = idx.copy()
        self._radius = radius[idx].copy()
        self._seen = position[idx].copy()
        # A thousandth kept back for rounding: the distances are computed, not exact, and a
        # pair right at the list's edge must not be lost to an ulp.
        self._budget = 0.999 * budget
        self._margin = (float(margin), float(margin_fraction))
        self._served = 1
        self.searches += 1
        return self.lo, self.hi

    def _fits(self, position, radius, idx, margin, margin_fraction, sweep) -> bool:
        """Whether the list still holds every pair the step can need: the same spheres, radii
        and margin, and each sphere's move since the search plus its sweep within its budget
        (a pair missing from the list was farther apart than its radii + margin + both
        budgets, so it cannot now be closer than radii + margin + both sweeps)."""
        if self._idx is None:
            return False
        if (self._idx.shape != idx.shape or self._margin != (margin, margin_fraction)
                or not np.array_equal(self._idx, idx)
                or not np.array_equal(self._radius, radius[idx])):
            return False
        return _within_budgets(position, idx, self._seen, sweep, self._budget)
