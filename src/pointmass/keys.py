"""Contact keys: the identity of a contact across steps, built in one place.

The solver warm-starts a contact with the impulse the contact with the same key needed in the
previous step (``impulse_history.py``), so a key must name the same physical contact every step:

- a sphere pair i < j:             i·2³¹ + j                      (bits 61 and 62 clear)
- a particle on a plane or wall:   bit 62 | plane serial·2³¹ | i
- a link (cable, rod):             bit 61 | link-set serial·2³¹ | link index

  (serials are numbered per world: ``World.add`` gives each plane and link set the next of the
  world's own, so a key depends on nothing outside its world, and a scene built after another
  in the same process gets the keys it gets in a fresh one)
- a rigid-body point:              bit 60 | a·2³⁴ | b·2¹⁴ | feature id (< 2¹⁴), with b the
  other body, or bit 59 set and b the plane's serial for a body on a plane (a, b < 2²⁰)
- a particle on a rigid body:      bit 60 | bit 58 | body·2³⁸ | particle·2³ | feature id (< 8)
  (body < 2²⁰, particle < 2³⁵; bit 59 clear; no other body key sets bit 58)

Keys are non-negative int64; -1 means "no key" (no warm start), as custom generators report.
"""

from __future__ import annotations

from numba import njit

NO_KEY = -1
_PLANE_BIT = 1 << 62
_LINK_BIT = 1 << 61
_SERIAL_MASK = 0x3FFFFFFF
_BODY_BIT = 1 << 60
_BODY_PLANE_BIT = 1 << 59
#: Bodies and plane serials a body key has room for (20 bits each), and feature ids (14 bits).
BODY_KEY_LIMIT = 1 << 20
FEATURE_LIMIT = 1 << 14
_PARTICLE_BODY_BIT = 1 << 58
#: Particles a particle–body key has room for (35 bits), and its feature ids (3 bits).
PARTICLE_KEY_LIMIT = 1 << 35
PARTICLE_FEATURE_LIMIT = 1 << 3


@njit(cache=True, inline="always")
def pair_key(i, j):
    """The key of the contact between particles i and j (i < j, both < 2³¹)."""
    return (i << 31) | j


def plane_key_base(serial: int) -> int:
    """The base of the contacts of the plane numbered ``serial`` in its world; OR the particle
    index into it."""
    return _PLANE_BIT | ((serial & _SERIAL_MASK) << 31)


def link_key_base(serial: int) -> int:
    """The base of the contacts of the link set numbered ``serial`` in its world; OR the link's
    index into it."""
    return _LINK_BIT | ((serial & _SERIAL_MASK) << 31)


@njit(cache=True, inline="always")
def body_pair_key(a, b, feature):
    """The key of contact point ``feature`` (< 2¹⁴) between bodies a and b (each < 2²⁰)."""
    return _BODY_BIT | (a << 34) | (b << 14) | (feature & (FEATURE_LIMIT - 1))


@njit(cache=True, inline="always")
def body_plane_key(a, plane_serial, feature):
    """The key of contact point ``feature`` between body a and the plane of this serial."""
    return (_BODY_BIT | _BODY_PLANE_BIT | (a << 34)
            | ((plane_serial & (BODY_KEY_LIMIT - 1)) << 14) | (feature & (FEATURE_LIMIT - 1)))


@njit(cache=True, inline="always")
def particle_body_key(particle, body, feature):
    """The key of the contact between a particle (< 2³⁵) and body ``body`` (< 2²⁰) at the
    narrow phase's feature id (< 8: ``sphere_box``'s region, 0 for a sphere body)."""
    return (_BODY_BIT | _PARTICLE_BODY_BIT | (body << 38) | (particle << 3)
            | (feature & (PARTICLE_FEATURE_LIMIT - 1)))


def bodies_of_keys(keys):
    """The two bodies (a (M,), b (M,), int64 arrays) each rigid-body key names: a body pair
    (a, b); a body on a plane (a, −1); a particle on a body (−1, body); −1 for other keys."""
    import numpy as np

    keys = np.asarray(keys, dtype=np.int64)
    mask = BODY_KEY_LIMIT - 1
    is_body = (keys >= 0) & ((keys & _BODY_BIT) != 0)
    on_particle = is_body & ((keys & _PARTICLE_BODY_BIT) != 0)
    on_plane = is_body & ~on_particle & ((keys & _BODY_PLANE_BIT) != 0)
    pair = is_body & ~on_particle & ~on_plane
    a = np.where(pair | on_plane, (keys >> 34) & mask, -1)
    b = np.where(pair, (keys >> 14) & mask, np.where(on_particle, (keys >> 38) & mask, -1))
    return a, b


def particle_of_key(key: int) -> int:
    """The particle of a particle–body key (``particle_body_key``)."""
    return (int(key) >> 3) & (PARTICLE_KEY_LIMIT - 1)


def plane_serial(key_base: int) -> int:
    """A plane's serial, from the key base ``plane_key_base`` gave it."""
    return (key_base >> 31) & _SERIAL_MASK
