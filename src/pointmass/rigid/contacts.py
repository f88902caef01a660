"""The contact points of rigid bodies, struct-of-arrays, as the solver reads them.

A row is one point of a manifold (``manifold.py``): body ``a`` is pushed along ``normal``, body
``b`` (or the scenery when ``b`` is -1) along −normal, at lever arms ``r_a`` and ``r_b`` from
their centres of mass to the point. A particle contact is the same row with both arms zero; the
particles keep their own buffer (``pointmass.contacts``) because their generators write into it
in place.
"""

from __future__ import annotations

import numpy as np


class BodyContacts:
    """The contact points of one substep (rebuilt every substep).

    Attributes (the first ``count`` rows):
        a, b: Bodies, shape (M,), int64; b = -1 for scenery (a plane). A particle–body row
            (``particle_body.py``) comes after the body rows with ``a`` ≥ the body count: an
            index into the solver's packed view, not a particle index (the particle is
            ``keys.particle_of_key(key)``).
        normal: Unit normal from b to a, shape (M, 3).
        r_a, r_b: Lever arms from each centre of mass to the point [m], shape (M, 3) (r_b is the
            world point itself when b is scenery).
        depth: Penetration [m] when found, shape (M,); < 0 a speculative gap.
        friction: Coulomb μ of the point, shape (M,).
        restitution: Coefficient of restitution, shape (M,).
        key: Identity across steps (``pointmass.keys``) for warm starting, shape (M,), int64.
        impulse: The normal impulse [N·s] the body stage gave each point over the whole step,
            shape (M,), filled after the solve (0 before): with the soft step the sum over its
            substeps and the restitution (Box2D's ``totalNormalImpulse``), not the warm start
            (``World.body_impulses`` keeps one substep's impulse, what the next step starts
            from). A pair's Σ is the impulse of their collision this step.
    """

    #: The per-row arrays (``trim`` and ``keep`` cut them all).
    FIELDS = ("a", "b", "normal", "r_a", "r_b", "depth", "friction", "restitution", "key",
              "impulse")

    def __init__(self, capacity: int = 0) -> None:
        self.count = 0
        self._room: tuple | None = None  # ``room``'s buffers
        self.resize(capacity)

    def resize(self, capacity: int) -> None:
        """Room for ``capacity`` rows; the contents are dropped (``count`` = 0) and the rows
        are not cleared: a writer fills rows from 0 and ``trim`` keeps those (the room is an
        upper bound, ~30 000 rows for the 1000-box pit, and clearing it was 3 % of its step)."""
        self.count = 0
        self.a = np.empty(capacity, np.int64)
        self.b = np.empty(capacity, np.int64)
        self.normal = np.empty((capacity, 3))
        self.r_a = np.empty((capacity, 3))
        self.r_b = np.empty((capacity, 3))
        self.depth = np.empty(capacity)
        self.friction = np.empty(capacity)
        self.restitution = np.empty(capacity)
        self.key = np.empty(capacity, np.int64)
        self.impulse = np.zeros(capacity)  # calloc: no pass over the room

    def room(self, rows: int) -> tuple:
        """Buffers (a, b, normal, r_a, r_b, depth, friction, restitution, key) with at least
        ``rows`` rows, for a kernel to write a step's rows into (``take_room`` then holds
        them). They are kept from step to step, grown to twice what is asked when too small:
        a step allocates nothing for its rows. The rows of a step are views of them, so they
        hold until the next step's collision writes the buffers again."""
        held = self._room
        if held is None or held[0].shape[0] < rows:
            size = max(2 * rows, 16)
            held = (np.empty(size, np.int64), np.empty(size, np.int64), np.empty((size, 3)),
                    np.empty((size, 3)), np.empty((size, 3)), np.empty(size), np.empty(size),
                    np.empty(size), np.empty(size, np.int64))
            self._room = held
        return held

    def take_room(self, count: int) -> None:
        """Hold the first ``count`` rows that a kernel wrote into ``room``'s buffers, and no
        others; the impulses are 0 until the solve."""
        a, b, normal, r_a, r_b, depth, friction, restitution, key = self._room
        self.count = count
        self.a, self.b, self.normal, self.r_a, self.r_b = (a[:count], b[:count], normal[:count],
                                                           r_a[:count], r_b[:count])
        self.depth, self.friction = depth[:count], friction[:count]
        self.restitution, self.key = restitution[:count], key[:count]
        self.impulse = np.zeros(count)

    def trim(self, count: int) -> None:
        """Keep the first ``count`` rows as views (after a kernel wrote them)."""
        self.count = count
        for name in self.FIELDS:
            setattr(self, name, getattr(self, name)[:count])

    def keep(self, rows: np.ndarray) -> None:
        """Keep only the rows where the mask ``rows`` (count,) is True, in order."""
        self.count = int(np.count_nonzero(rows))
        for name in self.FIELDS:
            setattr(self, name, getattr(self, name)[rows])

    def __len__(self) -> int:
        return self.count
