"""Collision detection: contact generators for planes, boxes and sphere–sphere pairs.

These only *find* contacts; the resolver resolves them. Sphere–sphere detection uses a uniform
grid (cell = largest diameter plus margin), dense over the spheres' bounding box when that is
small and a spatial hash when they are spread far apart, so finding pairs costs O(N) for evenly
spread spheres instead of the O(N²) pair loop of Cyclone's demos.

**Contact margin (speculative contacts).** A pair is reported not only when it overlaps but also
when its gap is smaller than a margin (by default 5 % of the radius), with a negative
penetration. Cyclone reports only overlapping pairs, so when the resolver pushes one sphere out of
another it pushes it into a third that was exactly touching but not in the list: a stack of
spheres then sinks and oscillates for ever (measured: a 5-sphere stack sank 0.28 radius and
never came to rest). With the margin the touching neighbours are in the list, their penetration is
updated as particles move, and the resolver treats a gap contact as a collision only if it would
close within the step (see ``resolver.py``) — the speculative contacts of Box2D and Bullet.

**Friction.** Every generator takes ``friction`` μ ≥ 0 (default 0, frictionless as in the book):
the Coulomb coefficient written into each contact it reports (see ``resolver.py``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from . import _validate as check
from ._sort import counting_sort
from .contacts import ContactBuffer, ContactGenerator, friction_value, restitution_value
from .forces import _Selection
from .keys import pair_key, plane_key_base, plane_serial
from .particles import Particles

#: Default contact margin, as a fraction of each particle's radius (see the module docstring).
DEFAULT_MARGIN_FRACTION = 0.05




def _margin_value(value) -> float | None:
    return None if value is None else check.scalar(value, "margin", low=0.0)


@njit(cache=True, nogil=True)
def _plane_contacts(pos, radius, inv_mass, idx, normal, offset, margin, margin_fraction,
                    restitution, key_base, out_a, out_b, out_n, out_pen, out_rest, out_key,
                    start):
    """Contacts of the movable particles ``idx`` whose gap to the plane is below the margin
    (``margin`` [m], or when negative ``margin_fraction`` × radius). Written from ``start``;
    returns the count written or needed, like ``_sphere_pairs``."""
    count = start
    capacity = out_a.shape[0]
    for k in range(idx.shape[0]):
        i = idx[k]
        if inv_mass[i] <= 0.0:
            continue
        gap = (pos[i, 0] * normal[0] + pos[i, 1] * normal[1] + pos[i, 2] * normal[2]
               - offset - radius[i])
        reach = margin if margin >= 0.0 else margin_fraction * radius[i]
        if gap >= reach:
            continue
        if count < capacity:
            out_a[count] = i
            out_b[count] = -1
            out_n[count, 0] = normal[0]
            out_n[count, 1] = normal[1]
            out_n[count, 2] = normal[2]
            out_pen[count] = -gap
            out_rest[count] = restitution
            out_key[count] = key_base | i
        count += 1
    return count


class Plane(ContactGenerator):
    """A one-sided plane n·x = offset; particles keep their surface (centre minus radius) on the
    side the unit normal ``n`` points to. Points (radius 0) collide with it too.

    Args:
        normal: Plane normal (normalised here), pointing into the free side.
        offset: n·x on the plane [m].
        restitution: In [0, 1].
        particles: Indices that collide with it, or None for all.
        margin: Report a contact when the gap is below this [m], ≥ 0 (a speculative contact
            with negative penetration); None: 5 % of each particle's radius.
        friction: Coulomb friction coefficient μ ≥ 0 (0: frictionless).
    """

    def __init__(self, normal=(0.0, 1.0, 0.0), offset: float = 0.0, *, restitution: float = 0.5,
                 particles=None, margin: float | None = None, friction: float = 0.0) -> None:
        n = check.vec3(normal, "normal")
        length = float(np.linalg.norm(n))
        if length == 0.0:
            raise ValueError("normal must be a non-zero 3-vector")
        self.normal = n / length
        self.offset = check.scalar(offset, "offset")
        self.restitution = restitution
        self.friction = friction
        self.margin = _margin_value(margin)
        self._sel = _Selection(particles)
        self._key_base = plane_key_base()

    restitution = property(lambda self: self._restitution, lambda self, v: setattr(
        self, "_restitution", restitution_value(v)), doc="Coefficient of restitution [0, 1].")
    friction = property(lambda self: self._friction, lambda self, v: setattr(
        self, "_friction", friction_value(v)), doc="Coulomb friction coefficient μ ≥ 0.")

    @property
    def serial(self) -> int:
        """This plane's number, unique in the process: rigid-body contact keys name it."""
        return plane_serial(self._key_base)

    def validate(self, particles: Particles) -> None:
        self._sel.validate(particles)

    def generate(self, particles: Particles, contacts: ContactBuffer) -> None:
        idx = self._sel.indices(particles)
        margin = -1.0 if self.margin is None else self.margin
        start = contacts.count
        for _ in range(2):  # the first try reports how much room it needs if short
            a, b, n, pen, rest = contacts.raw()
            total = _plane_contacts(particles.position, particles.radius, particles.inv_mass,
                                    idx, self.normal, self.offset, margin,
                                    DEFAULT_MARGIN_FRACTION, self._restitution, self._key_base,
                                    a, b, n, pen, rest, contacts.raw_key(), contacts.count)
            if total <= contacts.capacity:
                contacts.count = total
                contacts.raw_friction()[start:total] = self._friction
                return
            contacts.reserve(total - contacts.count)


