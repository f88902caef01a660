"""The sweep's velocity and projection passes on every core, phase by phase
(``partition.py``): the groups of a phase in parallel, each group's rows serially.

Same tolerances, caps and kernels as ``stages.solve_velocities`` and
``stages.project_positions`` (``sweeps.py``); only the order in which rows are visited differs
(group by group instead of row order), and the result is the same bits for any number of
threads.
"""

from __future__ import annotations

from numba import njit, prange

from .sweeps import has_friction, projection_rows, velocity_rows


@njit(cache=True, nogil=True, parallel=True)
def _velocity_phase(bod, con, order, spans, first, last, dt, friction, relaxation):
    """The groups first..last-1 of one phase in parallel, each group's rows in order."""
    largest = 0.0
    used = 0
    for g in prange(first, last):
        change, hits = velocity_rows(bod, con, order, spans[g, 0], spans[g, 1], dt, friction,
                                     relaxation)
        largest = max(largest, change)
        used += hits
    return largest, used


@njit(cache=True, nogil=True, parallel=True)
def _projection_phase(bod, con, order, spans, first, last):
    largest = 0.0
    for g in prange(first, last):
        largest = max(largest, projection_rows(bod, con, order, spans[g, 0],
                                                      spans[g, 1]))
    return largest


@njit(cache=True, nogil=True)
def solve_velocities(bod, con, order, spans, phases, dt, tolerance, max_passes, relaxation):
    """Sequential-impulse passes phase by phase (``partition.Phases``): the groups of a phase
    in parallel, a phase of one group serially; each row's step over-relaxed by
    ``relaxation`` (as ``stages.solve_velocities``). Returns (passes, resolutions)."""
    passes = 0
    used = 0
    friction = has_friction(con)
    while passes < max_passes:
        passes += 1
        largest = 0.0
        for p in range(phases.shape[0] - 1):
            first, last = phases[p], phases[p + 1]
            if last - first == 1:
                change, hits = velocity_rows(bod, con, order, spans[first, 0],
                                             spans[first, 1], dt, friction, relaxation)
            elif last > first:
                change, hits = _velocity_phase(bod, con, order, spans, first, last, dt,
                                               friction, relaxation)
            else:
                continue
            largest = max(largest, change)
            used += hits
        if largest <= tolerance:
            break
    return passes, used


@njit(cache=True, nogil=True)
def project_positions(bod, con, order, spans, phases, tolerance, max_passes):
    """Projection passes phase by phase (see ``stages.project_positions``).
    Returns (passes, largest depth left)."""
    passes = 0
    largest = 0.0
    while passes < max_passes:
        passes += 1
        largest = 0.0
        for p in range(phases.shape[0] - 1):
            first, end = phases[p], phases[p + 1]
            if end - first == 1:
                largest = max(largest, projection_rows(bod, con, order, spans[first, 0],
                                                       spans[first, 1]))
            elif end > first:
                largest = max(largest, _projection_phase(bod, con, order, spans, first, end))
        if largest <= tolerance:
            break
    return passes, largest
