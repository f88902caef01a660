"""One Gauss–Seidel visit of a run of contact rows: ``rows[lo:hi]`` in order (``rows`` None:
the contacts lo..hi-1 themselves, with no indirection), each row seeing the velocities its
predecessors left. The serial sweep visits every row (``stages``); the parallel one visits
one group of rows per thread, groups that share no particle (``partition.py``, ``parallel.py``).

Each body is written into its loop rather than called per row: a per-row helper taking the
arrays costs ~5× per contact visit even inlined (measured here: 505 against 148 ns a row on a
10 000-sphere pit under load; the stages' comments measured the same for push and project).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .kernels import PENETRATION_EPSILON, coulomb_disc


@njit(cache=True, inline="always")
def has_friction(con):
    """Whether any contact of the set has μ > 0 (else ``velocity_rows`` skips friction)."""
    mu = con.mu
    for c in range(mu.shape[0]):
        if mu[c] > 0.0:
            return True
    return False


#: Rows a velocity pass visits in turn from this many runs of the row list (row i of run 0,
#: row i of run 1, then row i + 1 of each): consecutive rows of one run share a particle, so
#: each waits for the last one's velocity; rows of different runs (other particles, far
#: apart) overlap in the processor (measured on the settled 10 000-sphere pit: a pass
#: 0.46 → 0.38 ms with two runs, 0.37 with four). Sets smaller than ``STREAMS_MIN_ROWS`` keep
#: plain row order.
STREAMS = 2
STREAMS_MIN_ROWS = 256


@njit(cache=True, inline="always")
def _interleaved(lo, hi):
    """(runs, rows per run) for visiting rows lo..hi-1 ``STREAMS`` runs in turn: round i
    visits row lo + i + s·run of each run s that has it."""
    streams = STREAMS if hi - lo >= STREAMS_MIN_ROWS else 1
    return streams, (hi - lo + streams - 1) // streams


@njit(cache=True, inline="always")
def _row(rows, r):
    """The contact of row r: ``rows[r]``, or r itself when ``rows`` is None; unsigned, since
    numba wraps negative indices around and with ``lo`` unknown it could not prove r ≥ 0 (15 %
    of a velocity pass; the same bits)."""
    return np.uint64(r if rows is None else rows[r])


def _velocity_rows_for(friction: bool):
    """``velocity_rows`` compiled for sets with friction or without: ``friction`` is a
    constant of the closure, so a frictionless set's loop has no friction branch at all
    (measured on the settled 10 000-sphere pit: 0.57 → 0.51 ms a pass, with the row's
    velocities read into locals once; the same bits)."""

    def rows_kernel(bod, con, rows, lo, hi, dt, relaxation):
        ca, cb, n, mu, wa, wb, k = con.a, con.b, con.n, con.mu, con.wa, con.wb, con.k
        target, impulse, tangent, bil = con.target, con.impulse, con.tangent, con.bil
        vel, disp = bod.vel, bod.disp
        largest = 0.0
        used = 0
        streams, run = _interleaved(lo, hi)
        for i in range(run):
            for s in range(streams):
                r = lo + i + s * run
                if r >= hi:
                    break
                c = _row(rows, r)
                # Branch-free (kernels.relative and push written out, see the module
                # docstring): whether a row's impulse changes, and whether its b is scenery,
                # change from row to row, and the processor guessed wrong (measured on the
                # settled 10 000-sphere pit: a pass 0.41 -> 0.26 ms, the same bits). So the
                # impulse and both velocities are stored whatever the step, and a row with
                # scenery reads and writes back particle a in b's place, with b's velocity
                # taken as 0 and its inverse mass 0 (b first, so a's new velocity is kept).
                # A row between two immovable ends has k = 0, so a step of 0.
                kc = k[c]
                step_k = kc * relaxation  # off the rows' chain of dependent reads
                a = ca[c]
                b = cb[c]
                scenery = b < 0
                other = a if scenery else b
                nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
                ax, ay, az = vel[a, 0], vel[a, 1], vel[a, 2]
                ox, oy, oz = vel[other, 0], vel[other, 1], vel[other, 2]
                bx = 0.0 if scenery else ox
                by = 0.0 if scenery else oy
                bz = 0.0 if scenery else oz
                vs = (ax - bx) * nx + (ay - by) * ny + (az - bz) * nz
                old = impulse[c]
                total = old + (target[c] - vs) * step_k
                # Contacts push, never pull (a rod does both: it is bilateral).
                total = total if bil[c] else max(total, 0.0)
                step = total - old
                impulse[c] = total
                w = wa[c]
                w_b = wb[c]
                # The row's velocities after its normal impulse, stored once below.
                px, py, pz = ax + nx * step * w, ay + ny * step * w, az + nz * step * w
                qx, qy, qz = ox - nx * step * w_b, oy - ny * step * w_b, oz - nz * step * w_b
                change = abs(step) * (w + w_b)  # the row's change of velocity [m/s]
                used += step != 0.0
                if friction:
                    # Coulomb friction right after the normal impulse, on the velocities it
                    # left, in locals and without branches, as the normal part (a row with
                    # μ = 0 clamps to 0 and changes nothing); the particles move by the
                    # velocity change × dt (``kernels.slide``: the integrator moved them with
                    # the old one). Measured on a pass of the 10 000-ball demo's pile: 61-63
                    # -> 40-42 ns a frictional row, against a helper that read back what the
                    # row had just stored and branched on the disc; the same bits.
                    t0x, t0y, t0z = tangent[c, 0], tangent[c, 1], tangent[c, 2]
                    fx, fy, fz = coulomb_disc(px - (0.0 if scenery else qx),
                                              py - (0.0 if scenery else qy),
                                              pz - (0.0 if scenery else qz),
                                              nx, ny, nz, t0x, t0y, t0z, kc, mu[c] * total)
                    tangent[c, 0] = fx
                    tangent[c, 1] = fy
                    tangent[c, 2] = fz
                    dx, dy, dz = fx - t0x, fy - t0y, fz - t0z
                    qx, qy, qz = qx + -dx * w_b, qy + -dy * w_b, qz + -dz * w_b
                    px, py, pz = px + dx * w, py + dy * w, pz + dz * w
                    sox, soy, soz = disp[other, 0], disp[other, 1], disp[other, 2]
                    sax, say, saz = disp[a, 0], disp[a, 1], disp[a, 2]
                    disp[other, 0] = sox + -dx * w_b * dt
                    disp[other, 1] = soy + -dy * w_b * dt
                    disp[other, 2] = soz + -dz * w_b * dt
                    disp[a, 0] = sax + dx * w * dt
                    disp[a, 1] = say + dy * w * dt
                    disp[a, 2] = saz + dz * w * dt
                    change = max(change, math.sqrt(dx * dx + dy * dy + dz * dz) * (w + w_b))
                vel[other, 0] = qx
                vel[other, 1] = qy
                vel[other, 2] = qz
                vel[a, 0] = px
                vel[a, 1] = py
                vel[a, 2] = pz
                largest = max(largest, change)
        return largest, used

    return njit(cache=True, nogil=True)(rows_kernel)


_rows_with_friction = _velocity_rows_for(True)
_rows_without_friction = _velocity_rows_for(False)


@njit(cache=True, nogil=True)
def velocity_rows(bod, con, rows, lo, hi, dt, friction, relaxation):
    """Sequential impulses (Catto; box2d-lite's ``Arbiter::ApplyImpulse``) on rows[lo:hi]:
    each keeps an accumulated impulse clamped at ≥ 0 (contacts push, never pull, and a warm
    start that was too strong is taken back; a bilateral rod is not clamped), aiming at the
    separating velocity ``target``; friction right after each normal impulse, where
    ``friction`` (``has_friction``: a frictionless set runs a loop without it).

    ``relaxation`` ω scales each normal step (successive over-relaxation, projected: the
    clamp still applies to the accumulated impulse): 1 is plain Gauss–Seidel, the same bits;
    1 < ω < 2 goes past each row's own answer, which speeds up the slow tail of a large
    coupled set (``solver.LARGE_SET_RELAXATION``). Friction steps are not scaled.

    Returns (the largest velocity change of a row [m/s], the rows whose impulse changed)."""
    if friction:
        return _rows_with_friction(bod, con, rows, lo, hi, dt, relaxation)
    return _rows_without_friction(bod, con, rows, lo, hi, dt, relaxation)


@njit(cache=True, nogil=True)
def projection_rows(bod, con, rows, lo, hi):
    """Mass-weighted projection on rows[lo:hi]: move each contact's particles apart along n by
    inverse mass until it no longer penetrates (a rod: until its length is right). Positions
    only. Returns the largest depth found [m].

    Visited as the velocity rows are (``STREAMS`` runs in turn) and without branches: whether
    a row penetrates changes from row to row (~60 % of the settled 10 000-sphere pit's rows
    do, in no pattern), and the processor guessed wrong. A row that does not penetrate moves
    its particles by 0. The test is a number multiplied in, not an ``if`` or a conditional
    expression, which numba compiles to branches (measured on that pile, four passes: 1.79 ms
    as a branch, 1.98 as conditional expressions, 1.72 multiplied in, 1.23 multiplied in and
    in two runs; 0.80 / 1.16 ms had no row / every row penetrated: the cost was the branch's
    guessing)."""
    ca, cb, n, depth0, wa, wb, k = con.a, con.b, con.n, con.depth0, con.wa, con.wb, con.k
    bil = con.bil
    disp = bod.disp
    largest = 0.0
    streams, run = _interleaved(lo, hi)
    for i in range(run):
        for s in range(streams):
            r = lo + i + s * run
            if r >= hi:
                break
            c = _row(rows, r)
            kc = k[c]
            a = ca[c]
            b = cb[c]
            scenery = b < 0  # scenery: a in b's place, b's displacement 0 (as velocity rows)
            other = a if scenery else b
            nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
            ax, ay, az = disp[a, 0], disp[a, 1], disp[a, 2]
            ox, oy, oz = disp[other, 0], disp[other, 1], disp[other, 2]
            bx = 0.0 if scenery else ox
            by = 0.0 if scenery else oy
            bz = 0.0 if scenery else oz
            d = depth0[c] - ((ax - bx) * nx + (ay - by) * ny + (az - bz) * nz)
            # 1.0 where the row moves its particles: it penetrates (a rod: or is too short)
            # and is not between two immovable ends.
            moves = np.float64((kc != 0.0) & ((d > PENETRATION_EPSILON)
                                              | (bil[c] & (d < -PENETRATION_EPSILON))))
            largest = max(largest, abs(d) * moves)
            share = d * kc * moves
            w = wa[c]
            w_b = wb[c]
            disp[other, 0] = ox - nx * share * w_b
            disp[other, 1] = oy - ny * share * w_b
            disp[other, 2] = oz - nz * share * w_b
            disp[a, 0] = ax + nx * share * w
            disp[a, 1] = ay + ny * share * w
            disp[a, 2] = az + nz * share * w
    return largest