class Ground(Plane):
    """The horizontal ground y = ``height`` (Cyclone's GroundContacts, at any height)."""

    def __init__(self, height: float = 0.0, *, restitution: float = 0.5, particles=None,
                 margin: float | None = None, friction: float = 0.0) -> None:
        super().__init__((0.0, 1.0, 0.0), height, restitution=restitution, particles=particles,
                         margin=margin, friction=friction)

    @property
    def height(self) -> float:
        return self.offset


class Box(ContactGenerator):
    """The inside of an axis-aligned box: a floor, four walls and optionally a ceiling.

    Args:
        low, high: Opposite corners [m]; low < high on every axis.
        restitution: In [0, 1].
        ceiling: Also keep particles below ``high[1]``.
        particles: Indices that collide with it, or None for all.
        margin: Contact margin [m], as for ``Plane``.
        friction: Coulomb friction coefficient μ ≥ 0 of every face (0: frictionless).
    """

    def __init__(self, low=(-5.0, 0.0, -5.0), high=(5.0, 10.0, 5.0), *,
                 restitution: float = 0.5, ceiling: bool = False, particles=None,
                 margin: float | None = None, friction: float = 0.0) -> None:
        self.low = check.vec3(low, "low")
        self.high = check.vec3(high, "high")
        if not (self.low < self.high).all():
            raise ValueError(f"low must be below high on every axis, got {self.low} and "
                             f"{self.high}")
        faces = [((0, 1, 0), self.low[1]), ((1, 0, 0), self.low[0]), ((-1, 0, 0), -self.high[0]),
                 ((0, 0, 1), self.low[2]), ((0, 0, -1), -self.high[2])]
        if ceiling:
            faces.append(((0, -1, 0), -self.high[1]))
        friction = friction_value(friction)
        self.planes = [Plane(n, d, restitution=restitution, particles=particles, margin=margin,
                             friction=friction) for n, d in faces]
        self.ceiling = ceiling

    @property
    def restitution(self) -> float:
        return self.planes[0].restitution

    @restitution.setter
    def restitution(self, value: float) -> None:
        for plane in self.planes:
            plane.restitution = value

    @property
    def friction(self) -> float:
        return self.planes[0].friction

    @friction.setter
    def friction(self, value: float) -> None:
        value = friction_value(value)
        for plane in self.planes:
            plane.friction = value

    def validate(self, particles: Particles) -> None:
        for plane in self.planes:
            plane.validate(particles)

    def generate(self, particles: Particles, contacts: ContactBuffer) -> None:
        for plane in self.planes:
            plane.generate(particles, contacts)


# --- sphere–sphere with a spatial hash ------------------------------------------------------

@njit(cache=True, inline="always")
def _cell_hash(ix, iy, iz, mask):
    h = (ix * 92837111) ^ (iy * 689287499) ^ (iz * 283923481)
    return h & mask


@njit(cache=True, inline="always")
def _swap_contacts(out_a, out_b, out_n, out_pen, out_rest, out_key, u, v):
    out_a[u], out_a[v] = out_a[v], out_a[u]
    out_b[u], out_b[v] = out_b[v], out_b[u]
    for c in range(3):
        out_n[u, c], out_n[v, c] = out_n[v, c], out_n[u, c]
    out_pen[u], out_pen[v] = out_pen[v], out_pen[u]
    out_rest[u], out_rest[v] = out_rest[v], out_rest[u]
    out_key[u], out_key[v] = out_key[v], out_key[u]


#: The sphere pairs' grid is dense (a slot for every cell of the spheres' bounding box, so the
#: three cells along z next to a cell are one run of the sorted spheres) when the box has at
#: most this many cells per sphere; spheres spread wider go to the spatial hash (a bucket per
#: neighbour cell, each checked for other cells sharing it).
DENSE_CELLS_PER_SPHERE = 8


