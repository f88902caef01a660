"""The impulse history (``impulse_history.py``): what ``keep`` stores is sorted by key however
it sorts (from the rows ``recall`` found, or afresh), and ``recall`` finds every kept key."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pointmass.impulse_history import ImpulseHistory, _sort_runs


def _kept(history):
    return history.keys.copy(), history._normal.copy(), history._tangent.copy()


def _step(history, keys):
    """A step's use: recall the impulses of ``keys``, then keep new ones (impulse = key)."""
    normal = np.empty(keys.shape[0])
    tangent = np.empty((keys.shape[0], 3))
    history.recall(keys, normal, tangent)
    recalled = normal.copy()
    history.keep(keys, keys.astype(float), np.repeat(keys[:, None], 3, axis=1).astype(float))
    return recalled


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(0, 10**6), min_size=0, max_size=300, unique=True),
       st.lists(st.integers(0, 10**6), min_size=0, max_size=300, unique=True),
       st.integers(0, 2**32 - 1))
def test_keep_sorts_by_key_whether_from_recalled_rows_or_afresh(first, second, seed):
    rng = np.random.default_rng(seed)
    first = np.array(first, np.int64)
    second = np.array(second, np.int64)
    rng.shuffle(second)  # emission order is not key order
    history, fresh = ImpulseHistory(), ImpulseHistory()
    _step(history, first)
    recalled = _step(history, second)  # recall, then keep sorts from the rows it found
    fresh.keep(second, second.astype(float), np.repeat(second[:, None], 3, axis=1).astype(float))
    for mine, reference in zip(_kept(history), _kept(fresh)):
        assert np.array_equal(mine, reference)
    assert np.array_equal(history.keys, np.sort(second))
    known = np.isin(second, first)
    assert np.array_equal(recalled[known], second[known].astype(float))
    assert not recalled[~known].any()


def test_keys_changed_between_recall_and_keep_are_sorted_afresh():
    history = ImpulseHistory()
    _step(history, np.array([5, 1, 9], np.int64))
    keys = np.array([9, 5, 1], np.int64)
    normal, tangent = np.empty(3), np.empty((3, 3))
    history.recall(keys, normal, tangent)
    keys[:] = (7, 3, 2)  # the rows recall found no longer hold these keys
    history.keep(keys, np.array([7.0, 3.0, 2.0]), None)
    assert np.array_equal(history.keys, [2, 3, 7])
    assert np.array_equal(history._normal, [2.0, 3.0, 7.0])


def test_unkeyed_contacts_are_dropped_and_the_rest_sorted_from_their_rows():
    history = ImpulseHistory()
    _step(history, np.array([4, 8, 2], np.int64))
    keys = np.array([8, -1, 2, 6, -1, 4], np.int64)
    normal, tangent = np.empty(6), np.empty((6, 3))
    history.recall(keys, normal, tangent)
    assert np.array_equal(normal, [8.0, 0.0, 2.0, 0.0, 0.0, 4.0])
    history.keep(keys, np.arange(6.0), None)
    assert np.array_equal(history.keys, [2, 4, 6, 8])
    assert np.array_equal(history._normal, [2.0, 5.0, 3.0, 0.0])


def test_a_key_given_twice_is_sorted_afresh_not_lost():
    history = ImpulseHistory()
    _step(history, np.array([4, 8, 2], np.int64))
    keys = np.array([8, 4, 8, 2], np.int64)  # a custom generator's duplicate
    normal, tangent = np.empty(4), np.empty((4, 3))
    history.recall(keys, normal, tangent)
    history.keep(keys, np.arange(4.0), None)
    assert np.array_equal(history.keys, [2, 4, 8, 8])
    assert np.array_equal(history._normal, [3.0, 1.0, 0.0, 2.0])


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(0, 10**6), min_size=1, max_size=400, unique=True),
       st.integers(1, 8), st.integers(0, 2**32 - 1))
def test_generators_runs_in_any_order_are_sorted_as_runs(keys, runs, seed):
    """Each generator emits its contacts in key order, the generators in any order: ``keep``
    puts the runs in order (``_sort_runs``) and stores what a full sort would. (Runs emitted
    in descending order stay apart; in another order two may join into one that overlaps a
    third, and the sort falls back.)"""
    rng = np.random.default_rng(seed)
    keys = np.sort(np.array(keys, np.int64))
    cuts = np.sort(rng.choice(np.arange(1, keys.shape[0] + 1), min(runs, keys.shape[0]),
                              replace=False))
    pieces = np.split(keys, cuts[:-1])
    order = np.empty(keys.shape[0], np.int64)
    descending = np.concatenate(pieces[::-1])
    assert _sort_runs(descending, order)
    assert np.array_equal(descending[order], keys)
    emitted = np.concatenate([pieces[i] for i in rng.permutation(len(pieces))])
    if _sort_runs(emitted, order):
        assert np.array_equal(emitted[order], keys)
    for given_keys in (descending, emitted):
        history = ImpulseHistory()
        history.keep(given_keys, given_keys.astype(float), None)
        assert np.array_equal(history.keys, keys) and np.array_equal(history._normal, keys)


def test_runs_that_interleave_are_not_sorted_as_runs():
    order = np.empty(6, np.int64)
    assert not _sort_runs(np.array([1, 5, 9, 2, 6, 10], np.int64), order)
    assert not _sort_runs(np.array([8, 4, 8, 2], np.int64), order[:4])  # a key twice
    assert _sort_runs(np.zeros(0, np.int64), order[:0])  # nothing to sort
