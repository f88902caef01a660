"""Collision detection: contact generators for planes, boxes and sphere–sphere pairs.

These only *find* contacts; the resolver resolves them. Sphere–sphere pairs come from a uniform
grid, searched again only when the spheres have moved far enough to need it
(``sphere_pairs.py``), so finding pairs costs O(N) for evenly spread spheres instead of the
O(N²) pair loop of Cyclone's demos.

**Contact margin (speculative contacts).** A pair is reported not only when it overlaps but also
when its gap is smaller than a margin (by default 2 % of the radius), with a negative
penetration. Cyclone reports only overlapping pairs, so when the resolver pushes one sphere out of
another it pushes it into a third that was exactly touching but not in the list: a stack of
spheres then sinks and oscillates for ever (measured: a 5-sphere stack sank 0.28 radius and
never came to rest). With the margin the touching neighbours are in the list, their penetration is
updated as particles move, and the resolver treats a gap contact as a collision only if it would
close within the step (see ``resolver.py``) — the speculative contacts of Box2D and Bullet.

**Friction.** Every generator takes ``friction`` μ ≥ 0 (default 0, frictionless as in the book):
the Coulomb coefficient written into each contact it reports (see ``resolver.py``).

**Materials of planes for rigid bodies.** A ``Plane``/``Ground`` left at its default material
(``friction`` and ``restitution`` not given) is neutral for rigid bodies: a body touching it
uses its own μ and e (``World.add_body``'s ``friction=0.5, restitution=0``), so a box on a
default ground grips and settles, while particles keep the book's numbers (μ = 0, e = 0.5). A
value given (or set later) applies to both, and a body's contact combines it with its own:
μ = √(μ_body·μ_plane), e = max(e_body, e_plane), as between two bodies.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator

import numpy as np
from numba import njit

from . import _validate as check
from .contacts import ContactBuffer, ContactGenerator, friction_value, restitution_value
from .forces import _Selection
from .keys import plane_key_base, plane_serial
from .particles import Particles
from .sphere_pairs import PairList, pair_contacts, sweep_lengths

#: The material a plane left at its defaults gives particle contacts: the book's e = 0.5 and no
#: friction (the cookbook's numbers). Rigid bodies use their own material on such a plane.
PARTICLE_RESTITUTION = 0.5
PARTICLE_FRICTION = 0.0

#: Default contact margin, as a fraction of each particle's radius (see the module docstring).
#: Fast pairs are found by their sweep (|v|·dt) whatever the margin; the margin only has to
#: catch slow neighbours the solver may push together. Measured on the 10 000-sphere pit:
#: 5 % gave 35 000 rows, ~6 600 of them never active in a step; 2 % gives 32 900 and a step
#: ~10 % faster, with the same overlaps and mean speed (1 000-sphere pit, seeds 0-5: mean |v|
#: 0.036-0.084 against 0.044-0.14, overlap 0.45-1.1 mm against 0.57-1.7); 1 % let the
#: overlap grow (0.8 -> 3 mm).
DEFAULT_MARGIN_FRACTION = 0.02




def _margin_value(value) -> float | None:
    return None if value is None else check.scalar(value, "margin", low=0.0)


@njit(cache=True, nogil=True)
def _plane_contacts(pos, radius, inv_mass, idx, normal, offset, margin, margin_fraction,
                    restitution, key_base, out_a, out_b, out_n, out_pen, out_rest, out_key,
                    start):
    """Contacts of the movable particles ``idx`` whose gap to the plane is below the margin
    (``margin`` [m], or when negative ``margin_fraction`` × radius). Written from ``start``;
    returns the count written or needed (if it exceeds the buffer, call again with more room)."""
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
        restitution: In [0, 1]; None (the default): 0.5 for particles, and each rigid body's
            own for bodies (see the module docstring, "Materials").
        particles: Indices that collide with it, or None for all.
        margin: Report a contact when the gap is below this [m], ≥ 0 (a speculative contact
            with negative penetration); None: 2 % of each particle's radius.
        friction: Coulomb friction coefficient μ ≥ 0; None (the default): 0 (frictionless)
            for particles, and each rigid body's own for bodies.
    """

    #: The μ and e rigid bodies combine with theirs (√(μa·μb), the larger e), or None when
    #: not set: each body then keeps its own.
    body_friction: float | None
    body_restitution: float | None

    def __init__(self, normal=(0.0, 1.0, 0.0), offset: float = 0.0, *,
                 restitution: float | None = None, particles=None, margin: float | None = None,
                 friction: float | None = None) -> None:
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
        self._key_base = plane_key_base(0)  # until a world numbers it (claim_keys)

    def claim_keys(self, serials: Iterator[int]) -> None:
        self._key_base = plane_key_base(next(serials))

    @property
    def restitution(self) -> float:
        """Coefficient of restitution [0, 1] of particle contacts (0.5 unless set)."""
        return self._restitution

    @restitution.setter
    def restitution(self, value: float | None) -> None:
        if value is None:
            self._restitution, self.body_restitution = PARTICLE_RESTITUTION, None
        else:
            self._restitution = self.body_restitution = restitution_value(value)

    @property
    def friction(self) -> float:
        """Coulomb friction coefficient μ ≥ 0 of particle contacts (0 unless set)."""
        return self._friction

    @friction.setter
    def friction(self, value: float | None) -> None:
        if value is None:
            self._friction, self.body_friction = PARTICLE_FRICTION, None
        else:
            self._friction = self.body_friction = friction_value(value)

    @property
    def serial(self) -> int:
        """This plane's number, unique in its world (``claim_keys``): rigid-body contact keys
        name it."""
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

    def __init__(self, height: float = 0.0, *, restitution: float | None = None, particles=None,
                 margin: float | None = None, friction: float | None = None) -> None:
        super().__init__((0.0, 1.0, 0.0), height, restitution=restitution, particles=particles,
                         margin=margin, friction=friction)

    @property
    def height(self) -> float:
        return self.offset


