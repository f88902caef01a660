"""``solver/borrow.py``: a borrowed view is the same array (data, shape, strides) without an
owner record, so kernels it is passed to count no references; writes through it land in the
owner."""

import numpy as np
from numba import njit

from pointmass.solver.borrow import borrowed, keep_alive, zeroed


@njit(cache=True)
def _add_one(view):
    for i in range(view.shape[0]):
        for j in range(view.shape[1]):
            view[i, j] += 1.0


@njit(cache=True)
def _through_views(a, n):
    """``a`` borrowed, and an array made here (``zeroed``: owner and view) kept alive to the
    end: each is changed ``n`` times by a kernel call; returns the made one's sum."""
    view = borrowed(a)
    own, made = zeroed((3, 2), np.float64)
    for _ in range(n):
        _add_one(view)
        _add_one(made)
    total = made.sum()
    keep_alive(own)
    return total


def test_a_borrowed_view_writes_into_its_owner_and_a_kept_scratch_array_stays_valid():
    a = np.arange(8.0).reshape(4, 2)
    expect = a + 5.0
    assert _through_views(a, 5) == 3 * 2 * 5.0
    assert np.array_equal(a, expect)


def test_a_strided_array_is_borrowed_with_its_strides():
    base = np.zeros((6, 4))
    column_pairs = base[::2, 1:3]  # not contiguous: numba's "A" layout
    _through_views(column_pairs, 2)
    expect = np.zeros((6, 4))
    expect[::2, 1:3] = 2.0
    assert np.array_equal(base, expect)
