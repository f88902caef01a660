"""Rigid bodies stored as a struct of arrays, like ``Particles``: a body is an index.

``Body`` gives object-style access on top (``b.position``, ``b.add_force_at_point(...)``). The
arrays grow as bodies are added (capacity doubles), so a property such as ``position`` returns a
view of the first ``count`` rows: read it again after adding bodies.

Inertia is stored as the three principal *inverse* moments in body coordinates (0 = infinite:
that axis never turns from a torque), and the world inverse inertia R·diag(I⁻¹)·Rᵀ is derived
from the orientation after every position update (not left from the last step, Cyclone's R2).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import _validate as check
from .._rows import RowViews, view
from ..particles import inverse_masses
from .quaternion import world_inv_inertia_numpy
from .scalar import qrot_inv
from .shapes import NONE, Box, Sphere, mass_properties

_FIELDS_3 = ("position", "velocity", "angular_velocity", "force", "torque", "inv_inertia", "size")
_FIELDS_1 = ("inv_mass", "linear_damping", "angular_damping", "friction", "restitution")
#: Sleep state (``islands.py``, ``sleep.py``): kept in snapshots like the rest.
_SLEEP_FIELDS = ("awake", "sleep_time", "island", "still_position", "still_orientation")
_DTYPES = {"shape": np.int64, "island": np.int64, "awake": np.bool_, "serial": np.int64}
#: The soft step's leapfrog (``solver/body_soft.py``, "Leapfrog"): the half-step velocity
#: and spin each body's last drift moved it with, and the (synchronised) velocity and spin that
#: step left; infinite where no step left one (a body just added). Kept in snapshots like the rest.
_LEAPFROG_FIELDS = ("half_velocity", "half_spin", "left_velocity", "left_spin")
_ALL_FIELDS = (*_FIELDS_3, *_FIELDS_1, "orientation", "inv_inertia_world", "shape",
               *_SLEEP_FIELDS, "serial", *_LEAPFROG_FIELDS)


class Bodies(RowViews):
    """All rigid bodies of a world, struct-of-arrays.

    Attributes (views of the first ``count`` rows):
        position: Centre of mass [m], shape (N, 3), float64.
        orientation: Unit quaternions (w, x, y, z), body -> world, shape (N, 4).
        velocity: Linear velocity of the centre of mass [m/s], shape (N, 3).
        angular_velocity: World angular velocity [rad/s], shape (N, 3).
        force: Force accumulator [N], shape (N, 3); cleared after every step.
        torque: Torque accumulator about the centre of mass [N m], shape (N, 3).
        inv_mass: Inverse mass [1/kg], shape (N,); 0 means infinite mass.
        inv_inertia: Inverse principal moments along the body axes [1/(kg m²)], shape (N, 3);
            0 means an infinite moment.
        inv_inertia_world: World inverse inertia [1/(kg m²)], shape (N, 3, 3); derived.
        linear_damping, angular_damping: Fraction of velocity kept per second, in [0, 1],
            shape (N,); 1 means none (the particles' convention).
        friction: Coulomb coefficient μ ≥ 0 of the body's surface, shape (N,); a contact uses
            √(μa·μb) (Box2D's and Jolt's rule: either surface being frictionless makes it so).
        restitution: Coefficient of restitution in [0, 1], shape (N,); a contact uses the larger.
        shape: Shape kind per body (``shapes.NONE``, ``SPHERE``, ``BOX``), shape (N,), int64.
        size: Sphere radius in column 0, or box half-extents [m], shape (N, 3).
        awake: Whether each body moves, shape (N,), bool. A sleeping body (``World(sleep=
            True)``, ``rigid/islands.py``) has zero velocity, is not integrated and is in no
            contact with another sleeping body or the scenery, until something wakes its
            island. Immovable bodies are always awake.
        sleep_time: Seconds each awake body has been still [s], shape (N,).
        still_position, still_orientation: The pose its still-time counts from, shapes (N, 3)
            and (N, 4): moving far from it restarts the count (``islands.still_timers``).
        island: The island a sleeping body fell asleep with (its lowest body index), or -1
            while awake, shape (N,), int64: waking one body wakes all of it.
    """

    # The storage ``_alloc`` makes (setattr by name; declared for type checkers).
    _position: np.ndarray
    _velocity: np.ndarray
    _angular_velocity: np.ndarray
    _force: np.ndarray
    _torque: np.ndarray
    _inv_inertia: np.ndarray
    _size: np.ndarray
    _inv_mass: np.ndarray
    _linear_damping: np.ndarray
    _angular_damping: np.ndarray
    _friction: np.ndarray
    _restitution: np.ndarray
    _orientation: np.ndarray
    _inv_inertia_world: np.ndarray
    _shape: np.ndarray
    _awake: np.ndarray
    _sleep_time: np.ndarray
    _island: np.ndarray
    _still_position: np.ndarray
    _still_orientation: np.ndarray
    _serial: np.ndarray
    _half_velocity: np.ndarray
    _half_spin: np.ndarray
    _left_velocity: np.ndarray
    _left_spin: np.ndarray

    def __init__(self, capacity: int = 16) -> None:
        self._count = 0
        #: How many times islands were woken (the world gives their warm start back when
        #: this changes, ``rigid/sleep.py``).
        self.wakes = 0
        #: The next body's serial: every body added to this store gets a new one (never
        #: reused, not rolled back by ``restore``), so a joint or handle can tell the body it
        #: was made for from a later one that took its index after a restore dropped it.
        self._next_serial = 0
        self._alloc(max(int(capacity), 1))

    # -- storage -------------------------------------------------------------------------------
    def _alloc(self, capacity: int) -> None:
        n = self._count
        shapes: dict[str, tuple[int, ...]] = dict.fromkeys(_FIELDS_3, (capacity, 3))
        shapes.update(dict.fromkeys(_FIELDS_1, (capacity,)))
        shapes.update(orientation=(capacity, 4), inv_inertia_world=(capacity, 3, 3),
                      shape=(capacity,), **dict.fromkeys(_SLEEP_FIELDS[:3], (capacity,)),
                      still_position=(capacity, 3), still_orientation=(capacity, 4),
                      serial=(capacity,), **dict.fromkeys(_LEAPFROG_FIELDS, (capacity, 3)))
        for name, shape in shapes.items():
            arr: np.ndarray = np.zeros(shape, dtype=_DTYPES.get(name, np.float64))
            old = getattr(self, "_" + name, None)
            if old is not None:
                arr[:n] = old[:n]
            setattr(self, "_" + name, arr)
        self._capacity = capacity
        self._refresh_views()

    @property
    def count(self) -> int:
        """Number of bodies."""
        return self._count

    def __len__(self) -> int:
        return self._count

    _VIEW_FIELDS = _ALL_FIELDS

    position = view("position", "Centre of mass [m], (N, 3).")
    orientation = view("orientation", "Unit quaternions (w, x, y, z), (N, 4).")
    velocity = view("velocity", "Linear velocity [m/s], (N, 3).")
    angular_velocity = view("angular_velocity", "World angular velocity [rad/s], (N, 3).")
    half_velocity = view("half_velocity", "The soft step's half-step velocity [m/s] (leapfrog's "
                         "v at t - h/2: the last drift's), (N, 3).")
    half_spin = view("half_spin", "The soft step's half-step angular velocity [rad/s], (N, 3).")
    left_velocity = view("left_velocity", "The velocity the last soft step left [m/s] (inf: "
                         "none), (N, 3): another one was set since.")
    left_spin = view("left_spin", "The angular velocity the last soft step left, (N, 3).")
    force = view("force", "Force accumulator [N], (N, 3).")
    torque = view("torque", "Torque accumulator [N m], (N, 3).")
    inv_mass = view("inv_mass", "Inverse mass [1/kg], (N,).")
    inv_inertia = view("inv_inertia", "Inverse principal moments [1/(kg m²)], (N, 3).")
    inv_inertia_world = view("inv_inertia_world", "World inverse inertia, (N, 3, 3).")
    linear_damping = view("linear_damping", "Fraction of v kept per second, (N,).")
    angular_damping = view("angular_damping", "Fraction of ω kept per second, (N,).")
    friction = view("friction", "Coulomb coefficient μ ≥ 0, (N,).")
    restitution = view("restitution", "Coefficient of restitution in [0, 1], (N,).")
    shape = view("shape", "Shape kind, (N,).")
    size = view("size", "Radius or half-extents [m], (N, 3).")
    awake = view("awake", "Whether each body moves (not asleep), (N,) bool.")
    sleep_time = view("sleep_time", "Seconds each awake body has been still [s], (N,).")
    island = view("island", "A sleeping body's island (lowest index), -1 awake, (N,).")
    still_position = view("still_position", "Where the still-time counts from [m], (N, 3).")
    still_orientation = view("still_orientation", "The orientation it counts from, (N, 4).")
    serial = view("serial", "Each body's serial in this store (``_next_serial``), (N,).")

    # -- adding --------------------------------------------------------------------------------
    def add(self, position=(0.0, 0.0, 0.0), orientation=(1.0, 0.0, 0.0, 0.0),
            velocity=(0.0, 0.0, 0.0), angular_velocity=(0.0, 0.0, 0.0), *,
            shape: Sphere | Box | None = None, mass: float | None = None,
            density: float | None = None, inertia=None, linear_damping: float = 1.0,
            angular_damping: float = 1.0, friction: float = 0.5,
            restitution: float = 0.0) -> int:
        """Add one body and return its index.

        Args:
            position: Centre of mass [m].
            orientation: Quaternion (w, x, y, z), nonzero; normalised here.
            velocity: Linear velocity [m/s].
            angular_velocity: World angular velocity [rad/s].
            shape: ``Sphere`` or ``Box`` (collision and mass properties), or ``None``.
            mass: Mass [kg] in (0, inf]; ``inf`` with a shape gives infinite inertia too.
            density: Density [kg/m³] in (0, inf], instead of ``mass`` (needs a shape).
            inertia: Principal moments [kg m²] along the body axes, each in (0, inf]
                (``inf`` locks that axis); overrides the shape's. Needed without a shape.
            linear_damping, angular_damping: Fraction of velocity kept per second, in [0, 1].
            friction: Coulomb coefficient μ ≥ 0 of the surface (contacts combine √(μa·μb)).
            restitution: In [0, 1] (contacts take the larger of the two).
        """
        pos = check.vec3(position, "position")
        quat = _unit_quaternion(orientation)
        vel = check.vec3(velocity, "velocity")
        ang = check.vec3(angular_velocity, "angular_velocity")
        if shape is None:
            if density is not None:
                raise ValueError("density needs a shape (Sphere or Box) to give a mass")
            if inertia is None:
                raise ValueError("a body without a shape needs inertia: three principal "
                                 "moments [kg m²], each in (0, inf]")
            m = 1.0 if mass is None else mass
            inv_m = inverse_masses(m, 1)[0]
            kind, size = NONE, np.zeros(3)
        else:
            if not isinstance(shape, (Sphere, Box)):
                raise TypeError(f"shape must be a Sphere, a Box or None, got {shape!r}")
            if mass is None and density is None:
                mass = 1.0
            m, moments = mass_properties(shape, density=density, mass=mass)
            inv_m = 0.0 if math.isinf(m) else inverse_masses(m, 1)[0]
            if inertia is None:
                inertia = moments
            kind, size = shape.kind, shape.size
        inv_i = inverse_inertia(inertia)
        lin = check.scalar(linear_damping, "linear_damping", low=0.0, high=1.0)
        angd = check.scalar(angular_damping, "angular_damping", low=0.0, high=1.0)
        mu = check.scalar(friction, "friction", low=0.0)
        rest = check.scalar(restitution, "restitution", low=0.0, high=1.0)
        if self._count == self._capacity:
            self._alloc(2 * self._capacity)
        i = self._count
        self._count += 1
        self._refresh_views()
        self._position[i] = pos
        self._orientation[i] = quat
        self._velocity[i] = vel
        self._angular_velocity[i] = ang
        self._force[i] = 0.0
        self._torque[i] = 0.0
        self._inv_mass[i] = inv_m
        self._inv_inertia[i] = inv_i
        self._inv_inertia_world[i] = world_inv_inertia_numpy(quat, inv_i)
        self._linear_damping[i] = lin
        self._angular_damping[i] = angd
        self._friction[i] = mu
        self._restitution[i] = rest
        self._shape[i] = kind
        self._size[i] = size
        self._awake[i] = True
        self._sleep_time[i] = 0.0
        self._island[i] = -1
        self._still_position[i] = pos
        self._still_orientation[i] = quat
        self._serial[i] = self._next_serial
        self._next_serial += 1
        self._left_velocity[i] = np.inf  # no step left its velocity: it opens with a half kick
        return i

    def add_sphere(self, radius: float, position=(0.0, 0.0, 0.0), velocity=(0.0, 0.0, 0.0),
                   **kwargs) -> int:
        """Add a solid sphere of ``radius`` [m]; keywords as ``add`` (``density`` or ``mass``)."""
        return self.add(position, velocity=velocity, shape=Sphere(radius), **kwargs)

    def add_box(self, half_extents, position=(0.0, 0.0, 0.0), orientation=(1.0, 0.0, 0.0, 0.0),
                **kwargs) -> int:
        """Add a solid box of ``half_extents`` [m]; keywords as ``add``."""
        return self.add(position, orientation, shape=Box(half_extents), **kwargs)

    def set_shape(self, index: int, shape: Sphere | Box, *, mass: float | None = None,
                  density: float | None = None) -> None:
        """Give body ``index`` a new ``shape`` and the mass properties of that solid (a block
        that breaks keeps one of its pieces): mass from ``mass`` [kg] or ``density`` [kg/m³]
        (each in (0, inf]; one of them), principal moments from the shape, the world inverse
        inertia from its orientation. Position, orientation and velocities are kept."""
        i = self.check_index(index)
        if not isinstance(shape, (Sphere, Box)):
            raise TypeError(f"shape must be a Sphere or a Box, got {shape!r}")
        m, moments = mass_properties(shape, density=density, mass=mass)
        self._inv_mass[i] = 0.0 if math.isinf(m) else 1.0 / m
        self._inv_inertia[i] = inverse_inertia(moments)
        self._inv_inertia_world[i] = world_inv_inertia_numpy(self._orientation[i],
                                                       self._inv_inertia[i])
        self._shape[i] = shape.kind
        self._size[i] = shape.size

    # -- access --------------------------------------------------------------------------------
    def __getitem__(self, index: int) -> Body:
        return Body(self, self.check_index(index))

    def check_index(self, index, name: str = "body") -> int:
        """``index`` as an int if it names a body, else an error naming ``name``."""
        if isinstance(index, Body):
            index = index.checked(self, name)
        if isinstance(index, bool) or not isinstance(index, (int, np.integer)):
            raise TypeError(f"{name} must be a body index (int), got {index!r}")
        if not 0 <= index < self._count:
            raise IndexError(f"{name}: {index} is not a body; indices must be in "
                             f"[0, {self._count - 1}]" if self._count else
                             f"{name}: {index} is not a body; there are none yet")
        return int(index)

    # -- forces --------------------------------------------------------------------------------
    def add_force(self, index: int, force) -> None:
        """Add a force [N] through the centre of mass (no torque); wakes the body."""
        i = self.check_index(index)
        self._force[i] += check.vec3(force, "force")
        self.wake(i)

    def add_torque(self, index: int, torque) -> None:
        """Add a torque [N m] about the centre of mass; wakes the body."""
        i = self.check_index(index)
        self._torque[i] += check.vec3(torque, "torque")
        self.wake(i)

    def add_force_at_point(self, index: int, force, point) -> None:
        """Add a force [N] acting at a world ``point`` [m]: the force, plus the torque
        (point − centre) × force; wakes the body."""
        i = self.check_index(index)
        f = check.vec3(force, "force")
        r = check.vec3(point, "point") - self._position[i]
        self._force[i] += f
        self._torque[i] += np.cross(r, f)
        self.wake(i)

    # -- sleep ---------------------------------------------------------------------------------
    def wake(self, index: int) -> None:
        """Wake body ``index`` and, if it was asleep, every body of its island; its still-time
        starts again from 0 (a body being pushed does not fall asleep)."""
        i = self.check_index(index)
        self._sleep_time[i] = 0.0
        if not self._awake[i]:
            self.wake_islands(np.array([self._island[i]]))

    def wake_islands(self, islands: np.ndarray) -> np.ndarray:
        """Wake every sleeping body whose island is in ``islands`` (int array); their
        still-times start from 0. Returns the mask (N,) of the bodies woken."""
        woken = ~self.awake & np.isin(self.island, islands)
        self.wakes += 1
        self.awake[woken] = True
        self.sleep_time[woken] = 0.0
        self.island[woken] = -1
        return woken

    def sleep(self, index: int) -> None:
        """Put body ``index`` to sleep alone, now (an island of its own; a contact with an awake
        body wakes it). An immovable body never sleeps: ValueError."""
        i = self.check_index(index)
        if self._inv_mass[i] == 0.0:
            raise ValueError(f"body {i} is immovable (infinite mass): it never sleeps")
        if self._awake[i]:
            self._awake[i] = False
            self._island[i] = i
            self._velocity[i] = 0.0
            self._angular_velocity[i] = 0.0
    def snapshot(self) -> dict[str, np.ndarray]:
        """Copies of every array, to restore with ``restore`` (a reset, an undone step)."""
        return {name: getattr(self, name).copy() for name in _ALL_FIELDS}

    def restore(self, snap: dict[str, np.ndarray]) -> None:
        """Return to a ``snapshot`` (bodies added since are dropped)."""
        n = len(snap["inv_mass"])
        if n > self._capacity:
            self._alloc(n)
        self._count = n
        self._refresh_views()
        if "awake" not in snap:  # a snapshot from before sleeping: every body awake
            self._awake[:n] = True
            self._sleep_time[:n] = 0.0
            self._island[:n] = -1
            self._still_position[:n] = snap["position"]
            self._still_orientation[:n] = snap["orientation"]
        if "left_velocity" not in snap:  # a snapshot from before the leapfrog: fresh
            self._left_velocity[:n] = np.inf
        for name, arr in snap.items():
            getattr(self, "_" + name)[:n] = arr

    def clear_accumulators(self) -> None:
        """Zero every force and torque (the stepper does this after each step)."""
        self.force[:] = 0.0
        self.torque[:] = 0.0

    # -- derived -------------------------------------------------------------------------------
    def awake_movable(self) -> int:
        """How many bodies of finite mass are awake (``StepStats.awake_bodies``; one kernel:
        numpy's mask and count were ~2 µs of a tiny world's step)."""
        return int(_awake_movable(self.awake, self.inv_mass))

    def all_awake(self) -> bool:
        """Whether no body sleeps (one kernel: a sleep-off world asks every step)."""
        return bool(_all_true(self.awake))

    def kinetic_energy(self) -> float:
        """Σ ½ m|v|² + ½ ω·Iω over bodies with finite mass / moments [J] (one kernel: the world
        sums it every step, and numpy's temporaries cost 18 % of a 10-box tower's step)."""
        return float(_kinetic_energy(self.velocity, self.angular_velocity, self.orientation,
                                     self.inv_mass, self.inv_inertia))

    def angular_momentum(self, index: int) -> np.ndarray:
        """I_world·ω about the centre of mass [kg m²/s], shape (3,), for a body whose three
        moments are finite."""
        i = self.check_index(index)
        inv = self.inv_inertia[i]
        if not (inv > 0).all():
            raise ValueError(f"body {i} has an infinite moment of inertia: no finite momentum")
        r = world_rotation(self.orientation[i])
        return r @ ((r.T @ self.angular_velocity[i]) / inv)

    def update_world_inertia(self) -> None:
        """Recompute ``inv_inertia_world`` from the orientations (after editing them by hand)."""
        for i in range(self._count):
            self._inv_inertia_world[i] = world_inv_inertia_numpy(self._orientation[i],
                                                           self._inv_inertia[i])


def world_rotation(q: np.ndarray) -> np.ndarray:
    """Rotation matrix (3, 3) of a unit quaternion (w, x, y, z), in numpy."""
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def inverse_inertia(inertia) -> np.ndarray:
    """Inverse principal moments from moments [kg m²], each in (0, inf] (``inf`` gives 0)."""
    check.numeric(inertia, "inertia", "three principal moments [kg m²]")
    try:
        arr = np.asarray(inertia, dtype=np.float64).reshape(3)
    except (TypeError, ValueError):
        raise ValueError("inertia must be three principal moments [kg m²], each in (0, inf], "
                         f"got {inertia!r}") from None
    ok = (arr > 0.0) & ~np.isnan(arr)
    if not ok.all():
        raise ValueError("inertia must be three principal moments [kg m²], each in (0, inf], "
                         f"got {tuple(arr.tolist())}")
    return np.where(np.isinf(arr), 0.0, 1.0 / arr)


def _unit_quaternion(value) -> np.ndarray:
    check.numeric(value, "orientation", "a quaternion (w, x, y, z)")
    try:
        q = np.asarray(value, dtype=np.float64).reshape(4)
    except (TypeError, ValueError):
        raise ValueError(f"orientation must be a quaternion (w, x, y, z), got {value!r}") from None
    n = float(np.sqrt(q @ q)) if np.isfinite(q).all() else math.nan
    if not (n > 1e-9 and math.isfinite(n)):
        raise ValueError("orientation must be a finite, nonzero quaternion (w, x, y, z), "
                         f"got {tuple(q.tolist())}")
    return q / n


class Body:
    """Object-style handle on one body: reads and writes go straight to the arrays."""

    __slots__ = ("bodies", "index", "serial")

    def __init__(self, bodies: Bodies, index: int) -> None:
        self.bodies = bodies
        self.index = index
        self.serial = int(bodies.serial[index])

    def checked(self, bodies: Bodies, name: str = "body") -> int:
        """This handle's index, if it names a body of ``bodies`` (its world's store) that is
        still the body it was made for; else an error naming ``name``."""
        if self.bodies is not bodies:
            raise ValueError(f"{name} is a Body of another world (index {self.index} there): "
                             "a handle acts only in the world whose add_body returned it")
        if not (self.index < bodies.count and bodies.serial[self.index] == self.serial):
            raise ValueError(f"{name} is a stale Body handle: body {self.index} was dropped "
                             "(a restore of an older snapshot) and its index is another "
                             "body's now, or none")
        return self.index

    def __index__(self) -> int:
        return self.index

    def __repr__(self) -> str:
        b, i = self.bodies, self.index
        return (f"Body({i}, position={tuple(b.position[i].round(6).tolist())}, "
                f"orientation={tuple(b.orientation[i].round(6).tolist())}, mass={self.mass:g})")

    @property
    def position(self) -> np.ndarray:
        """Centre of mass [m], a writable view (3,); assigning it wakes the body."""
        return self.bodies.position[self.index]

    @position.setter
    def position(self, value) -> None:
        self.bodies.position[self.index] = check.vec3(value, "position")
        self.bodies.wake(self.index)

    @property
    def orientation(self) -> np.ndarray:
        """Unit quaternion (w, x, y, z) (4,); set it through this property, which normalises it
        and updates the world inertia."""
        return self.bodies.orientation[self.index].copy()

    @orientation.setter
    def orientation(self, value) -> None:
        q = _unit_quaternion(value)
        i = self.index
        self.bodies.orientation[i] = q
        self.bodies.inv_inertia_world[i] = world_inv_inertia_numpy(q, self.bodies.inv_inertia[i])
        self.bodies.wake(i)

    @property
    def velocity(self) -> np.ndarray:
        """Linear velocity [m/s], a writable view (3,)."""
        return self.bodies.velocity[self.index]

    @velocity.setter
    def velocity(self, value) -> None:
        self.bodies.velocity[self.index] = check.vec3(value, "velocity")
        self.bodies.wake(self.index)

    @property
    def angular_velocity(self) -> np.ndarray:
        """World angular velocity [rad/s], a writable view (3,)."""
        return self.bodies.angular_velocity[self.index]

    @angular_velocity.setter
    def angular_velocity(self, value) -> None:
        self.bodies.angular_velocity[self.index] = check.vec3(value, "angular_velocity")
        self.bodies.wake(self.index)

    @property
    def awake(self) -> bool:
        """Whether the body moves; set False to put it to sleep now (alone: a contact with an
        awake body wakes it), True to wake it and its island. Assigning ``position``,
        ``orientation``, ``velocity`` or ``angular_velocity`` through this handle wakes it too
        (writing into the arrays in place does not)."""
        return bool(self.bodies.awake[self.index])

    @awake.setter
    def awake(self, value: bool) -> None:
        if not isinstance(value, (bool, np.bool_)):
            raise TypeError(f"awake must be True or False, got {value!r}")
        if value:
            self.bodies.wake(self.index)
        else:
            self.bodies.sleep(self.index)

    @property
    def mass(self) -> float:
        """Mass [kg]; ``inf`` when immovable."""
        inv = float(self.bodies.inv_mass[self.index])
        return 1.0 / inv if inv > 0 else math.inf

    @property
    def inertia(self) -> np.ndarray:
        """Principal moments [kg m²] along the body axes (3,); ``inf`` on a locked axis."""
        inv = self.bodies.inv_inertia[self.index]
        with np.errstate(divide="ignore"):
            return np.where(inv > 0, 1.0 / np.where(inv > 0, inv, 1.0), np.inf)

    def add_force(self, force) -> None:
        """Add a force [N] through the centre of mass."""
        self.bodies.add_force(self.index, force)

    def add_torque(self, torque) -> None:
        """Add a torque [N m]."""
        self.bodies.add_torque(self.index, torque)

    def add_force_at_point(self, force, point) -> None:
        """Add a force [N] at a world point [m] (force + torque)."""
        self.bodies.add_force_at_point(self.index, force, point)

    def point_velocity(self, point) -> np.ndarray:
        """Velocity [m/s] of the body's material point at world ``point`` [m]: v + ω × r."""
        r = check.vec3(point, "point") - self.position
        return self.velocity + np.cross(self.angular_velocity, r)

    def to_world(self, local) -> np.ndarray:
        """World position [m] of a body-space point [m]."""
        return self.position + world_rotation(self.orientation) @ check.vec3(local, "local")