class BoxContainer(ContactGenerator):
    """The inside of an axis-aligned box that keeps particles in: a floor, four walls and
    optionally a ceiling. (Formerly ``pointmass.Box``; that name is now the rigid-body shape,
    ``pointmass.rigid.shapes.Box``.)

    Args:
        low, high: Opposite corners [m]; low < high on every axis.
        restitution: In [0, 1] (None: 0.5, as ``Plane``).
        ceiling: Also keep particles below ``high[1]``.
        particles: Indices that collide with it, or None for all.
        margin: Contact margin [m], as for ``Plane``.
        friction: Coulomb friction coefficient μ ≥ 0 of every face (None: 0, frictionless).
    """

    def __init__(self, low=(-5.0, 0.0, -5.0), high=(5.0, 10.0, 5.0), *,
                 restitution: float | None = None, ceiling: bool = False, particles=None,
                 margin: float | None = None, friction: float | None = None) -> None:
        self.low = check.vec3(low, "low")
        self.high = check.vec3(high, "high")
        if not (self.low < self.high).all():
            raise ValueError(f"low must be below high on every axis, got {self.low} and "
                             f"{self.high}")
        faces = [((0, 1, 0), self.low[1]), ((1, 0, 0), self.low[0]), ((-1, 0, 0), -self.high[0]),
                 ((0, 0, 1), self.low[2]), ((0, 0, -1), -self.high[2])]
        if ceiling:
            faces.append(((0, -1, 0), -self.high[1]))
        friction = None if friction is None else friction_value(friction)
        self.planes = [Plane(n, d, restitution=restitution, particles=particles, margin=margin,
                             friction=friction) for n, d in faces]
        self.claim_keys(itertools.count())  # its faces apart until a world numbers them
        self.ceiling = ceiling

    def claim_keys(self, serials: Iterator[int]) -> None:
        for plane in self.planes:
            plane.claim_keys(serials)

    @property
    def restitution(self) -> float:
        return self.planes[0].restitution

    @restitution.setter
    def restitution(self, value: float | None) -> None:
        for plane in self.planes:
            plane.restitution = value

    @property
    def friction(self) -> float:
        return self.planes[0].friction

    @friction.setter
    def friction(self, value: float | None) -> None:
        value = None if value is None else friction_value(value)
        for plane in self.planes:
            plane.friction = value

    def validate(self, particles: Particles) -> None:
        for plane in self.planes:
            plane.validate(particles)

    def generate(self, particles: Particles, contacts: ContactBuffer) -> None:
        for plane in self.planes:
            plane.generate(particles, contacts)


# --- sphere–sphere pairs (sphere_pairs.py) -----------------------------------------------------

class SphereCollisions(ContactGenerator):
    """Collisions between all particles with radius > 0 (or a chosen subset).

    Args:
        restitution: In [0, 1].
        particles: Indices that collide with each other, or None for every particle with
            radius > 0.
        margin: Report pairs whose gap is below this [m], ≥ 0 (speculative contacts with
            negative penetration); None: 2 % of the larger radius of each pair.
        friction: Coulomb friction coefficient μ ≥ 0 between spheres (0: frictionless).
    """

    def __init__(self, *, restitution: float = 0.5, particles=None,
                 margin: float | None = None, friction: float = 0.0) -> None:
        self.restitution = restitution
        self.friction = friction
        self.margin = _margin_value(margin)
        self._sel = _Selection(particles)
        self._pairs = PairList()  # candidate pairs kept between steps (sphere_pairs.py)

    @property
    def restitution(self) -> float:
        """Coefficient of restitution [0, 1]."""
        return self._restitution

    @restitution.setter
    def restitution(self, value: float) -> None:
        self._restitution = restitution_value(value)

    @property
    def friction(self) -> float:
        """Coulomb friction coefficient μ ≥ 0."""
        return self._friction

    @friction.setter
    def friction(self, value: float) -> None:
        self._friction = friction_value(value)

    def validate(self, particles: Particles) -> None:
        self._sel.validate(particles)

    def generate(self, particles: Particles, contacts: ContactBuffer) -> None:
        idx = self._sel.indices(particles)
        radius = particles.radius
        idx = idx[radius[idx] > 0.0]
        if idx.size < 2:
            return
        margin = -1.0 if self.margin is None else self.margin
        # Speculative reach by speed (Box2D v3's speculative distance): a pair closing by more
        # than its gap within the step is found before it can pass through (r = 0.1 spheres at
        # 100 m/s and dt = 1/60 tunnelled with a fixed margin).
        sweep = sweep_lengths(particles.velocity, contacts.dt)
        lo, hi = self._pairs.pairs(particles.position, radius, idx, margin,
                                   DEFAULT_MARGIN_FRACTION, sweep)
        start = contacts.count
        contacts.reserve(lo.shape[0])
        a, b, n, pen, rest = contacts.raw()
        contacts.count = pair_contacts(particles.position, particles.velocity, radius,
                                       particles.inv_mass, lo, hi, self._restitution, margin,
                                       DEFAULT_MARGIN_FRACTION, sweep, float(contacts.dt), a, b,
                                       n, pen, rest, contacts.raw_key(), start)
        contacts.raw_friction()[start:contacts.count] = self._friction
