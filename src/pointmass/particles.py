"""Particles stored as a struct of arrays: one row per particle, one array per quantity.

A particle is an index into these arrays. ``Particle`` gives the cookbook's object-style access
(``p.position``, ``p.velocity``, ``p.mass``) on top of them, for users coming from its ``Particle``.

The arrays grow as particles are added (capacity doubles), so a property such as ``position``
returns a view of the first ``count`` rows: read it again after adding particles.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from . import _validate as check
from ._rows import RowViews, view

#: Below this many particles the per-particle passes (the integration, the kinetic energy) run
#: on one core: starting threads costs more than it saves (measured ~2 ms per call on a busy
#: 2-core machine, against microseconds).
PARALLEL_MIN_PARTICLES = 50_000
#: Particles per chunk of those passes. Chunks, not threads, split the work, so a sum adds the
#: same numbers in the same order whatever the thread count.
CHUNK = 8192

_FIELDS_3 = ("position", "velocity", "force", "acceleration")
_FIELDS_1 = ("inv_mass", "radius", "damping")
#: Sleep state (``particle_sleep.py``), kept in snapshots like the rest: whether each particle
#: moves, how long it has been still, the island it fell asleep with, where its still-time
#: counts from, and the force the generators gave it when it fell asleep.
_SLEEP_3 = ("still_position", "rest_force")
_SLEEP_1 = ("awake", "sleep_time", "island", "rest_inv_mass")
_ALL = _FIELDS_3 + _FIELDS_1 + _SLEEP_3 + _SLEEP_1
_DTYPES = {"awake": np.bool_, "island": np.int64}
#: Fill values of a new row (0 for the rest).
_FILL = {"damping": 1.0, "awake": True, "island": -1}


class Particles(RowViews):
    """All particles of a world, struct-of-arrays.

    Attributes (views of the first ``count`` rows):
        position: Positions [m], shape (N, 3), float64.
        velocity: Velocities [m/s], shape (N, 3).
        force: Force accumulator [N], shape (N, 3); the integration reads and clears it, so a
            force added before a step acts in it (in its first substep).
        acceleration: Acceleration used by the last integration [m/s²], shape (N, 3); the
            resolver's resting-contact test reads it. The world stores it only when it has
            contact generators or rigid bodies (its readers); otherwise it is left as it was.
        inv_mass: Inverse mass [1/kg], shape (N,); 0 means infinite mass (immovable).
        radius: Collision radius [m], shape (N,); 0 means a point that never collides as a sphere.
        damping: Fraction of velocity kept per second, in [0, 1], shape (N,); 1 means none.
        awake: Whether each particle moves, shape (N,), bool. A sleeping particle (``World(
            sleep=True)``, ``particle_sleep.py``) has zero velocity, is not integrated and is in
            no contact that the solver sees; it wakes with its island. Immovable particles are
            always awake.
        sleep_time: Seconds each awake particle has been still [s], shape (N,).
        still_position: Where its still-time counts from [m], shape (N, 3) (a sleeping
            particle's pose: writing ``position`` wakes it).
        rest_force: The force [N] the generators gave it when it fell asleep, shape (N, 3): a
            different force on a sleeping particle wakes it.
        rest_inv_mass: Its inverse mass when it fell asleep, shape (N,): a mass changed since
            (a demo's load spread over particles as mass) wakes it.
        island: The island a sleeping particle fell asleep with, -1 while awake, shape (N,).
    """

    # The storage ``_alloc`` makes (setattr by name; declared for type checkers).
    _position: np.ndarray
    _velocity: np.ndarray
    _force: np.ndarray
    _acceleration: np.ndarray
    _inv_mass: np.ndarray
    _radius: np.ndarray
    _damping: np.ndarray
    _awake: np.ndarray
    _sleep_time: np.ndarray
    _island: np.ndarray
    _still_position: np.ndarray
    _rest_force: np.ndarray
    _rest_inv_mass: np.ndarray

    def __init__(self, capacity: int = 16) -> None:
        self._count = 0
        self._alloc(max(int(capacity), 1))

    # -- storage -------------------------------------------------------------------------------
    def _alloc(self, capacity: int) -> None:
        old = {name: getattr(self, "_" + name, None) for name in _ALL}
        n = self._count
        for name in _ALL:
            wide = name in _FIELDS_3 or name in _SLEEP_3
            arr: np.ndarray = np.zeros((capacity, 3) if wide else capacity,
                                       _DTYPES.get(name, np.float64))
            if name in _FILL:
                arr[:] = _FILL[name]
            previous = old[name]
            if previous is not None:
                arr[:n] = previous[:n]
            setattr(self, "_" + name, arr)
        self._capacity = capacity
        self._refresh_views()

    def _reserve(self, extra: int) -> None:
        need = self._count + extra
        if need > self._capacity:
            self._alloc(max(need, 2 * self._capacity))

    @property
    def count(self) -> int:
        """Number of particles."""
        return self._count

    def __len__(self) -> int:
        return self._count

    _VIEW_FIELDS = _ALL
    position = view("position", doc="Positions [m], (N, 3).")
    velocity = view("velocity", doc="Velocities [m/s], (N, 3).")
    force = view("force", doc="Force accumulator [N], (N, 3).")
    acceleration = view("acceleration",
                        doc="Acceleration of the last integration [m/s²], (N, 3).")
    inv_mass = view("inv_mass", doc="Inverse mass [1/kg], (N,).")
    radius = view("radius", doc="Radius [m], (N,).")
    damping = view("damping", doc="Fraction of velocity kept per second, (N,).")
    awake = view("awake", doc="Whether each particle moves (not asleep), (N,) bool.")
    sleep_time = view("sleep_time", doc="Seconds each awake particle has been still [s], (N,).")
    island = view("island", doc="A sleeping particle's island, -1 awake, (N,).")
    still_position = view("still_position", doc="Where the still-time counts from [m], (N, 3).")
    rest_force = view("rest_force", doc="The generators' force when it fell asleep [N], (N, 3).")
    rest_inv_mass = view("rest_inv_mass", doc="Inverse mass when it fell asleep [1/kg], (N,).")

    @property
    def mass(self) -> np.ndarray:
        """Masses [kg], shape (N,); ``inf`` for immovable particles. A copy."""
        with np.errstate(divide="ignore"):
            return np.where(self.inv_mass > 0, 1.0 / np.where(self.inv_mass > 0, self.inv_mass, 1),
                            np.inf)

    # -- adding --------------------------------------------------------------------------------
    def add(self, position=(0.0, 0.0, 0.0), velocity=(0.0, 0.0, 0.0), *, mass: float = 1.0,
            radius: float = 0.0, damping: float = 1.0) -> int:
        """Add one particle and return its index.

        Args:
            position: Initial position [m].
            velocity: Initial velocity [m/s].
            mass: Mass [kg], in (0, inf]; ``math.inf`` makes it immovable.
            radius: Collision radius [m], ≥ 0.
            damping: Fraction of velocity kept per second, in [0, 1].
        """
        return int(self.add_many([position], [velocity], masses=mass, radii=radius,
                                 damping=damping)[0])

    def add_many(self, positions, velocities=None, *, masses=1.0, radii=0.0,
                 damping=1.0) -> np.ndarray:
        """Add many particles at once; returns their indices, shape (K,), int64.

        ``positions`` has shape (K, 3); ``velocities`` (K, 3) or ``None`` for rest; ``masses``,
        ``radii`` and ``damping`` are numbers or arrays of shape (K,), with the ranges of ``add``.
        """
        pos = check.vec3_array(positions, "position")
        k = pos.shape[0]
        vel = (np.zeros((k, 3)) if velocities is None
               else check.vec3_array(velocities, "velocity", k))
        inv = inverse_masses(masses, k)
        rad = check.scalar_array(radii, "radius", k, low=0.0)
        damp = check.scalar_array(damping, "damping", k, low=0.0, high=1.0)
        self._reserve(k)
        s = slice(self._count, self._count + k)
        self._position[s] = pos
        self._velocity[s] = vel
        self._force[s] = 0.0
        self._acceleration[s] = 0.0
        self._inv_mass[s] = inv
        self._radius[s] = rad
        self._damping[s] = damp
        self._awake[s] = True
        self._sleep_time[s] = 0.0
        self._island[s] = -1
        self._still_position[s] = pos
        self._rest_force[s] = 0.0
        self._count += k
        self._refresh_views()
        return np.arange(s.start, s.stop, dtype=np.int64)

    # -- single-particle access ----------------------------------------------------------------
    def __getitem__(self, index: int) -> Particle:
        return Particle(self, self.check_index(index))

    def check_index(self, index, name: str = "particle") -> int:
        """``index`` as an int if it names a particle, else an IndexError naming ``name``."""
        if isinstance(index, Particle):
            index = index.checked(self, name)
        if isinstance(index, bool) or not isinstance(index, (int, np.integer)):
            raise TypeError(f"{name} must be a particle index (int), got {index!r}")
        if not 0 <= index < self._count:
            raise IndexError(f"{name}: {index} is not a particle; indices must be in "
                             f"[0, {self._count - 1}]" if self._count else
                             f"{name}: {index} is not a particle; there are none yet")
        return int(index)

    def check_indices(self, indices, name: str = "particles") -> np.ndarray:
        """Indices as an int64 array, each naming a particle, else an error naming ``name``."""
        if isinstance(indices, Particle):
            indices = indices.checked(self, name)
        return check.indices(indices, name, self._count)

    def set_mass(self, index: int, mass: float) -> None:
        """Set one particle's mass [kg], in (0, inf]."""
        self._inv_mass[self.check_index(index)] = inverse_masses(mass, 1)[0]

    def pin(self, index: int) -> None:
        """Make a particle immovable (infinite mass) and stop it."""
        i = self.check_index(index)
        self.wake(i)
        self._inv_mass[i] = 0.0
        self._velocity[i] = 0.0

    # -- sleep ---------------------------------------------------------------------------------
    def wake(self, index: int) -> None:
        """Wake particle ``index`` and, if it was asleep, every particle of its island; its
        still-time starts again from 0."""
        i = self.check_index(index)
        self._sleep_time[i] = 0.0
        if not self._awake[i]:
            self.wake_islands(np.array([self._island[i]]))

    def wake_islands(self, islands: np.ndarray) -> np.ndarray:
        """Wake every sleeping particle whose island is in ``islands`` (int array); their
        still-times start from 0. Returns the mask (N,) of the particles woken."""
        woken = ~self.awake & np.isin(self.island, islands)
        self.awake[woken] = True
        self.sleep_time[woken] = 0.0
        self.island[woken] = -1
        return woken

    def sleep(self, index: int) -> None:
        """Put particle ``index`` to sleep alone, now (an island of its own: a moving particle
        or body that touches it wakes it). An immovable particle never sleeps: ValueError."""
        i = self.check_index(index)
        if self._inv_mass[i] == 0.0:
            raise ValueError(f"particle {i} is immovable (infinite mass): it never sleeps")
        if self._awake[i]:
            self._awake[i] = False
            self._island[i] = -2 - i  # a name no island built from contacts has (those are >= 0)
            self._velocity[i] = 0.0
            self._still_position[i] = self._position[i]
            self._rest_force[i] = 0.0
            self._rest_inv_mass[i] = self._inv_mass[i]

    def wake_all(self) -> None:
        """Wake every particle."""
        self.awake[:] = True
        self.island[:] = -1

    def kinetic_energy(self) -> float:
        """Total kinetic energy ½·m·|v|² of the movable particles [J] (the same bits on any
        number of threads)."""
        energy = (_kinetic_energy_parallel if self._count >= PARALLEL_MIN_PARTICLES
                  else _kinetic_energy)
        return float(energy(self.velocity, self.inv_mass))

    def momentum(self) -> np.ndarray:
        """Total linear momentum Σ m·v of the movable particles [kg·m/s], shape (3,)."""
        inv = self.inv_mass
        moving = inv > 0
        return (self.velocity[moving] / inv[moving, None]).sum(axis=0)

    def snapshot(self) -> dict[str, np.ndarray]:
        """Copies of every array, to restore with ``restore`` (a reset, a determinism check)."""
        return {name: getattr(self, name).copy() for name in _ALL}

    def restore(self, snap: dict[str, np.ndarray]) -> None:
        """Return to a ``snapshot`` (particles added since are dropped)."""
        n = len(snap["inv_mass"])
        self._count = 0
        self._reserve(n)
        self._count = n
        self._refresh_views()
        if "awake" not in snap:  # a snapshot from before sleeping: every particle awake
            self._awake[:n] = True
            self._sleep_time[:n] = 0.0
            self._island[:n] = -1
            self._still_position[:n] = snap["position"]
            self._rest_force[:n] = 0.0
            self._rest_inv_mass[:n] = snap["inv_mass"]
        for name, arr in snap.items():
            getattr(self, "_" + name)[:n] = arr


@njit(cache=True, nogil=True)
def energy_chunk(velocity, inv_mass, start, stop):
    """Σ |v|²/w over the movable particles ``start`` to ``stop`` (no temporaries)."""
    total = 0.0
    for i in range(start, stop):
        w = inv_mass[i]
        if w > 0.0:
            vx, vy, vz = velocity[i, 0], velocity[i, 1], velocity[i, 2]
            total += (vx * vx + vy * vy + vz * vz) / w
    return total


@njit(cache=True, nogil=True)
def _kinetic_energy(velocity, inv_mass):
    """Σ ½·|v|²/w over movable particles, summed by chunks of ``CHUNK`` added in order (the
    bits of ``_kinetic_energy_parallel``). It runs every step, after the solver."""
    n = velocity.shape[0]
    total = 0.0
    for start in range(0, n, CHUNK):
        total += energy_chunk(velocity, inv_mass, start, min(n, start + CHUNK))
    return 0.5 * total


@njit(cache=True, nogil=True, parallel=True)
def _kinetic_energy_parallel(velocity, inv_mass):
    """``_kinetic_energy`` on all cores, a chunk per task, the chunks' sums added in order."""
    n = velocity.shape[0]
    chunks = (n + CHUNK - 1) // CHUNK
    parts = np.empty(chunks)
    for c in prange(chunks):
        parts[c] = energy_chunk(velocity, inv_mass, c * CHUNK, min(n, (c + 1) * CHUNK))
    total = 0.0
    for c in range(chunks):
        total += parts[c]
    return 0.5 * total


#: Masses must lie in [MIN_MASS, MAX_MASS] kg (or be inf, immovable): both ends keep 1/m and
#: m·g finite with room to spare (5e-324 kg inverts to inf; the first step then fails).
MIN_MASS = 1e-12
MAX_MASS = 1e18


def inverse_masses(masses, count: int) -> np.ndarray:
    """Inverse masses from masses in [MIN_MASS, MAX_MASS] or inf (``inf`` gives 0, immovable)."""
    check.numeric(masses, "mass", "a number of kg")
    try:
        m = np.asarray(masses, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"mass must be a number in (0, inf], got {masses!r}") from None
    if m.ndim == 0:
        m = np.full(count, float(m))
    if m.shape != (count,):
        raise ValueError(f"mass must be a number or have shape ({count},), got {m.shape}")
    bad = ~((m >= MIN_MASS) & (m <= MAX_MASS) | (m == np.inf))  # catches NaN too
    if bad.any():
        raise ValueError(f"mass must be in (0, inf] kg: between {MIN_MASS:g} and {MAX_MASS:g}, "
                         f"or inf for immovable; got {m[bad][0]}")
    with np.errstate(divide="ignore"):
        return np.where(np.isinf(m), 0.0, 1.0 / m)


class Particle:
    """Object-style handle on one particle: reads and writes go straight to the arrays."""

    __slots__ = ("index", "particles")

    def __init__(self, particles: Particles, index: int) -> None:
        self.particles = particles
        self.index = index

    def __index__(self) -> int:
        return self.index

    def checked(self, particles: Particles, name: str = "particle") -> int:
        """This handle's index, if it is a handle of ``particles`` (its world's store); else
        an error naming ``name`` (an index that exists here would act on another particle)."""
        if self.particles is not particles:
            raise ValueError(f"{name} is a Particle of another world (index {self.index} "
                             "there): a handle acts only in the world it came from")
        return self.index

    def __repr__(self) -> str:
        p = self.particles
        i = self.index
        return (f"Particle({i}, position={tuple(p.position[i].round(6).tolist())}, "
                f"velocity={tuple(p.velocity[i].round(6).tolist())}, mass={self.mass:g})")

    @property
    def position(self) -> np.ndarray:
        """Position [m], a writable view of shape (3,)."""
        return self.particles.position[self.index]

    @position.setter
    def position(self, value) -> None:
        self.particles.position[self.index] = check.vec3(value, "position")

    @property
    def velocity(self) -> np.ndarray:
        """Velocity [m/s], a writable view of shape (3,)."""
        return self.particles.velocity[self.index]

    @velocity.setter
    def velocity(self, value) -> None:
        self.particles.velocity[self.index] = check.vec3(value, "velocity")

    @property
    def force(self) -> np.ndarray:
        """The force accumulated for the next step [N], shape (3,) (cleared by each step)."""
        return self.particles.force[self.index]

    def add_force(self, force) -> None:
        """Add a force [N] to the accumulator (from a force generator or a per-frame hook)."""
        self.particles.force[self.index] += check.vec3(force, "force")

    @property
    def inverse_mass(self) -> float:
        """Inverse mass [1/kg]; 0 means immovable."""
        return float(self.particles.inv_mass[self.index])

    @property
    def mass(self) -> float:
        """Mass [kg]; ``inf`` when immovable."""
        inv = self.inverse_mass
        return 1.0 / inv if inv > 0 else math.inf

    @mass.setter
    def mass(self, value: float) -> None:
        self.particles.set_mass(self.index, value)

    @property
    def radius(self) -> float:
        """Collision radius [m]."""
        return float(self.particles.radius[self.index])

    @radius.setter
    def radius(self, value: float) -> None:
        self.particles.radius[self.index] = check.scalar(value, "radius", low=0.0)

    @property
    def damping(self) -> float:
        """Fraction of velocity kept per second."""
        return float(self.particles.damping[self.index])

    @damping.setter
    def damping(self, value: float) -> None:
        self.particles.damping[self.index] = check.scalar(value, "damping", low=0.0, high=1.0)

    @property
    def awake(self) -> bool:
        """Whether the particle moves (False: asleep with its island, ``particle_sleep.py``);
        assign True to wake it and its island, False to put it to sleep alone."""
        return bool(self.particles.awake[self.index])

    @awake.setter
    def awake(self, value: bool) -> None:
        if not isinstance(value, (bool, np.bool_)):
            raise TypeError(f"awake must be True or False, got {value!r}")
        if value:
            self.particles.wake(self.index)
        else:
            self.particles.sleep(self.index)

    @property
    def has_finite_mass(self) -> bool:
        """True unless immovable (Cyclone's version is always true)."""
        return self.inverse_mass > 0
