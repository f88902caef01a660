"""The particles' integration: semi-implicit Euler in the cookbook's order, with the folded
generators (gravity, drag) and the force accumulator consumed as it is read; serial in chunks,
or on every core from ``PARALLEL_MIN_PARTICLES`` (the same arithmetic, so the same bits)."""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from .forces import drag_force
from .particles import CHUNK, PARALLEL_MIN_PARTICLES, Particles


@njit(cache=True, inline="always")
def _integrate_particle(px, py, pz, vx, vy, vz, fx, fy, fz, w, d, gx, gy, gz, k1, k2, dt):
    """Semi-implicit Euler for one particle, in the cookbook's order: v += a·dt, v *= d^dt,
    p += v·dt, from its position, velocity and accumulated force, inverse mass w and damping d.
    The folded generators (``forces.fold``) act here: the uniform acceleration g and the
    drag of coefficients k1, k2 on the velocity before the step, as if added to the force.
    Immovable particles (w = 0) get no acceleration but keep moving with whatever velocity they
    were given (kinematic). Returns the new position, velocity and acceleration (9 numbers).

    A pure function of scalars: the driver loads and stores. (As a helper that stored into the
    arrays itself, numba compiled the serial loop at 71 ns a particle, against 4.5 ns for the
    same helper in the parallel loop on one thread; given g as an array, whose loads the
    stores may alias, 39 ns against 18.)
    """
    ax = 0.0
    ay = 0.0
    az = 0.0
    if w > 0.0:
        if k1 != 0.0 or k2 != 0.0:  # the same for every particle: a branch never mispredicted
            dx, dy, dz = drag_force(vx, vy, vz, k1, k2)
            fx += dx
            fy += dy
            fz += dz
        ax = gx + fx * w
        ay = gy + fy * w
        az = gz + fz * w
        vx += ax * dt
        vy += ay * dt
        vz += az * dt
        if d < 1.0:  # no multiply by 1 for the undamped (1 ns of 11 a particle, measured)
            keep = d**dt
            vx *= keep
            vy *= keep
            vz *= keep
    return px + vx * dt, py + vy * dt, pz + vz * dt, vx, vy, vz, ax, ay, az


@njit(cache=True, nogil=True)
def _first_not_finite(pos, vel, start, stop):
    """The first particle in [start, stop) with a non-finite position or velocity, or -1."""
    for i in range(start, stop):
        if not math.isfinite(pos[i, 0] + pos[i, 1] + pos[i, 2]
                             + vel[i, 0] + vel[i, 1] + vel[i, 2]):
            return i
    return -1


@njit(cache=True, nogil=True)
def _integrate(pos, vel, force, acc, inv_mass, damping, awake, g, k1, k2, dt, store_acc, start,
               stop):
    """Integrate particles ``start`` to ``stop`` (a chunk); returns the first that is not
    finite afterwards, or -1. The acceleration is stored only with ``store_acc`` (when
    something reads it: the solver's resting-contact test). Sleeping particles (``awake``
    False) are skipped, their accumulated force left for the wake test
    (``particle_sleep.py``); with every particle awake the arithmetic is the same.

    Each particle's force accumulator is cleared as it is read, as Cyclone's integrate ends with
    clearAccumulator: no separate pass clears it, and a force added to ``particles.force``
    before a step acts in it (as ``addForce`` does in the book). The stores are written out
    here: an inlined helper that stores into the arrays made numba's serial loop 3× slower
    (measured 49 against 16 ns a particle). Non-finite values are caught by one sum of the
    new positions, tested once (a non-finite velocity makes its position non-finite: dt > 0):
    a per-particle test cost 1–2 ns of 11; an overflow of the sum alone only costs a rescan
    that finds nothing. The kinetic energy is not summed here (in this loop it cost 2.3 ns a
    particle of 11.7, 8192 particles on one thread): ``StepStats`` sums it only when read."""
    gx, gy, gz = g[0], g[1], g[2]
    probe = 0.0
    for i in range(start, stop):
        if not awake[i]:
            continue
        px, py, pz, vx, vy, vz, ax, ay, az = _integrate_particle(
            pos[i, 0], pos[i, 1], pos[i, 2], vel[i, 0], vel[i, 1], vel[i, 2],
            force[i, 0], force[i, 1], force[i, 2], inv_mass[i], damping[i], gx, gy, gz,
            k1, k2, dt)
        pos[i, 0] = px
        pos[i, 1] = py
        pos[i, 2] = pz
        vel[i, 0] = vx
        vel[i, 1] = vy
        vel[i, 2] = vz
        if store_acc:
            acc[i, 0] = ax
            acc[i, 1] = ay
            acc[i, 2] = az
        force[i, 0] = 0.0  # the accumulator is consumed (Cyclone's clearAccumulator)
        force[i, 1] = 0.0
        force[i, 2] = 0.0
        probe += px + py + pz
    return -1 if math.isfinite(probe) else _first_not_finite(pos, vel, start, stop)


@njit(cache=True, nogil=True, parallel=True)
def _integrate_parallel(pos, vel, force, acc, inv_mass, damping, awake, g, k1, k2, dt,
                        store_acc):
    """``_integrate`` on all cores, one chunk of ``CHUNK`` particles per task; returns the
    first non-finite particle in chunk order (the same for any thread count), or -1."""
    n = pos.shape[0]
    chunks = (n + CHUNK - 1) // CHUNK
    bad = np.empty(chunks, np.int64)
    for c in prange(chunks):
        start, stop = c * CHUNK, min(n, (c + 1) * CHUNK)
        bad[c] = _integrate(pos, vel, force, acc, inv_mass, damping, awake, g, k1, k2, dt,
                            store_acc, start, stop)
    first = -1
    for c in range(chunks):
        if bad[c] >= 0:
            first = bad[c]
            break
    return first


def integrate_particles(p: Particles, g: np.ndarray, k1: float, k2: float, dt: float,
                        store_acc: bool, time: float) -> None:
    """Integrate every awake particle of ``p`` over ``dt`` (``_integrate``), on all cores from
    ``PARALLEL_MIN_PARTICLES``; raises ``FloatingPointError`` naming the first particle that
    is not finite afterwards (at world time ``time``)."""
    args = (p.position, p.velocity, p.force, p.acceleration, p.inv_mass, p.damping, p.awake,
            g, k1, k2, dt, store_acc)
    if p.count >= PARALLEL_MIN_PARTICLES:
        bad = _integrate_parallel(*args)
    else:
        bad = _integrate(*args, 0, p.count)
    if bad >= 0:
        raise FloatingPointError(
            f"particle {bad} became non-finite at t = {time:.6g} s "
            f"(position {p.position[bad].tolist()}, velocity {p.velocity[bad].tolist()}); "
            "a force is too strong for this dt, or a generator produced NaN")
