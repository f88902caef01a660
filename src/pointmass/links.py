"""Cables and rods: hard constraints written as contact generators (Millington's ParticleLinks).

A cable lets its ends move freely closer than ``max_length`` and stops them going further (a
contact pulling them together when over-extended, with restitution). A rod holds its ends at
``length``: it pulls when too long and pushes when too short, with restitution 0. Anchored
versions tie a particle to a fixed point (the contact's second body is scenery, -1).

One object holds many links (index arrays), like the springs.

A rod reports one *bilateral* contact every step, with its signed error as depth (positive when
too long, negative when too short): its impulse may pull or push, so it holds the rod both ways,
and it carries a key, so the solver warm-starts a loaded rod from last step's impulse (a rod
that reported nothing at its exact length lost its impulse every other step, and a heavy chain
sagged). A cable reports a
contact once it is within ``CABLE_MARGIN`` of taut (a speculative contact that acts only if it
would go taut within the step), so a taut cable keeps its warm start too.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from . import _validate as check
from .contacts import ContactBuffer, ContactGenerator, restitution_value
from .keys import link_key_base
from .particles import Particles

#: A cable reports a (speculative) contact once slack by less than this fraction of its length.
CABLE_MARGIN = 0.01



class _Links(ContactGenerator):
    """Pairs a[k]–b[k] (b may be an anchor) with one length each."""

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
        self._key_base = link_key_base(0)  # until a world numbers it (claim_keys)

    def claim_keys(self, serials: Iterator[int]) -> None:
        self._key_base = link_key_base(next(serials))

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

    def _anchors(self) -> np.ndarray | None:
        """The scenery points of the b ends (None: b ends are particles)."""
        return None

    def current_lengths(self, particles: Particles) -> np.ndarray:
        """Current lengths [m], shape (K,)."""
        pa, pb = self._ends(particles)
        return np.linalg.norm(pb - pa, axis=1)

    def segments(self, particles: Particles):
        pa, pb = self._ends(particles)
        length = np.linalg.norm(pb - pa, axis=1)
        return pa, pb, (length - self._len) / self._len


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

    @property
    def restitution(self) -> float:
        return self._restitution

    @restitution.setter
    def restitution(self, value: float) -> None:
        self._restitution = restitution_value(value)

    @property
    def max_length(self) -> np.ndarray:
        return self._len

    def generate(self, particles: Particles, contacts: ContactBuffer) -> None:
        pa, pb = self._ends(particles)
        d = pb - pa
        length = np.linalg.norm(d, axis=1)
        over = length > self._len * (1.0 - CABLE_MARGIN)
        if not over.any():
            return
        # The normal points from b to a's target: a must move toward b.
        anchors = self._anchors()
        contacts.add(self.a[over], self._b_index()[over], _unit(d[over], length[over]),
                     length[over] - self._len[over], self._restitution,
                     self._key_base | np.flatnonzero(over),
                     anchor=None if anchors is None else anchors[over])

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
        # The normal points from b toward a's target: a moves toward b when the rod is too long.
        contacts.add(self.a, self._b_index(), _unit(d, length), error, 0.0,
                     self._key_base | np.arange(self.a.shape[0]), bilateral=True,
                     anchor=self._anchors())

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
        self._key_base = link_key_base(0)  # until a world numbers it (claim_keys)

    def validate(self, particles: Particles) -> None:
        self.a = particles.check_indices(self._a_given, "particles")

    def _ends(self, particles: Particles) -> tuple[np.ndarray, np.ndarray]:
        return particles.position[self.a], self.anchor

    def _b_index(self) -> np.ndarray:
        return np.full(self.a.shape[0], -1, np.int64)

    def _anchors(self) -> np.ndarray:
        return self.anchor


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
