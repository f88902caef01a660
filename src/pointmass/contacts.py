"""Contacts and the contact-generator interface.

A contact says that particle ``a`` must move along ``normal`` away from ``b`` (another particle,
or ``-1`` for scenery such as the ground): the normal points from b to a. ``penetration`` [m] is
how far they overlap (negative: a gap, as a slack rod reports), ``restitution`` in [0, 1] how
much closing speed comes back as separating speed, and ``friction`` μ ≥ 0 is the Coulomb friction
coefficient: the tangential impulse a contact may apply is at most μ × its normal impulse (0, the
default: frictionless, as in the book).

Contacts are stored as a struct of arrays (``ContactBuffer``) so the compiled resolver reads them
directly; generators append many at once.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from . import _validate as check
from .particles import Particles


class ContactBuffer:
    """A growable struct-of-arrays list of contacts, cleared at every step.

    Attributes (views of the first ``count`` rows):
        a: First particle, shape (M,), int64.
        b: Second particle or -1 for scenery, shape (M,), int64.
        normal: Unit normal from b to a, shape (M, 3).
        penetration: Overlap depth [m], shape (M,).
        restitution: Coefficient of restitution in [0, 1], shape (M,).
        friction: Coulomb friction coefficient μ ≥ 0, shape (M,); 0 (the default) for none.
        bilateral: True for a two-way constraint (a rod): its impulse may pull as well as push
            and its depth may be negative (too short) as well as positive, shape (M,), bool.
        key: Identity of the contact across steps, shape (M,), int64; -1 for none. The solver
            warm-starts a contact with the impulse that the contact with the same key needed in
            the previous step (``pointmass.keys`` builds them, ``impulse_history.py`` keeps them).
        anchors: For contacts against scenery that is a point (an anchored cable or rod), that
            point, shape (M, 3), NaN for the other rows; None when no row has one. The solver
            measures such a contact again from the point where its particle has moved
            (``solver/remeasure.py``), as it does a contact between two particles.
    """

    # The storage ``_alloc`` makes (declared for type checkers).
    _a: np.ndarray
    _b: np.ndarray
    _normal: np.ndarray
    _penetration: np.ndarray
    _restitution: np.ndarray
    _key: np.ndarray
    _friction: np.ndarray
    _bilateral: np.ndarray
    _anchor: np.ndarray

    def __init__(self, capacity: int = 64) -> None:
        self.count = 0
        #: The step these contacts are for [s] (the world sets it; 0: no speculative reach by
        #: speed, for contacts found outside a step).
        self.dt = 0.0
        self._anchored = False  # some row since the last clear has an anchor point
        self._alloc(max(int(capacity), 1))

    def _alloc(self, capacity: int) -> None:
        n = self.count
        old = getattr(self, "_a", None)
        a = np.zeros(capacity, np.int64)
        b = np.full(capacity, -1, np.int64)
        normal = np.zeros((capacity, 3))
        pen = np.zeros(capacity)
        rest = np.zeros(capacity)
        key = np.full(capacity, -1, np.int64)
        friction = np.zeros(capacity)
        bilateral = np.zeros(capacity, np.bool_)
        anchor = np.full((capacity, 3), np.nan)
        if old is not None:
            anchor[:n] = self._anchor[:n]
            bilateral[:n] = self._bilateral[:n]
            key[:n] = self._key[:n]
            friction[:n] = self._friction[:n]
            a[:n], b[:n] = self._a[:n], self._b[:n]
            normal[:n], pen[:n], rest[:n] = self._normal[:n], self._penetration[:n], \
                self._restitution[:n]
        self._a, self._b, self._normal = a, b, normal
        self._penetration, self._restitution, self._key = pen, rest, key
        self._friction = friction
        self._bilateral = bilateral
        self._anchor = anchor
        self.capacity = capacity

    def reserve(self, extra: int) -> None:
        """Make room for ``extra`` more contacts."""
        need = self.count + extra
        if need > self.capacity:
            self._alloc(max(need, 2 * self.capacity))

    def clear(self) -> None:
        # Zero the friction of the old rows: a compiled generator that writes through ``raw()``
        # and knows nothing of friction then leaves frictionless contacts, not stale ones.
        if self.count:  # (no slicing for an empty buffer: a tiny world's step clears one)
            self._friction[: self.count] = 0.0
            self._bilateral[: self.count] = False
            if self._anchored:  # (only then: the pit's 35 000 rows never have one)
                self._anchor[: self.count] = np.nan
                self._anchored = False
            self.count = 0

    def __len__(self) -> int:
        return self.count

    @property
    def a(self) -> np.ndarray:
        return self._a[: self.count]

    @property
    def b(self) -> np.ndarray:
        return self._b[: self.count]

    @property
    def normal(self) -> np.ndarray:
        return self._normal[: self.count]

    @property
    def penetration(self) -> np.ndarray:
        return self._penetration[: self.count]

    @property
    def restitution(self) -> np.ndarray:
        return self._restitution[: self.count]

    @property
    def key(self) -> np.ndarray:
        return self._key[: self.count]

    @property
    def friction(self) -> np.ndarray:
        return self._friction[: self.count]

    @property
    def bilateral(self) -> np.ndarray:
        return self._bilateral[: self.count]

    @property
    def anchors(self) -> np.ndarray | None:
        return self._anchor[: self.count] if self._anchored else None

    def add(self, a, b, normal, penetration, restitution, key=-1, *, friction=0.0,
            bilateral=False, anchor=None) -> None:
        """Append contacts; each argument is one value or an array of length K (broadcast).
        ``key`` identifies a contact across steps (-1: none, no warm start); ``friction`` is the
        Coulomb coefficient μ ≥ 0 (0: frictionless); ``bilateral`` makes a two-way constraint
        (a rod: held at depth 0 from both sides); ``anchor`` (K, 3) is the scenery point of
        contacts with b = -1 whose normal lies along the line from it to a (see ``anchors``)."""
        a = np.atleast_1d(np.asarray(a, np.int64))
        k = a.shape[0]
        if k == 0:
            return
        if not (isinstance(friction, float) and friction == 0.0):
            friction = np.asarray(friction, np.float64)
            if not (np.isfinite(friction).all() and (friction >= 0.0).all()):
                raise ValueError(f"friction must be finite and >= 0, got {friction!r}")
        self.reserve(k)
        s = slice(self.count, self.count + k)
        self._a[s] = a
        self._b[s] = b
        self._normal[s] = normal
        self._penetration[s] = penetration
        self._restitution[s] = restitution
        self._key[s] = key
        self._friction[s] = friction
        self._bilateral[s] = bilateral
        if anchor is not None:
            self._anchor[s] = anchor
            self._anchored = True
        self.count += k

    def raw(self) -> tuple[np.ndarray, ...]:
        """The full backing arrays (a, b, normal, penetration, restitution) for compiled kernels
        that append in place; set ``count`` afterwards (and ``raw_key`` for keys)."""
        return self._a, self._b, self._normal, self._penetration, self._restitution

    def raw_key(self) -> np.ndarray:
        """The full backing array of ``key``."""
        return self._key

    def raw_friction(self) -> np.ndarray:
        """The full backing array of ``friction`` (rows a kernel leaves alone stay 0)."""
        return self._friction


class ContactGenerator:
    """Something that finds contacts (hard constraints): collisions, cables, rods.

    Subclasses implement ``generate``; it appends to ``contacts`` and never resolves anything.
    Custom generators (the blob demo's platforms) subclass this too.
    """

    #: Drawing hint for renderers: "cable", "rod" or None (not drawn as lines).
    kind: str | None = None

    def generate(self, particles: Particles, contacts: ContactBuffer) -> None:
        raise NotImplementedError

    def validate(self, particles: Particles) -> None:
        """Check particle indices when added to a world (raise naming the bad parameter)."""

    def claim_keys(self, serials: Iterator[int]) -> None:
        """Take the contact-key serials this generator needs (``pointmass.keys``) from
        ``serials``, the world's own numbering: ``World.add`` calls it. A generator whose keys
        need no serial (or that reports none) takes nothing."""

    def segments(self, particles: Particles) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """Line segments a renderer may draw: (start (K,3), end (K,3), strain (K,)) or None."""
        return None


def restitution_value(value, name: str = "restitution") -> float:
    """A coefficient of restitution, checked to lie in [0, 1]."""
    return check.scalar(value, name, low=0.0, high=1.0)


def friction_value(value, name: str = "friction") -> float:
    """A Coulomb friction coefficient, checked to be finite and ≥ 0."""
    return check.scalar(value, name, low=0.0)