@njit(cache=True, nogil=True)
def _grid(pos, idx, cell_size):
    """Bin the spheres ``idx`` into cells of side ``cell_size``: their cells (n, 3), each
    one's slot in the cell-sorted order (a stable counting sort: in a cell, index order), the
    sorted order itself, the slot ranges per bucket (``starts``), and the grid's shape
    (``low`` corner and ``span`` cells per axis; span[0] == 0: hashed, not dense)."""
    n = idx.shape[0]
    inv = 1.0 / cell_size
    cells = np.empty((n, 3), np.int64)
    low = np.empty(3, np.int64)
    high = np.empty(3, np.int64)
    for c in range(3):
        low[c] = np.iinfo(np.int64).max
        high[c] = np.iinfo(np.int64).min
    for k in range(n):
        i = idx[k]
        for c in range(3):
            cell = math.floor(pos[i, c] * inv)
            cells[k, c] = cell
            low[c] = min(low[c], cell)
            high[c] = max(high[c], cell)
    span = np.zeros(3, np.int64)
    volume = 1.0
    for c in range(3):
        volume *= float(high[c] - low[c] + 1)
    keys = np.empty(n, np.int64)
    if volume <= DENSE_CELLS_PER_SPHERE * n + 64:
        for c in range(3):
            span[c] = high[c] - low[c] + 1
        table = span[0] * span[1] * span[2]
        for k in range(n):
            keys[k] = (((cells[k, 0] - low[0]) * span[1] + cells[k, 1] - low[1]) * span[2]
                       + cells[k, 2] - low[2])
    else:
        table = 1
        while table < 2 * n:
            table *= 2
        for k in range(n):
            keys[k] = _cell_hash(cells[k, 0], cells[k, 1], cells[k, 2], table - 1)
    order, starts = counting_sort(keys, table)
    slot = np.empty(n, np.int64)
    for s in range(n):
        slot[order[s]] = s
    return cells, slot, order, starts, low, span


@njit(cache=True, nogil=True)
def _neighbour_runs(cells, slot, starts, low, span, k, runs):
    """The runs of sorted slots holding sphere k's own cell (the spheres after k in it) and
    its 13 "forward" neighbour cells, into ``runs`` rows (first, stop, cx, cy, cz); returns
    how many. Dense: five runs (a cell's z neighbours are adjacent slots), cell column
    unused; hashed: a bucket per cell, with the cell to check its spheres against."""
    cx, cy, cz = cells[k, 0], cells[k, 1], cells[k, 2]
    count = 0
    if span[0] > 0:
        x, y, z = cx - low[0], cy - low[1], cz - low[2]
        # Own cell after k, then the cell at z + 1: adjacent slots.
        base = (x * span[1] + y) * span[2] + z
        runs[count, 0] = slot[k] + 1
        runs[count, 1] = starts[base + 2] if z + 1 < span[2] else starts[base + 1]
        count += 1
        z0 = max(z - 1, 0)
        z1 = min(z + 1, span[2] - 1)
        for dx, dy in ((0, 1), (1, -1), (1, 0), (1, 1)):
            if x + dx >= span[0] or y + dy < 0 or y + dy >= span[1]:
                continue
            row = ((x + dx) * span[1] + y + dy) * span[2]
            runs[count, 0] = starts[row + z0]
            runs[count, 1] = starts[row + z1 + 1]
            count += 1
        return count
    mask = starts.shape[0] - 2
    for dx in range(-1, 2):
        for dy in range(-1, 2):
            for dz in range(-1, 2):
                forward = dx > 0 or (dx == 0 and (dy > 0 or (dy == 0 and dz > 0)))
                own = dx == 0 and dy == 0 and dz == 0
                if not (forward or own):
                    continue
                bucket = _cell_hash(cx + dx, cy + dy, cz + dz, mask)
                runs[count, 0] = slot[k] + 1 if own else starts[bucket]
                runs[count, 1] = starts[bucket + 1]
                runs[count, 2] = cx + dx
                runs[count, 3] = cy + dy
                runs[count, 4] = cz + dz
                count += 1
    return count


