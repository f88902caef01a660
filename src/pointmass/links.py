"""Cables and rods: hard constraints written as contact generators (Millington's ParticleLinks).

A cable lets its ends move freely closer than ``max_length`` and stops them going further (a
contact pulling them together when over-extended, with restitution). A rod holds its ends at
``length``: it pulls when too long and pushes when too short, with restitution 0. Anchored
versions tie a particle to a fixed point (the contact's second body is scenery, -1).

One object holds many links (index arrays), like the springs.

A rod at its exact length makes no contact (within ``ROD_TOLERANCE``), so when the resolver
projects one rod of a chain it may stretch its neighbour after the contacts were made; the world
therefore regenerates and resolves link contacts for a few extra rounds each step
(``world.LINK_ROUNDS``). Link contacts carry keys, so the sweep resolver warm-starts a link that
stays taut.
"""

from __future__ import annotations

import itertools

import numpy as np

from . import _validate as check
from .contacts import ContactBuffer, ContactGenerator, restitution_value
from .particles import Particles

#: Rods within this fraction of their length count as exact (Cyclone compares floats with ==,
#: so it makes a contact almost every step).
ROD_TOLERANCE = 1e-9

#: Contact keys (see ``ContactBuffer.key``): bit 61, the link set's serial number, the direction
#: (bit 30: a rod pushing) and the link's position in its set; so the sweep resolver warm-starts
#: a link that stays taut from the impulse it needed in the previous step.
_LINK_KEY_BIT = 1 << 61
_PUSH_BIT = 1 << 30
_link_serials = itertools.count()


class _Links(ContactGenerator):
    """Pairs a[k]–b[k] (b may be an anchor) with one length each."""

    refresh = True

    def _init_pairs(self, a, b, lengths, name: str) -> None:
        self._a_given = np.atleast_1d(np.asarray(a))
        self._b_given = np.atleast_1d(np.asarray(b))
        if self._a_given.shape != self._b_given.shape:
            raise ValueError(f"a and b must have the same length, got {self._a_given.shape[0]} "
                             f"and {self._b_given.shape[0]}")
        self.a = self._a_given.astype(np.int64)
        self.b = self._b_given.astype(np.int64)
        self._name = name
        self.lengths_target = lengths
        self._key_base = _new_key_base()

    @property
    def lengths_target(self) -> np.ndarray:
        return self._len

    @lengths_target.setter
    def lengths_target(self, value) -> None:
        self._len = check.scalar_array(value, self._name, self.a.shape[0], low=0.0,
                                       low_open=True)

    def validate(self, particles: Particles) -> None:
        self.a = particles.check_indices(self._a_given, "a")
        self.b = particles.check_indices(self._b_given, "b")
        same = self.a == self.b
        if same.any():
            raise ValueError(f"a link joins particle {int(self.a[same][0])} to itself")

    def _ends(self, particles: Particles) -> tuple[np.ndarray, np.ndarray]:
        p = particles.position
        return p[self.a], p[self.b]

    def current_lengths(self, particles: Particles) -> np.ndarray:
        """Current lengths [m], shape (K,)."""
        pa, pb = self._ends(particles)
        return np.linalg.norm(pb - pa, axis=1)

    def segments(self, particles: Particles):
        pa, pb = self._ends(particles)
        length = np.linalg.norm(pb - pa, axis=1)
        return pa, pb, (length - self._len) / self._len


def _new_key_base() -> int:
    return _LINK_KEY_BIT | ((next(_link_serials) & 0x3FFFFFFF) << 31)


def _unit(vectors: np.ndarray, length: np.ndarray) -> np.ndarray:
    safe = np.where(length > 0, length, 1.0)
    out = vectors / safe[:, None]
    out[length == 0] = (0.0, 1.0, 0.0)
    return out


