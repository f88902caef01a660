"""The impulse history (``solver/history.py``): what ``keep`` stores is sorted by key however
it sorts (from the rows ``recall`` found, or afresh), and ``recall`` finds every kept key."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pointmass.solver.history import ImpulseHistory


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