@njit(cache=True, nogil=True)
def _all_true(mask):
    for i in range(mask.shape[0]):
        if not mask[i]:
            return False
    return True


@njit(cache=True, nogil=True)
def _awake_movable(awake, inv_mass):
    count = 0
    for i in range(awake.shape[0]):
        if awake[i] and inv_mass[i] > 0.0:
            count += 1
    return count


@njit(cache=True, nogil=True)
def _kinetic_energy(vel, ang, quat, inv_mass, inv_inertia):
    """``Bodies.kinetic_energy``: rotation in body coordinates, where I is diagonal; a body
    with an infinite moment about any axis contributes no rotational energy."""
    total = 0.0
    for i in range(vel.shape[0]):
        if inv_mass[i] > 0.0:
            total += 0.5 * (vel[i, 0] ** 2 + vel[i, 1] ** 2 + vel[i, 2] ** 2) / inv_mass[i]
        ix, iy, iz = inv_inertia[i, 0], inv_inertia[i, 1], inv_inertia[i, 2]
        if ix > 0.0 and iy > 0.0 and iz > 0.0:
            wx, wy, wz = qrot_inv(quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3],
                                  ang[i, 0], ang[i, 1], ang[i, 2])
            total += 0.5 * (wx * wx / ix + wy * wy / iy + wz * wz / iz)
    return total


def body_index(body, name: str) -> int:
    """A body index from a ``Body`` handle or an int >= 0 (checked against a world when the
    generator or joint is added), or a TypeError naming ``name``."""
    if isinstance(body, Body):
        return body.index
    if isinstance(body, bool) or not isinstance(body, (int, np.integer)) or body < 0:
        raise TypeError(f"{name} must be a Body or a body index (int >= 0), got {body!r}")
    return int(body)
