"""A stable counting sort, shared by the sphere grid (``sphere_pairs``) and the solver's row
blocks (``solver.partition``)."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def counting_sort(keys, buckets):
    """Sort the indices 0..n-1 by ``keys`` (each in [0, buckets)), stably (index order within a
    bucket): returns (order, starts), bucket b holding ``order[starts[b]:starts[b + 1]]``."""
    starts = np.zeros(buckets + 1, np.int64)
    for i in range(keys.shape[0]):
        starts[keys[i] + 1] += 1
    for b in range(buckets):
        starts[b + 1] += starts[b]
    order = np.empty(keys.shape[0], np.int64)
    fill = starts[:-1].copy()
    for i in range(keys.shape[0]):
        order[fill[keys[i]]] = i
        fill[keys[i]] += 1
    return order, starts
