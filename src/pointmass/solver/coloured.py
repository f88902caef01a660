"""The sweep's two stages on every core: velocity passes and projection passes colour by
colour (``colouring.py``), the rows of one colour in parallel, the overflow group serially.

Same tolerances, caps and results as ``stages.solve_velocities`` and
``stages.project_positions``, except for the order in which rows are visited (colour by colour
instead of row order), and the same bits for any number of threads.
"""

from __future__ import annotations

from numba import njit

from .sweeps import (
    projection_rows_parallel,
    projection_rows_serial,
    velocity_rows_parallel,
    velocity_rows_serial,
)


@njit(cache=True, nogil=True)
def solve_velocities(bod, con, order, starts, dt, tolerance, max_passes):
    """Sequential-impulse passes colour by colour (see ``stages.solve_velocities``);
    ``order``, ``starts``: a ``colouring.Colouring``. Returns (passes, resolutions)."""
    colours = starts.shape[0] - 2
    passes = 0
    used = 0
    while passes < max_passes:
        passes += 1
        largest = 0.0
        for k in range(colours):
            if starts[k + 1] > starts[k]:
                change, hits = velocity_rows_parallel(bod, con, order, starts[k],
                                                      starts[k + 1], dt)
                largest = max(largest, change)
                used += hits
        change, hits = velocity_rows_serial(bod, con, order, starts[colours],
                                            starts[colours + 1], dt)
        largest = max(largest, change)
        used += hits
        if largest <= tolerance:
            break
    return passes, used


@njit(cache=True, nogil=True)
def project_positions(bod, con, order, starts, tolerance, max_passes):
    """Projection passes colour by colour (see ``stages.project_positions``).
    Returns (passes, largest depth left)."""
    colours = starts.shape[0] - 2
    passes = 0
    largest = 0.0
    while passes < max_passes:
        passes += 1
        largest = 0.0
        for k in range(colours):
            if starts[k + 1] > starts[k]:
                largest = max(largest, projection_rows_parallel(bod, con, order, starts[k],
                                                                starts[k + 1]))
        largest = max(largest, projection_rows_serial(bod, con, order, starts[colours],
                                                      starts[colours + 1]))
        if largest <= tolerance:
            break
    return passes, largest