class Cable(_Links):
    """Cables between particle pairs: never longer than ``max_length``.

    Args:
        a, b: Particle indices (ints or equal-length arrays).
        max_length: Length at which the cable goes taut [m], > 0.
        restitution: Bounce when it snaps taut, in [0, 1].
    """

    kind = "cable"

    def __init__(self, a, b, max_length: float, *, restitution: float = 0.3) -> None:
        self._init_pairs(a, b, max_length, "max_length")
        self.restitution = restitution

    restitution = property(lambda self: self._restitution, lambda self, v: setattr(
        self, "_restitution", restitution_value(v)))

    @property
    def max_length(self) -> np.ndarray:
        return self._len

    def generate(self, particles: Particles, contacts: ContactBuffer) -> None:
        pa, pb = self._ends(particles)
        d = pb - pa
        length = np.linalg.norm(d, axis=1)
        over = length > self._len
        if not over.any():
            return
        # The normal points from b to a's target: a must move toward b.
        contacts.add(self.a[over], self._b_index()[over], _unit(d[over], length[over]),
                     length[over] - self._len[over], self._restitution,
                     self._key_base | np.flatnonzero(over))

    def _b_index(self) -> np.ndarray:
        return self.b


class Rod(_Links):
    """Rigid rods between particle pairs: held at ``length`` both ways (restitution 0).

    Args:
        a, b: Particle indices (ints or equal-length arrays).
        length: Rod length [m], > 0.
    """

    kind = "rod"

    def __init__(self, a, b, length: float) -> None:
        self._init_pairs(a, b, length, "length")

    @property
    def length(self) -> np.ndarray:
        return self._len

    def generate(self, particles: Particles, contacts: ContactBuffer) -> None:
        pa, pb = self._ends(particles)
        d = pb - pa
        length = np.linalg.norm(d, axis=1)
        error = length - self._len
        act = np.abs(error) > ROD_TOLERANCE * self._len
        if not act.any():
            return
        toward_b = _unit(d[act], length[act])
        # Too long: a moves toward b; too short: a moves away from b.
        pulling = error[act] > 0
        sign = np.where(pulling, 1.0, -1.0)
        keys = self._key_base | np.flatnonzero(act) | np.where(pulling, 0, _PUSH_BIT)
        contacts.add(self.a[act], self._b_index()[act], toward_b * sign[:, None],
                     np.abs(error[act]), 0.0, keys)

    def _b_index(self) -> np.ndarray:
        return self.b


class _Anchored:
    """Mix-in: ``b`` is a fixed point (scenery) instead of a particle."""

    def _init_anchor(self, particles, anchor, lengths, name: str) -> None:
        self._a_given = np.atleast_1d(np.asarray(particles))
        self.a = self._a_given.astype(np.int64)
        self.anchor = check.vec3_array(anchor, "anchor", self.a.shape[0]).copy()
        self._name = name
        self.lengths_target = lengths
        self._key_base = _new_key_base()

    def validate(self, particles: Particles) -> None:
        self.a = particles.check_indices(self._a_given, "particles")

    def _ends(self, particles: Particles) -> tuple[np.ndarray, np.ndarray]:
        return particles.position[self.a], self.anchor

    def _b_index(self) -> np.ndarray:
        return np.full(self.a.shape[0], -1, np.int64)


class AnchoredCable(_Anchored, Cable):
    """Cables from particles to fixed anchor points (Cyclone's ParticleCableConstraint).

    Args:
        particles: Particle indices (an int or an array of K).
        anchor: Anchor points [m], a 3-vector or shape (K, 3).
        max_length, restitution: As for ``Cable``.
    """

    def __init__(self, particles, anchor, max_length: float, *,
                 restitution: float = 0.3) -> None:
        self._init_anchor(particles, anchor, max_length, "max_length")
        self.restitution = restitution


class AnchoredRod(_Anchored, Rod):
    """Rods from particles to fixed anchor points (Cyclone's ParticleRodConstraint)."""

    def __init__(self, particles, anchor, length: float) -> None:
        self._init_anchor(particles, anchor, length, "length")