@njit(cache=True, nogil=True)
def _sphere_pairs(pos, vel, radius, inv_mass, idx, cell_size, restitution, margin,
                  margin_fraction, sweep, dt, out_a, out_b, out_n, out_pen, out_rest, out_key,
                  start):
    """Find sphere pairs among ``idx`` closer than their radii plus the margin (``margin`` [m],
    or when negative ``margin_fraction`` × the larger radius) plus how far each may travel in
    the step (``sweep`` [m] per particle, |v|·dt); write contacts from ``start``.

    Returns the total count written or needed (if it exceeds the buffer, call again with more
    room: nothing beyond the buffer is written).

    The spheres are binned (``_grid``) and copied in cell order, so a neighbour cell's spheres
    are read from adjacent memory (measured on the settled 10 000-sphere pit: 2.3 ms a step,
    against 5.5 for a hashed bucket per neighbour cell and reads through the index).
    """
    n = idx.shape[0]
    cells, slot, order, starts, low, span = _grid(pos, idx, cell_size)
    dense = span[0] > 0
    # Cell-ordered copies of what each candidate pair reads.
    sj = np.empty(n, np.int64)
    sp = np.empty((n, 3))
    sr = np.empty(n)
    sw = np.empty(n)
    ss = np.empty(n)
    for s in range(n):
        j = idx[order[s]]
        sj[s] = j
        sp[s, 0] = pos[j, 0]
        sp[s, 1] = pos[j, 1]
        sp[s, 2] = pos[j, 2]
        sr[s] = radius[j]
        sw[s] = inv_mass[j]
        ss[s] = sweep[j]
    runs = np.empty((14, 5), np.int64)

    count = start
    capacity = out_a.shape[0]
    for k in range(n):
        i = idx[k]
        first = count
        # Own cell (later particles only) and the 13 "forward" neighbour cells: each pair is
        # met exactly once, from the particle in the lower cell (or the lower index), and
        # written as (lower index, higher index), so its key and its normal's direction do not
        # change when the two cross a cell boundary (written as met, 9 % of a settled
        # 10 000-sphere pit's contacts flipped every step and lost their warm start).
        px, py, pz = pos[i, 0], pos[i, 1], pos[i, 2]
        ri, wi, si = radius[i], inv_mass[i], sweep[i]
        for r in range(_neighbour_runs(cells, slot, starts, low, span, k, runs)):
            for s in range(runs[r, 0], runs[r, 1]):
                # A hashed bucket may hold other cells: only take the run's own cell.
                if not dense:
                    m = order[s]
                    if (cells[m, 0] != runs[r, 2] or cells[m, 1] != runs[r, 3]
                            or cells[m, 2] != runs[r, 4]):
                        continue
                if wi == 0.0 and sw[s] == 0.0:
                    continue
                j = sj[s]
                ddx = px - sp[s, 0]
                ddy = py - sp[s, 1]
                ddz = pz - sp[s, 2]
                reach = ri + sr[s]
                if margin >= 0.0:
                    catch = reach + margin
                else:
                    catch = reach + margin_fraction * max(ri, sr[s])
                d2 = ddx * ddx + ddy * ddy + ddz * ddz
                if d2 >= (catch + si + ss[s]) ** 2:
                    continue
                nx, ny, nz = ddx, ddy, ddz
                if d2 >= catch * catch:
                    # Beyond the margin but fast: a contact only if the pair would
                    # touch within the step, with the normal at that moment (so a pair
                    # that passes by is not deflected by a ghost contact).
                    nx, ny, nz = _impact_direction(ddx, ddy, ddz, vel, i, j, reach, dt)
                    if nx == 0.0 and ny == 0.0 and nz == 0.0:
                        continue
                if count < capacity:
                    dist = math.sqrt(nx * nx + ny * ny + nz * nz)
                    if dist > 0.0:
                        out_n[count, 0] = nx / dist
                        out_n[count, 1] = ny / dist
                        out_n[count, 2] = nz / dist
                    else:  # same centre: any direction separates them; pick up
                        out_n[count, 0] = 0.0
                        out_n[count, 1] = 1.0
                        out_n[count, 2] = 0.0
                    # The gap along that normal (the separation it must not close).
                    along = (ddx * out_n[count, 0] + ddy * out_n[count, 1]
                             + ddz * out_n[count, 2])
                    out_pen[count] = reach - along
                    out_rest[count] = restitution
                    lo, hi = (i, j) if i < j else (j, i)
                    if lo != i:  # the normal points from b to a
                        for c in range(3):
                            out_n[count, c] = -out_n[count, c]
                    out_a[count] = lo
                    out_b[count] = hi
                    out_key[count] = pair_key(lo, hi)
                count += 1
        # Sort this particle's few contacts by key, so the keys come out sorted (the warm
        # start then matches them against the previous step's in linear time).
        last = min(count, capacity)
        for u in range(first + 1, last):
            v = u
            while v > first and out_key[v - 1] > out_key[v]:
                _swap_contacts(out_a, out_b, out_n, out_pen, out_rest, out_key, v - 1, v)
                v -= 1
    return count


