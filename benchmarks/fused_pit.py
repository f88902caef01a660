"""The ball pit's in-run limit: one fused, single-threaded numba loop doing a sequential-impulse
step the simplest way (no World, no generators, no warm start, no checks).

Per step: gravity into the velocities; a hash grid (cell = one diameter); every touching
sphere pair and sphere–wall contact; ``velocity_passes`` of projected Gauss–Seidel on the normal
impulses (restitution e for closing speeds above 2·g·dt, the resting-contact trick below);
positions; ``position_passes`` of position projection on depths measured afresh. Frictionless,
unit masses, like the pit of bench_peers.py. Used by bench_limits.py and bench_peers.py.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True, inline="always")
def _bucket(cx, cy, cz, mask):
    return ((cx * 73856093) ^ (cy * 19349663) ^ (cz * 83492791)) & mask


@njit(cache=True)
def fused_pit(pos, vel, radius, half, top, e, g, dt, steps, velocity_passes, position_passes):
    """Advance ``pos``/``vel`` (N, 3) in place by ``steps`` steps; returns the last step's
    contact count. Walls at x, z = ±half, floor at y = 0, ceiling at ``top``."""
    n = pos.shape[0]
    size = 1
    while size < 2 * n:
        size *= 2
    mask = size - 1
    head = np.empty(size, np.int64)
    nxt = np.empty(n, np.int64)
    cell = np.empty((n, 3), np.int64)
    cap = 16 * n
    ca = np.empty(cap, np.int64)
    cb = np.empty(cap, np.int64)
    nrm = np.empty((cap, 3))
    target = np.empty(cap)
    lam = np.empty(cap)
    diameter = 2.0 * radius
    resting = 2.0 * math.sqrt(g[0] ** 2 + g[1] ** 2 + g[2] ** 2) * dt
    m = 0
    for _ in range(steps):
        for i in range(n):
            vel[i, 0] += g[0] * dt
            vel[i, 1] += g[1] * dt
            vel[i, 2] += g[2] * dt
        head[:] = -1
        for i in range(n):
            cx = math.floor(pos[i, 0] / diameter)
            cy = math.floor(pos[i, 1] / diameter)
            cz = math.floor(pos[i, 2] / diameter)
            cell[i, 0] = cx
            cell[i, 1] = cy
            cell[i, 2] = cz
            h = _bucket(cx, cy, cz, mask)
            nxt[i] = head[h]
            head[h] = i
        # Contacts: sphere pairs (each found once: j's cell must be the neighbour visited),
        # then the six planes (b = -1).
        m = 0
        for i in range(n):
            for dx in range(-1, 2):
                for dy in range(-1, 2):
                    for dz in range(-1, 2):
                        nx_, ny_, nz_ = cell[i, 0] + dx, cell[i, 1] + dy, cell[i, 2] + dz
                        j = head[_bucket(nx_, ny_, nz_, mask)]
                        while j >= 0:
                            if (j > i and cell[j, 0] == nx_ and cell[j, 1] == ny_
                                    and cell[j, 2] == nz_):
                                ux = pos[i, 0] - pos[j, 0]
                                uy = pos[i, 1] - pos[j, 1]
                                uz = pos[i, 2] - pos[j, 2]
                                d2 = ux * ux + uy * uy + uz * uz
                                if 0.0 < d2 < diameter * diameter and m < cap:
                                    d = math.sqrt(d2)
                                    ca[m] = i
                                    cb[m] = j
                                    nrm[m, 0] = ux / d
                                    nrm[m, 1] = uy / d
                                    nrm[m, 2] = uz / d
                                    m += 1
                            j = nxt[j]
            for axis in range(3):
                low = 0.0 if axis == 1 else -half
                high = top if axis == 1 else half
                for side in range(2):
                    if m >= cap:
                        break
                    if side == 0 and pos[i, axis] < low + radius:
                        sign = 1.0
                    elif side == 1 and pos[i, axis] > high - radius:
                        sign = -1.0
                    else:
                        continue
                    ca[m] = i
                    cb[m] = -1
                    nrm[m, 0] = 0.0
                    nrm[m, 1] = 0.0
                    nrm[m, 2] = 0.0
                    nrm[m, axis] = sign
                    m += 1
        # Velocities: bounce targets once, then projected Gauss–Seidel passes.
        for c in range(m):
            a, b = ca[c], cb[c]
            vn = vel[a, 0] * nrm[c, 0] + vel[a, 1] * nrm[c, 1] + vel[a, 2] * nrm[c, 2]
            if b >= 0:
                vn -= vel[b, 0] * nrm[c, 0] + vel[b, 1] * nrm[c, 1] + vel[b, 2] * nrm[c, 2]
            target[c] = -e * vn if vn < -resting else 0.0
            lam[c] = 0.0
        for _p in range(velocity_passes):
            for c in range(m):
                a, b = ca[c], cb[c]
                vn = vel[a, 0] * nrm[c, 0] + vel[a, 1] * nrm[c, 1] + vel[a, 2] * nrm[c, 2]
                k = 1.0
                if b >= 0:
                    vn -= vel[b, 0] * nrm[c, 0] + vel[b, 1] * nrm[c, 1] + vel[b, 2] * nrm[c, 2]
                    k = 0.5
                new = max(lam[c] + k * (target[c] - vn), 0.0)
                dl = new - lam[c]
                lam[c] = new
                vel[a, 0] += dl * nrm[c, 0]
                vel[a, 1] += dl * nrm[c, 1]
                vel[a, 2] += dl * nrm[c, 2]
                if b >= 0:
                    vel[b, 0] -= dl * nrm[c, 0]
                    vel[b, 1] -= dl * nrm[c, 1]
                    vel[b, 2] -= dl * nrm[c, 2]
        for i in range(n):
            pos[i, 0] += vel[i, 0] * dt
            pos[i, 1] += vel[i, 1] * dt
            pos[i, 2] += vel[i, 2] * dt
        # Positions: push overlaps apart along the contact normal, depths measured afresh.
        for _p in range(position_passes):
            for c in range(m):
                a, b = ca[c], cb[c]
                if b >= 0:
                    ux = pos[a, 0] - pos[b, 0]
                    uy = pos[a, 1] - pos[b, 1]
                    uz = pos[a, 2] - pos[b, 2]
                    depth = diameter - math.sqrt(ux * ux + uy * uy + uz * uz)
                    if depth > 0.0:
                        s = 0.5 * depth
                        for q in range(3):
                            pos[a, q] += s * nrm[c, q]
                            pos[b, q] -= s * nrm[c, q]
                else:
                    axis = 0 if nrm[c, 0] != 0.0 else (1 if nrm[c, 1] != 0.0 else 2)
                    sign = nrm[c, axis]
                    if sign > 0.0:
                        wall = 0.0 if axis == 1 else -half
                        depth = wall + radius - pos[a, axis]
                    else:
                        wall = top if axis == 1 else half
                        depth = pos[a, axis] - (wall - radius)
                    if depth > 0.0:
                        pos[a, axis] += sign * depth
    return m
