"""The impulse history: what each contact needed last step, found again by its key.

Warm starting (Catto, GDC 2006; Box2D's ``b2WarmStartContactsTask``) begins each contact from
the impulse that the same contact (same key, ``pointmass.keys``) needed in the previous step,
so a resting pile or a loaded chain is already solved when the passes begin: measured, a
5-sphere stack kept closing at 0.1 m/s after 10 cold passes and needed ~70 passes per step to
rest; warm started, it rests with one pass.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def _find_rows(old_keys, order, rank, keys, out):
    """out[c] = the row of keys[c] in the sorted ``old_keys``, or -1.

    A generator emits its contacts in nearly the same order every step, so the contact after
    one found at the old emission position e is most likely the one kept at e + 1: ``rank``
    (emission position -> sorted row) and ``order`` (its inverse) let that guess be checked
    first, with a binary search only where it fails (a contact made or broken). Measured on the
    10 000-sphere pit (35 000 contacts, keys in short per-particle runs), the whole recall:
    1.75 ms a step with a binary search per run, 0.76 ms guessed. Without ``order`` (empty),
    every key is searched; the answer is the same either way (keys are unique)."""
    n_old = old_keys.shape[0]
    hinted = order.shape[0] == n_old
    e = 0
    for c in range(keys.shape[0]):
        key = keys[c]
        out[c] = -1
        if key < 0:
            continue
        if hinted and e < n_old and old_keys[rank[e]] == key:
            out[c] = rank[e]
            e += 1
            continue
        lo = 0
        hi = n_old
        while lo < hi:
            mid = (lo + hi) >> 1
            if old_keys[mid] < key:
                lo = mid + 1
            else:
                hi = mid
        if lo < n_old and old_keys[lo] == key:
            out[c] = lo
            if hinted:
                e = order[lo] + 1


@njit(cache=True, nogil=True)
def _sort_by_recalled_rows(keys, rows, old_keys, order):
    """Fill ``order`` with the permutation that sorts ``keys`` (all >= 0, unique), built from
    where ``recall`` found them among the sorted ``old_keys`` (``rows``, -1: new): the contacts
    found come out in their old rows' order, which is their keys' order; only the new ones are
    sorted, then the two runs are merged. Linear in the contacts but for the few new ones (the
    settled 10 000-sphere pit: 35 000 contacts, a few hundred new a step; numpy's argsort of
    their ~3 300 sorted runs took 0.56 ms). Returns False, leaving ``order`` unusable, if a
    row does not hold its contact's key (``keys`` changed since the recall) or two contacts
    share one (a custom generator's keys): the caller then sorts afresh."""
    m = keys.shape[0]
    if rows.shape[0] != m:
        return False
    at_old = np.full(old_keys.shape[0], -1, np.int64)
    fresh = 0
    for c in range(m):
        r = rows[c]
        if r >= 0:
            if old_keys[r] != keys[c] or at_old[r] >= 0:
                return False  # keys changed since the recall, or a key came twice
            at_old[r] = c
        else:
            fresh += 1
    new = np.empty(fresh, np.int64)
    f = 0
    for c in range(m):
        if rows[c] < 0:
            new[f] = c
            f += 1
    new = new[np.argsort(keys[new])]
    i = 0  # the next old row to look at
    j = 0  # the next new contact
    for o in range(m):
        while i < at_old.shape[0] and at_old[i] < 0:
            i += 1
        if j >= fresh or (i < at_old.shape[0] and old_keys[i] < keys[new[j]]):
            order[o] = at_old[i]
            i += 1
        else:
            order[o] = new[j]
            j += 1
    return True


@njit(cache=True, nogil=True)
def _in_order(order, keys, normal, sorted_keys, sorted_normal, rank):
    """sorted_keys[r] = keys[order[r]], the same for ``normal``, and rank[order[r]] = r, in
    one pass (numpy's three indexings: 0.24 ms on the settled pit's 33 000 contacts)."""
    for r in range(order.shape[0]):
        c = order[r]
        sorted_keys[r] = keys[c]
        sorted_normal[r] = normal[c]
        rank[c] = r


@njit(cache=True, nogil=True)
def _is_sorted(keys):
    for c in range(1, keys.shape[0]):
        if keys[c] <= keys[c - 1]:
            return False
    return True


@njit(cache=True, nogil=True)
def _sort_runs(keys, order):
    """Fill ``order`` with the permutation that sorts ``keys`` when they are a few ascending
    runs whose ranges do not overlap — each generator's contacts in key order, the generators
    in any order (a box's planes, then the sphere pairs): the runs put in the order of their
    first keys. Returns False (``order`` unusable) where two runs overlap or the keys have
    more than ``len(keys) // 8 + 8`` runs, for the caller to sort another way."""
    m = keys.shape[0]
    if m == 0:
        return True
    limit = m // 8 + 8
    starts = np.empty(limit + 1, np.int64)
    runs = 1
    starts[0] = 0
    for c in range(1, m):
        if keys[c] <= keys[c - 1]:
            if runs == limit:
                return False
            starts[runs] = c
            runs += 1
    starts[runs] = m
    firsts = np.empty(runs, np.int64)
    for r in range(runs):
        firsts[r] = keys[starts[r]]
    by_first = np.argsort(firsts)
    o = 0
    for q in range(runs):
        r = by_first[q]
        if q > 0 and keys[order[o - 1]] >= firsts[r]:
            return False  # this run begins before the last one ended: they interleave
        for c in range(starts[r], starts[r + 1]):
            order[o] = c
            o += 1
    return True


@njit(cache=True, nogil=True)
def _recall_into(old_keys, order, rank, old_normal, old_tangent, keys, normal, tangent, rows):
    """``recall``'s work in one compiled call: zero ``normal`` and ``tangent``, find each key's
    old row (``_find_rows``) into ``rows`` (-1: new) and copy what it kept (``old_tangent``
    with no rows: none kept)."""
    _find_rows(old_keys, order, rank, keys, rows)
    tangents = old_tangent.shape[0] > 0
    for c in range(keys.shape[0]):
        normal[c] = 0.0
        for k in range(tangent.shape[1]):
            tangent[c, k] = 0.0
        r = rows[c]
        if r >= 0:
            normal[c] = old_normal[r]
            if tangents:
                for k in range(tangent.shape[1]):
                    tangent[c, k] = old_tangent[r, k]


@njit(cache=True, nogil=True)
def _key_state(keys):
    """0: every key is ≥ 0 and the keys are already sorted (``keep``'s usual case, where the
    history is a copy of what it is given: made in Python, as numba boxes each array it
    returns, ~2.5 µs apiece, and the five this case returned were ~8 % of a tiny world's
    step); 1: every key ≥ 0, not sorted; 2: some key < 0 (no identity: not kept)."""
    state = 0
    for c in range(keys.shape[0]):
        if keys[c] < 0:
            return 2
        if c > 0 and keys[c] <= keys[c - 1]:
            state = 1
    return state


@njit(cache=True, nogil=True)
def _sort_order(keys, recalled, old_keys, order):
    """Fill ``order`` with the permutation that sorts ``keys`` (all ≥ 0), the cheapest way
    that applies, in one compiled call: none needed; the generators' runs in another order
    (``_sort_runs``; the settled 10 000-sphere pit: 0.16 ms a step found among the old rows,
    0.055 as runs); found among the old rows (``_sort_by_recalled_rows``, ``recalled``: where
    ``recall`` found the keys, empty when it did not); else a stable sort."""
    m = keys.shape[0]
    if _is_sorted(keys):
        for c in range(m):
            order[c] = c
        return
    if _sort_runs(keys, order):
        return
    if recalled.shape[0] == m and _sort_by_recalled_rows(keys, recalled, old_keys, order):
        return
    order[:] = np.argsort(keys, kind="mergesort")  # stable: numpy's "stable" permutation


_NO_TANGENT = np.zeros((0, 3))

#: The empty history's arrays, shared (with no element, nothing can be written into them): a
#: world whose solver clears the history every step (nothing touching) allocates nothing for it.
_EMPTY_KEYS = np.zeros(0, np.int64)
_EMPTY_IMPULSES = np.zeros(0)


class ImpulseHistory:
    """Keys → (normal impulse [N·s], friction impulse [N·s] (3,)) kept from the last step."""

    def __init__(self) -> None:
        self._keys = _EMPTY_KEYS
        self._normal = _EMPTY_IMPULSES
        self._tangent: np.ndarray | None = None
        # Where each kept contact stood in the order it was given to ``keep`` (sorted row ->
        # position, and the inverse); empty after pick, merge or restore (no guessing then).
        self._order = self._rank = _EMPTY_KEYS
        # The old rows where ``recall`` last found its keys (-1: new), for ``keep``'s sort.
        self._recalled: np.ndarray | None = None

    def __len__(self) -> int:
        return int(self._keys.shape[0])

    def clear(self) -> None:
        """Forget everything (after a reset, so a replay is bit-identical to the first run)."""
        if self._keys.shape[0] or self._order.shape[0] or self._tangent is not None:
            self.__init__()

    def snapshot(self) -> tuple:
        """What is kept now, to ``restore`` (the world undoes a step that blew up)."""
        return self._keys, self._normal, self._tangent

    def restore(self, snap: tuple) -> None:
        self._keys, self._normal, self._tangent = snap
        self._order = self._rank = _EMPTY_KEYS
        self._recalled = None

    @property
    def keys(self) -> np.ndarray:
        """The keys kept, sorted (M,), int64 (read only)."""
        return self._keys

    def pick(self, rows: np.ndarray) -> ImpulseHistory:
        """A new history with the entries where ``rows`` (bool, one per key) is True."""
        out = ImpulseHistory()
        out._keys = self._keys[rows]
        out._normal = self._normal[rows]
        out._tangent = self._tangent[rows] if self._tangent is not None else None
        return out

    def merge(self, other: ImpulseHistory) -> None:
        """Add ``other``'s entries (a key kept in both keeps this history's impulses): the
        warm start of bodies that wake joins that of the bodies already awake."""
        if len(other) == 0:
            return
        new = ~np.isin(other._keys, self._keys)
        keys = np.concatenate([self._keys, other._keys[new]])
        normal = np.concatenate([self._normal, other._normal[new]])
        tangents = [t if t is not None else np.zeros((len(h), 3))
                    for h, t in ((self, self._tangent), (other, other._tangent))]
        tangent = None if self._tangent is None and other._tangent is None else \
            np.concatenate([tangents[0], tangents[1][new]])
        order = np.argsort(keys, kind="stable")
        self._keys, self._normal = keys[order], normal[order]
        self._order = self._rank = _EMPTY_KEYS
        self._recalled = None
        self._tangent = tangent[order] if tangent is not None else None

    def recall(self, keys: np.ndarray, normal: np.ndarray, tangent: np.ndarray) -> None:
        """Fill ``normal`` (M,) and ``tangent`` (M, 3) with the impulses kept for ``keys`` (0
        for a contact that is new or has no key)."""
        self._recalled = None
        if self._keys.shape[0] == 0:
            normal[:] = 0.0
            tangent[:] = 0.0
            return
        rows = np.empty(keys.shape[0], np.int64)
        _recall_into(self._keys, self._order, self._rank, self._normal,
                     _NO_TANGENT if self._tangent is None else self._tangent, keys, normal,
                     tangent, rows)
        self._recalled = rows

    def keep(self, keys: np.ndarray, normal: np.ndarray, tangent: np.ndarray | None) -> None:
        """Keep this step's impulses of the keyed contacts, sorted by key (``tangent`` None:
        no friction anywhere, nothing to keep)."""
        state = _key_state(keys)
        if state == 0:
            m = keys.shape[0]
            self._recalled = None
            self._keys, self._normal = keys.copy(), normal.copy()
            self._tangent = None if tangent is None else tangent.copy()
            self._order, self._rank = np.arange(m), np.arange(m)
            return
        if state == 2:
            keyed = keys >= 0
            keys, normal = keys[keyed], normal[keyed]
            tangent = tangent[keyed] if tangent is not None else None
            if self._recalled is not None and self._recalled.shape == keyed.shape:
                self._recalled = self._recalled[keyed]  # the rows of the keys kept
        order = np.empty(keys.shape[0], np.int64)
        _sort_order(keys, _EMPTY_KEYS if self._recalled is None else self._recalled,
                    self._keys, order)
        self._recalled = None
        self._order = order
        self._rank = np.empty_like(order)
        self._keys = np.empty_like(keys)
        self._normal = np.empty_like(normal)
        _in_order(order, keys, normal, self._keys, self._normal, self._rank)
        self._tangent = tangent[order] if tangent is not None else None