@njit(cache=True, inline="always")
def _impact_direction(dx, dy, dz, vel, i, j, reach, dt):
    """Where i is relative to j when they first touch within the next step, moving apart by
    d = (dx, dy, dz) + u·t with u = v_i - v_j; (0, 0, 0) if they do not touch by t = dt."""
    ux = vel[i, 0] - vel[j, 0]
    uy = vel[i, 1] - vel[j, 1]
    uz = vel[i, 2] - vel[j, 2]
    uu = ux * ux + uy * uy + uz * uz
    du = dx * ux + dy * uy + dz * uz
    if uu == 0.0 or du >= 0.0:
        return 0.0, 0.0, 0.0  # not approaching
    # |d + u·t|² = reach²: uu·t² + 2·du·t + (d·d - reach²) = 0, the first root.
    c = dx * dx + dy * dy + dz * dz - reach * reach
    disc = du * du - uu * c
    if disc < 0.0:
        return 0.0, 0.0, 0.0  # the closest approach stays wider than the radii
    t = (-du - math.sqrt(disc)) / uu
    if t > dt:
        return 0.0, 0.0, 0.0  # touches only after this step: found next step
    return dx + ux * t, dy + uy * t, dz + uz * t


@njit(cache=True, nogil=True)
def _sweep_lengths(velocity, dt):
    """|v|·dt per particle [m]: how far each may travel in the coming step."""
    out = np.empty(velocity.shape[0])
    for i in range(velocity.shape[0]):
        out[i] = math.sqrt(velocity[i, 0] ** 2 + velocity[i, 1] ** 2 + velocity[i, 2] ** 2) * dt
    return out


class SphereCollisions(ContactGenerator):
    """Collisions between all particles with radius > 0 (or a chosen subset).

    Args:
        restitution: In [0, 1].
        particles: Indices that collide with each other, or None for every particle with
            radius > 0.
        margin: Report pairs whose gap is below this [m], ≥ 0 (speculative contacts with
            negative penetration); None: 5 % of the larger radius of each pair.
        friction: Coulomb friction coefficient μ ≥ 0 between spheres (0: frictionless).
    """

    def __init__(self, *, restitution: float = 0.5, particles=None,
                 margin: float | None = None, friction: float = 0.0) -> None:
        self.restitution = restitution
        self.friction = friction
        self.friction = friction
        self.margin = _margin_value(margin)
        self._sel = _Selection(particles)
        self._key_base = plane_key_base()

    restitution = property(lambda self: self._restitution, lambda self, v: setattr(
        self, "_restitution", restitution_value(v)), doc="Coefficient of restitution [0, 1].")
    friction = property(lambda self: self._friction, lambda self, v: setattr(
        self, "_friction", friction_value(v)), doc="Coulomb friction coefficient μ ≥ 0.")

    def validate(self, particles: Particles) -> None:
        self._sel.validate(particles)

    def generate(self, particles: Particles, contacts: ContactBuffer) -> None:
        idx = self._sel.indices(particles)
        radius = particles.radius
        idx = idx[radius[idx] > 0.0]
        if idx.size < 2:
            return
        largest = float(radius[idx].max())
        margin = -1.0 if self.margin is None else self.margin
        reach = DEFAULT_MARGIN_FRACTION * largest if self.margin is None else self.margin
        # Speculative reach by speed (Box2D v3's speculative distance): a pair closing by more
        # than its gap within the step is found before it can pass through (r = 0.1 spheres at
        # 100 m/s and dt = 1/60 tunnelled with a fixed margin).
        sweep = _sweep_lengths(particles.velocity, contacts.dt)
        reach += 2.0 * float(sweep[idx].max())
        cell = 2.0 * largest + reach  # a cell holds the whole reach: neighbours are 1 cell away
        start = contacts.count
        # Two tries at most: the first reports how much room it needs if the buffer was short.
        for _ in range(2):
            a, b, n, pen, rest = contacts.raw()
            total = _sphere_pairs(particles.position, particles.velocity, radius,
                                  particles.inv_mass, idx, cell, self._restitution, margin,
                                  DEFAULT_MARGIN_FRACTION, sweep, float(contacts.dt), a, b, n,
                                  pen, rest, contacts.raw_key(), contacts.count)
            if total <= contacts.capacity:
                contacts.count = total
                contacts.raw_friction()[start:total] = self._friction
                return
            contacts.reserve(total - contacts.count)
        raise RuntimeError("sphere contact buffer could not grow")  # unreachable
