"""The world: particles, force generators, contact generators, and the step that runs them."""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from functools import partial
from typing import Any

import numpy as np
from numba import njit, prange

from . import _validate as check
from . import particle_sleep as psleep
from .collide import Plane
from .contacts import ContactBuffer, ContactGenerator, friction_value, restitution_value
from .forces import ForceGenerator, drag_force, fold
from .particles import CHUNK, PARALLEL_MIN_PARTICLES, Particles
from .rigid import sleep as sleeping
from .rigid.bodies import Bodies, Body
from .rigid.collide import generate as generate_body_contacts
from .rigid.contacts import BodyContacts
from .rigid.forces import BodyForceGenerator
from .rigid.joint_set import Joints
from .rigid.joints import Joint
from .rigid.particle_body import add_particle_contacts
from .rigid.shapes import Box, Sphere
from .rigid.step import integrate_positions, integrate_velocities, spin_error
from .solver import ImpulseHistory, Solver, SolveStats, body_soft
from .solver.body_late import project_late
from .stability import SpringCheck, jump_check, needs_jump_check


@dataclass(frozen=True)
class StepStats:
    """What one ``World.step`` did.

    Attributes:
        contacts: Contacts generated in the last substep, including speculative ones (a gap
            within the collision margin, negative penetration).
        iterations: Single-contact resolutions the solver performed (all substeps).
        max_penetration: Largest overlap left after resolving [m] (0 when none).
        kinetic_energy: Total kinetic energy after the step [J], summed when first read (a
            property: a step whose energy nobody reads makes no pass over the velocities for
            it). Read it before the world steps again; reading it later raises, as the state
            it described is gone (``World.kinetic_energy()`` gives the current one).
        mode: The solver mode ("sequential" or "worst-first").
        velocity_passes: Velocity passes of the solver (all substeps; see ``pointmass.solver``).
        position_passes: Projection passes (all substeps).
        body_contacts: Rigid-body contact points in the last substep (speculative included),
            particle–body points among them.
        awake_bodies: Movable rigid bodies awake after the step (the rest sleep).
    """

    contacts: int
    iterations: int
    max_penetration: float
    mode: str
    velocity_passes: int = 0
    position_passes: int = 0
    body_contacts: int = 0
    awake_bodies: int = 0

    # The energy is not a field: ``_energy`` holds it once read, or what computes it
    # (``World._energy_after``, set by the step), so ``asdict``, ``==`` and ``repr`` never
    # reach the world behind it.

    @property
    def kinetic_energy(self) -> float:
        energy = self.__dict__.get("_energy")
        if energy is None:
            raise RuntimeError("this StepStats was pickled or deep-copied before its kinetic "
                               "energy was read (it is summed when first read, from the world "
                               "that stepped; a copy does not carry the world along)")
        if callable(energy):
            energy = energy()
            object.__setattr__(self, "_energy", energy)  # frozen: cache it once
        return energy

    def __getstate__(self) -> dict:
        state = dict(self.__dict__)
        if callable(state.get("_energy")):
            del state["_energy"]  # a pickle or deep copy does not carry the world along
        return state

    def __setstate__(self, state: dict) -> None:
        for name, value in state.items():
            object.__setattr__(self, name, value)


@njit(cache=True, inline="always")
def _integrate_particle(px, py, pz, vx, vy, vz, fx, fy, fz, w, d, gx, gy, gz, k1, k2, dt):
    """Semi-implicit Euler for one particle, in the cookbook's order: v += a·dt, v *= d^dt,
    p += v·dt, from its position, velocity and accumulated force, inverse mass w and damping d.
    The folded generators (``forces.fold``) act here: the uniform acceleration g and the
    drag of coefficients k1, k2 on the velocity before the step, as if added to the force.
    Immovable particles (w = 0) get no acceleration but keep moving with whatever velocity they
    were given (kinematic). Returns the new position, velocity and acceleration (9 numbers).

    A pure function of scalars: the driver loads and stores. (As a helper that stored into the
    arrays itself, numba compiled the serial loop at 71 ns a particle, against 4.5 ns for the
    same helper in the parallel loop on one thread; given g as an array, whose loads the
    stores may alias, 39 ns against 18.)
    """
    ax = 0.0
    ay = 0.0
    az = 0.0
    if w > 0.0:
        if k1 != 0.0 or k2 != 0.0:  # the same for every particle: a branch never mispredicted
            dx, dy, dz = drag_force(vx, vy, vz, k1, k2)
            fx += dx
            fy += dy
            fz += dz
        ax = gx + fx * w
        ay = gy + fy * w
        az = gz + fz * w
        vx += ax * dt
        vy += ay * dt
        vz += az * dt
        if d < 1.0:  # no multiply by 1 for the undamped (1 ns of 11 a particle, measured)
            keep = d**dt
            vx *= keep
            vy *= keep
            vz *= keep
    return px + vx * dt, py + vy * dt, pz + vz * dt, vx, vy, vz, ax, ay, az


@njit(cache=True, nogil=True)
def _first_not_finite(pos, vel, start, stop):
    """The first particle in [start, stop) with a non-finite position or velocity, or -1."""
    for i in range(start, stop):
        if not math.isfinite(pos[i, 0] + pos[i, 1] + pos[i, 2]
                             + vel[i, 0] + vel[i, 1] + vel[i, 2]):
            return i
    return -1


@njit(cache=True, nogil=True)
def _integrate(pos, vel, force, acc, inv_mass, damping, awake, g, k1, k2, dt, store_acc, start,
               stop):
    """Integrate particles ``start`` to ``stop`` (a chunk); returns the first that is not
    finite afterwards, or -1. The acceleration is stored only with ``store_acc`` (when
    something reads it: the solver's resting-contact test). Sleeping particles (``awake``
    False) are skipped, their accumulated force left for the wake test
    (``particle_sleep.py``); with every particle awake the arithmetic is the same.

    Each particle's force accumulator is cleared as it is read, as Cyclone's integrate ends with
    clearAccumulator: no separate pass clears it, and a force added to ``particles.force``
    before a step acts in it (as ``addForce`` does in the book). The stores are written out
    here: an inlined helper that stores into the arrays made numba's serial loop 3× slower
    (measured 49 against 16 ns a particle). Non-finite values are caught by one sum of the
    new positions, tested once (a non-finite velocity makes its position non-finite: dt > 0):
    a per-particle test cost 1–2 ns of 11; an overflow of the sum alone only costs a rescan
    that finds nothing. The kinetic energy is not summed here (in this loop it cost 2.3 ns a
    particle of 11.7, 8192 particles on one thread): ``StepStats`` sums it only when read."""
    gx, gy, gz = g[0], g[1], g[2]
    probe = 0.0
    for i in range(start, stop):
        if not awake[i]:
            continue
        px, py, pz, vx, vy, vz, ax, ay, az = _integrate_particle(
            pos[i, 0], pos[i, 1], pos[i, 2], vel[i, 0], vel[i, 1], vel[i, 2],
            force[i, 0], force[i, 1], force[i, 2], inv_mass[i], damping[i], gx, gy, gz,
            k1, k2, dt)
        pos[i, 0] = px
        pos[i, 1] = py
        pos[i, 2] = pz
        vel[i, 0] = vx
        vel[i, 1] = vy
        vel[i, 2] = vz
        if store_acc:
            acc[i, 0] = ax
            acc[i, 1] = ay
            acc[i, 2] = az
        force[i, 0] = 0.0  # the accumulator is consumed (Cyclone's clearAccumulator)
        force[i, 1] = 0.0
        force[i, 2] = 0.0
        probe += px + py + pz
    return -1 if math.isfinite(probe) else _first_not_finite(pos, vel, start, stop)


@njit(cache=True, nogil=True, parallel=True)
def _integrate_parallel(pos, vel, force, acc, inv_mass, damping, awake, g, k1, k2, dt,
                        store_acc):
    """``_integrate`` on all cores, one chunk of ``CHUNK`` particles per task; returns the
    first non-finite particle in chunk order (the same for any thread count), or -1."""
    n = pos.shape[0]
    chunks = (n + CHUNK - 1) // CHUNK
    bad = np.empty(chunks, np.int64)
    for c in prange(chunks):
        start, stop = c * CHUNK, min(n, (c + 1) * CHUNK)
        bad[c] = _integrate(pos, vel, force, acc, inv_mass, damping, awake, g, k1, k2, dt,
                            store_acc, start, stop)
    first = -1
    for c in range(chunks):
        if bad[c] >= 0:
            first = bad[c]
            break
    return first


class World:
    """Particles and everything acting on them.

    Args:
        gravity: World-wide gravitational acceleration [m/s²] applied to every movable particle.
        iterations: Cap on the solver's velocity passes per substep (None: automatic; the
            passes stop once converged), or on single-contact resolutions for "worst-first"
            (None: 2 × contacts, the book's choice).
        resolver: "sequential" (the default: impacts by sequential propagation, then
            warm-started sequential impulses; "auto" and "sweep" are older names for it) or
            "worst-first" (the book's loop). See ``pointmass.solver``.
        restitution_threshold: Closing speeds below this [m/s] do not bounce. 0 by default:
            the resting-contact trick keeps piles still without hiding any inelasticity.
        substeps: Substeps per ``step``; each runs the whole pipeline with dt / substeps.
        sleep: Whether bodies and particles sleep: an island of touching (or jointed, linked)
            bodies and particles none of whose points has gone 2.5 cm in 0.5 s (0.05 m/s)
            stops being integrated and solved until a moving body or particle touches it, a
            force pushes it or the user moves it (``rigid/islands.py``, ``rigid/sleep.py``,
            ``particle_sleep.py``). On by default; False gives everything a full step always
            (bit for bit the trajectory of an engine without sleep).
        body_step: The rigid bodies' contact stage: "impulses" (the default: sequential
            impulses, exact normals for small sets, position projection) or "soft" (Box2D
            v3's soft step, ``solver/body_soft.py``: after one collision pass, 4 substeps of
            soft contacts and relax, then restitution; it keeps linear and angular momentum
            exactly and stands towers of 30 boxes, but is experimental, not the default yet:
            12 tests of the earlier stage's exact figures do not hold with it and force-free
            random scenes can gain energy with it; its joints: ``solver/joint_soft.py``;
            see that module).

    Example:
        >>> import pointmass as pm
        >>> world = pm.World(gravity=(0, -9.81, 0))
        >>> ball = world.add_particle(position=(0, 1, 0), radius=0.1)
        >>> stats = world.step(1 / 60)
        >>> round(float(world.particles.velocity[ball, 1]), 4)
        -0.1635
    """

    def __init__(self, gravity=(0.0, -9.81, 0.0), *, iterations: int | None = None,
                 resolver: str = "sequential", restitution_threshold: float = 0.0,
                 substeps: int = 1, sleep: bool = True, body_step: str = "impulses") -> None:
        self.particles = Particles()
        #: Rigid bodies (``add_body``); they meet each other, every ``Plane``/``Ground`` and every
        #: particle with radius > 0 (``rigid/particle_body.py``).
        self.bodies = Bodies()
        self.body_contacts = BodyContacts()
        #: The warm start of rigid-body contact points (clear it with ``impulses``).
        self.body_impulses = ImpulseHistory()
        self._late_contacts = BodyContacts()  # the overlaps after the drift (body_late)
        self._body_rows = None
        self._packed = None  # the last substep's particle–body view (or None)
        #: The longest still-time of an awake particle after the last step [s].
        self._longest_still = 0.0
        self._plinks: np.ndarray | None = None
        self._force_dt = 0.0  # how long the next kicks apply forces (``_kick``)
        #: The warm start of sleeping bodies' contact points, given back when they wake.
        self.sleeping_impulses = sleeping.SleepingImpulses()
        #: Body pairs (K, 2) that must share an island (joints): they sleep and wake together.
        self.island_links = np.zeros((0, 2), np.int64)
        self._wakes_seen = 0
        self.sleep = sleep
        #: The particles' surface against rigid bodies (every particle with radius > 0 meets
        #: every body): a contact uses √(μp·μb) and max(ep, eb), as between two bodies. The
        #: defaults are ``add_body``'s, so a particle meets a body as a default body would.
        self.particle_friction = 0.5
        self.particle_restitution = 0.0
        self.forces: list[ForceGenerator] = []
        #: Rigid-body force generators (``pointmass.rigid.forces``), applied before the kick.
        self.body_forces: list[BodyForceGenerator] = []
        #: Joints between rigid bodies (``pointmass.rigid.joints``, ``add``); jointed bodies
        #: do not collide with each other.
        self.joints = Joints()
        self.contact_generators: list[ContactGenerator] = []
        #: This world's numbering of planes and link sets in contact keys (``keys.py``).
        self._key_serials = itertools.count()
        self.contacts = ContactBuffer()
        self.solver = Solver()
        #: What each keyed contact needed last step (the solver's warm start); clear it after
        #: restoring a snapshot so a replay is bit-identical.
        self.impulses = ImpulseHistory()
        self.gravity = gravity
        self.iterations = iterations
        self.resolver = resolver
        self.restitution_threshold = restitution_threshold
        self.substeps = substeps
        if body_step not in ("impulses", "soft"):
            raise ValueError(f'body_step must be "impulses" or "soft", got {body_step!r}')
        self._body_step = body_step
        self.time = 0.0
        #: Probes sampled after every step (``add_probe``).
        self.probes: list = []
        #: The particle count that every generator was last validated against.
        self._checked_count = 0
        self._checked_bodies = 0  # the same for bodies and the body force generators
        self._jump_check = False
        #: The springs' check together (stability.py): what it measured last, for this world.
        self._spring_check = SpringCheck()
        #: Steps taken: a ``StepStats`` sums its kinetic energy only while this is unchanged.
        self._steps = 0
        #: This step's generators, split by ``forces.fold``: (those that add to the
        #: accumulator, gravity + the folded accelerations, drag k1, k2).
        self._folded: tuple[list, Any, float, float] = ([], self._gravity, 0.0, 0.0)

    # -- settings, checked on assignment --------------------------------------------------------
    @property
    def gravity(self) -> np.ndarray:
        """World gravity [m/s²], shape (3,)."""
        return self._gravity

    @gravity.setter
    def gravity(self, value) -> None:
        self._gravity = check.vec3(value, "gravity")

    @property
    def iterations(self) -> int | None:
        """The solver's cap on passes (see ``Solver.max_passes``); None: automatic."""
        return self.solver.max_passes

    @iterations.setter
    def iterations(self, value: int | None) -> None:
        if value is not None and (isinstance(value, bool) or not isinstance(value, int)
                                  or value < 1):
            raise ValueError(f"iterations must be None (automatic) or an int >= 1, got {value!r}")
        self.solver.max_passes = value

    @property
    def resolver(self) -> str:
        """The solver's mode: "sequential" (default) or "worst-first"."""
        return self.solver.mode

    @resolver.setter
    def resolver(self, value: str) -> None:
        self.solver.mode = value

    @property
    def substeps(self) -> int:
        return self._substeps

    @substeps.setter
    def substeps(self, value: int) -> None:
        if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= 1000:
            raise ValueError(f"substeps must be an int in [1, 1000], got {value!r}")
        self._substeps = value

    @property
    def sleep(self) -> bool:
        """Whether still islands of bodies and particles sleep (see the class docstring);
        turning it off wakes every body and particle."""
        return self._sleep

    @sleep.setter
    def sleep(self, value: bool) -> None:
        if not isinstance(value, (bool, np.bool_)):
            raise TypeError(f"sleep must be True or False, got {value!r}")
        self._sleep = bool(value)
        if not value:
            self._wake_all()

    def _wake_all(self) -> None:
        b = self.bodies
        if not b.awake.all():
            b.wake_islands(np.unique(b.island[~b.awake]))
        p = self.particles
        if not p.awake.all():
            p.wake_all()

    @property
    def restitution_threshold(self) -> float:
        return self.solver.restitution_threshold

    @restitution_threshold.setter
    def restitution_threshold(self, value: float) -> None:
        self.solver.restitution_threshold = check.scalar(value, "restitution_threshold",
                                                         low=0.0)

    @property
    def particle_friction(self) -> float:
        """Coulomb μ ≥ 0 of the particles' surface against rigid bodies."""
        return self._particle_friction

    @particle_friction.setter
    def particle_friction(self, value: float) -> None:
        self._particle_friction = friction_value(value, "particle_friction")

    @property
    def particle_restitution(self) -> float:
        """Restitution in [0, 1] of the particles' surface against rigid bodies."""
        return self._particle_restitution

    @particle_restitution.setter
    def particle_restitution(self, value: float) -> None:
        self._particle_restitution = restitution_value(value, "particle_restitution")

    # -- building --------------------------------------------------------------------------------
    def add_particle(self, position=(0.0, 0.0, 0.0), velocity=(0.0, 0.0, 0.0), *,
                     mass: float = 1.0, radius: float = 0.0, damping: float = 1.0) -> int:
        """Add one particle; returns its index. See ``Particles.add`` for units and ranges."""
        return self.particles.add(position, velocity, mass=mass, radius=radius, damping=damping)

    def add_particles(self, positions, velocities=None, *, masses=1.0, radii=0.0,
                      damping=1.0) -> np.ndarray:
        """Add many particles; returns their indices. See ``Particles.add_many``."""
        return self.particles.add_many(positions, velocities, masses=masses, radii=radii,
                                       damping=damping)

    def add_body(self, shape, position=(0.0, 0.0, 0.0), orientation=(1.0, 0.0, 0.0, 0.0), *,
                 velocity=(0.0, 0.0, 0.0), angular_velocity=(0.0, 0.0, 0.0),
                 density: float | None = None, mass: float | None = None, inertia=None,
                 friction: float = 0.5, restitution: float = 0.0,
                 linear_damping: float = 1.0, angular_damping: float = 1.0) -> Body:
        """Add a rigid body of ``shape`` (``rigid.shapes.Sphere`` or ``Box``); returns its
        ``Body`` handle. Mass from ``density`` [kg/m³] (1000, water, when neither is given) or
        ``mass`` [kg], in (0, inf] (inf: static); orientation a quaternion (w, x, y, z);
        ``friction`` μ ≥ 0 and ``restitution`` in [0, 1] of its surface (a contact uses
        √(μa·μb) and the larger e; a plane counts as a surface, and one left at its default
        material leaves the body's own). See ``Bodies.add``."""
        if shape is None:
            raise ValueError("shape must be a pm.Sphere or a pm.Box (pointmass.rigid.shapes); a "
                             "body without a shape cannot collide: use world.bodies.add for one")
        if density is None and mass is None:
            density = 1000.0
        index = self.bodies.add(position, orientation, velocity, angular_velocity, shape=shape,
                                mass=mass, density=density, inertia=inertia,
                                linear_damping=linear_damping, angular_damping=angular_damping,
                                friction=friction, restitution=restitution)
        return Body(self.bodies, index)

    def add(self, generator):
        """Add a force generator, a rigid-body force generator (``pointmass.rigid.forces``),
        a joint (``pointmass.rigid.joints``) or a contact generator; returns it (to keep as a
        handle). A joint's angles are measured from the pose its bodies have now.

        Particle and body indices are checked here, against those that exist now.
        """
        if any(generator is g for g in (*self.forces, *self.contact_generators,
                                        *self.body_forces, *self.joints)):
            raise ValueError(f"{type(generator).__name__} is already in this world: adding it "
                             "again would apply it twice (add another instance for more)")
        if isinstance(generator, ForceGenerator):
            generator.validate(self.particles)
            self.forces.append(generator)
        elif isinstance(generator, ContactGenerator):
            generator.validate(self.particles)
            generator.claim_keys(self._key_serials)
            self.contact_generators.append(generator)
        elif isinstance(generator, BodyForceGenerator):
            generator.check_handles(self.bodies)
            generator.validate(self.bodies)
            self.body_forces.append(generator)
            self._checked_bodies = max(self._checked_bodies, self.bodies.count)
            return generator
        elif isinstance(generator, Joint):
            self.joints.add(generator, self.bodies)
            self._checked_bodies = max(self._checked_bodies, self.bodies.count)
            return generator
        else:
            hint = ""
            if isinstance(generator, (Box, Sphere)):  # the rigid shapes, pm.Box and pm.Sphere
                hint = (f"; a {type(generator).__name__} is a rigid body's shape: "
                        f"world.add_body(shape, position, ...) (walls that keep particles in "
                        f"are pm.BoxContainer)")
            raise TypeError(f"world.add takes a ForceGenerator, BodyForceGenerator, Joint or "
                            f"ContactGenerator, got {type(generator).__name__}{hint}")
        self._checked_count = max(self._checked_count, self.particles.count)
        return generator

    def _check_references(self) -> None:
        """Generators were validated against the particles that existed then; if particles
        have gone since (``particles.restore`` of an older snapshot), validate them again, so a
        spring to a dropped particle fails here, naming it, instead of reading a stale row."""
        count = self.particles.count
        if count < self._checked_count:
            generators: list[ForceGenerator | ContactGenerator] = [*self.forces,
                                                                   *self.contact_generators]
            for generator in generators:
                try:
                    generator.validate(self.particles)
                except (IndexError, ValueError) as error:
                    raise IndexError(
                        f"{type(generator).__name__} refers to a particle that no longer exists "
                        f"(the world has {count} now): {error}; remove it with world.remove() "
                        "or restore a snapshot that has its particles") from None
        self._checked_count = count
        bodies = self.bodies.count
        if bodies < self._checked_bodies:
            for generator in (*self.body_forces, *self.joints):
                try:
                    generator.validate(self.bodies)
                except (IndexError, ValueError) as error:
                    raise IndexError(
                        f"{type(generator).__name__} refers to a body that no longer exists "
                        f"(the world has {bodies} now): {error}; remove it with world.remove() "
                        "or restore a snapshot that has its bodies") from None
        self._checked_bodies = bodies
        self.joints.check_bodies(self.bodies)

    def add_probe(self, probe):
        """Sample ``probe`` (a ``pointmass.Probe``) after every step; returns it."""
        if not hasattr(probe, "record"):
            raise TypeError(f"add_probe takes a Probe, got {type(probe).__name__}")
        self.probes.append(probe)
        return probe

    def remove(self, generator) -> None:
        """Remove a generator (or a joint) added with ``add``."""
        if generator in self.joints:
            self.joints.remove(generator)
            return
        for group in (self.forces, self.contact_generators, self.body_forces):
            if generator in group:
                group.remove(generator)
                return
        raise ValueError(f"{generator!r} is not in this world")

    # -- the step -------------------------------------------------------------------------------
    def step(self, dt: float) -> StepStats:
        """Advance by ``dt`` seconds (> 0), in ``substeps`` equal parts."""
        if isinstance(dt, (bool, np.bool_)) or not (
                isinstance(dt, (int, float, np.integer, np.floating)) and math.isfinite(dt)
                and dt > 0):
            raise ValueError(f"dt must be a finite number of seconds > 0, got {dt!r}")
        self._check_references()
        h = float(dt) / self._substeps
        # Blow-ups are caught before anything moves (stability.py: springs check their
        # stiffness against the step, user forces the velocity change they would cause), so
        # the world stays as it was and the user can go on with a smaller dt. With substeps,
        # the earlier substeps are undone from a copy.
        self._folded = fold(self.forces, self._gravity)
        self._plinks = None  # made when first asked for (``_particle_links``)
        self._jump_check = needs_jump_check(self._folded[0])
        self._spring_check(self._folded[0], self.particles, self._folded[2], h)
        if not self._sleep:
            self._wake_all()  # bodies put to sleep by hand while sleeping is off
        saved = (self.particles.snapshot(), self.time, self.impulses.snapshot(),
                 self.bodies.snapshot(), self.body_impulses.snapshot(),
                 self.sleeping_impulses.snapshot(), self.joints.snapshot()) \
            if self._substeps > 1 else None
        iterations = velocity_passes = position_passes = 0
        try:
            for _ in range(self._substeps):
                solved = self._substep(h)
                iterations += solved.resolutions
                velocity_passes += solved.velocity_passes
                position_passes += solved.position_passes
        except FloatingPointError:
            if saved is not None:  # a later substep blew up: undo the earlier ones
                self.particles.restore(saved[0])
                self.time = saved[1]
                self.impulses.restore(saved[2])
                self.bodies.restore(saved[3])
                self.body_impulses.restore(saved[4])
                self.sleeping_impulses.restore(saved[5])
                self.joints.restore(saved[6])
            raise
        self.time += float(dt)
        if self.bodies.count:
            self.bodies.clear_accumulators()  # user forces and torques last one step
        if self._sleep and (self.bodies.count or self.particles.count):
            self._fall_asleep(float(dt))
        self._steps += 1
        pen = self.contacts.penetration
        b = self.bodies
        awake = int(np.count_nonzero(b.awake & (b.inv_mass > 0))) if b.count else 0
        deepest = float(pen.max()) if pen.size and pen.max() > 0 else 0.0
        rows = self._body_rows
        if rows is not None:
            deepest = max(deepest, rows.deepest)
        for probe in self.probes:
            probe.record(self)
        stats = StepStats(contacts=self.contacts.count, iterations=iterations,
                          max_penetration=deepest, mode=self.solver.mode,
                          velocity_passes=velocity_passes, position_passes=position_passes,
                          body_contacts=self.body_contacts.count, awake_bodies=awake)
        object.__setattr__(stats, "_energy", partial(self._energy_after, self._steps))
        return stats

    def _energy_after(self, steps: int) -> float:
        """The kinetic energy for ``StepStats`` of step number ``steps``: summed now, when it
        is read (no step pays a pass over the velocities that nobody reads), so only while the
        world is still where that step left it."""
        if steps != self._steps:
            raise RuntimeError(
                f"StepStats.kinetic_energy of step {steps} was read after step {self._steps}: "
                "it is summed when first read, from the state its step left, which is gone. "
                "Read it before the next step, or call World.kinetic_energy() for the current "
                "energy (or record it every step with a probe)")
        energy = self.kinetic_energy()
        if not math.isfinite(energy):
            # particles, bodies or both: an empty store has no largest speed (numpy's max of
            # nothing raised "zero-size array" in a world of bodies alone)
            speeds = [float(np.abs(v).max()) for v in (self.particles.velocity,
                      self.bodies.velocity, self.bodies.angular_velocity) if v.size]
            raise FloatingPointError(
                f"the kinetic energy overflowed ({energy}) at t = {self.time:.6g} s: a velocity "
                f"is too large to square (largest |v| or |ω| component = {max(speeds):.3g} "
                "m/s or rad/s)")
        return energy

    def _substep(self, dt: float) -> SolveStats:
        p = self.particles

        # Let every force generator add its forces to the accumulators (which hold whatever
        # the user added since the last step; the integration reads and clears them). Gravity
        # and drag on all particles are folded into the integration instead (forces.fold).
        accumulating, g, k1, k2 = self._folded
        try:
            for generator in accumulating:
                generator.apply(p, dt)
            if self._jump_check:  # user forces: refuse a step that would throw a particle
                jump_check(accumulating, p, g, dt)
        except BaseException:
            p.force[:] = 0.0  # a refused step leaves no half-accumulated forces behind
            raise

        # Integrate: v += a·dt, then p += v·dt (semi-implicit Euler, the cookbook's order).
        # The acceleration is stored only where it is read: the resting-contact test of the
        # particle solver and of the body stage.
        after = bool(self.contact_generators) or self.bodies.count > 0
        sleepers = self._sleep and p.count > 0 and self._wake_disturbed(dt)
        args = (p.position, p.velocity, p.force, p.acceleration, p.inv_mass, p.damping, p.awake,
                g, k1, k2, dt, after)
        if p.count >= PARALLEL_MIN_PARTICLES:
            bad = _integrate_parallel(*args)
        else:
            bad = _integrate(*args, 0, p.count)
        if bad >= 0:
            raise FloatingPointError(
                f"particle {bad} became non-finite at t = {self.time:.6g} s "
                f"(position {p.position[bad].tolist()}, velocity {p.velocity[bad].tolist()}); "
                "a force is too strong for this dt, or a generator produced NaN")

        # Find contacts: every contact generator appends to the buffer. With particles
        # asleep: none when nothing can disturb them, else the rows wake what they touch and
        # those left reaching a sleeper are left out (``particle_sleep.py``).
        self.contacts.clear()
        self.contacts.dt = dt
        live = psleep.active(p) if sleepers else None
        if live is None or live.any():
            for generator in self.contact_generators:
                generator.generate(p, self.contacts)
        if live is not None:  # particles asleep (``sleepers``)
            self._wake_touched(live, g, dt)

        # Resolve them: impacts, resting contacts and links, then interpenetration.
        solved = self.solver.solve(p, self.contacts, self.impulses, dt)
        if self.bodies.count:
            rows = self._substep_bodies(dt)
            solved = SolveStats(
                contacts=solved.contacts, impact_passes=solved.impact_passes,
                velocity_passes=solved.velocity_passes + rows.velocity_passes,
                position_passes=solved.position_passes + rows.position_passes,
                resolutions=solved.resolutions, cold_restart=solved.cold_restart)
        return solved

    def _wake_disturbed(self, dt: float) -> bool:
        """Before the integration of a substep of ``dt``: wake the islands of sleeping
        particles that a force or the user disturbed (``particle_sleep.py``) and keep the
        force of those that may fall asleep after this step; returns whether any still sleep.
        """
        p = self.particles
        # Still for this long, a particle may fall asleep at the end of this step (a margin of
        # a step for the sums of the still-time's floats).
        candidate = psleep.TIME_TO_SLEEP - 2.0 * dt * self._substeps
        if p.awake.all():
            if self._longest_still < candidate:
                return False  # none can fall asleep after this step: no rest force to keep
            psleep.disturbed(p.force, p.rest_force, p.velocity, p.position, p.still_position,
                             p.inv_mass, p.rest_inv_mass, p.awake, p.sleep_time, candidate,
                             psleep.NUDGE,
                             np.zeros(0, np.bool_))
            return False
        out = np.zeros(p.count, np.bool_)
        if psleep.disturbed(p.force, p.rest_force, p.velocity, p.position, p.still_position,
                            p.inv_mass, p.rest_inv_mass, p.awake, p.sleep_time, candidate,
                             psleep.NUDGE, out):
            self._wake_particles(out)
        return not p.awake.all()

    def _wake_touched(self, live: np.ndarray, g: np.ndarray, dt: float) -> None:
        """After finding contacts with particles asleep: wake the islands that a row or a link
        joins to an active particle (those woken get this substep's kick: their rows are
        solved), until none; then leave out the rows that still reach a sleeper."""
        p = self.particles
        c = self.contacts
        if not live.any():  # nothing moves: no rows were found, no link can wake
            p.force[~p.awake] = 0.0
            return
        links = self._particle_links()
        while True:
            out = np.zeros(p.count, np.bool_)
            psleep.touched(c.a, c.b, c.normal, c.penetration, p.velocity, p.awake, live,
                           float(dt), out)
            if links.shape[0]:
                psleep.wake_linked(p, links, live, out)
            if not out.any():
                break
            woken = self._wake_particles(out)
            psleep.kick(p.velocity, p.acceleration, p.force, p.inv_mass, p.damping, woken, g,
                        float(dt))
            live = psleep.active(p)
        asleep = ~p.awake
        p.force[asleep] = 0.0  # the accumulator is consumed, as by the integration
        if c.count:
            psleep.leave_out_sleepers(c, p.awake)

    def _particle_links(self) -> np.ndarray:
        """This step's particle pairs that share an island (``psleep.link_pairs``), made once
        a step when first asked for."""
        if self._plinks is None:
            self._plinks = psleep.link_pairs(self.forces, self.contact_generators)
        return self._plinks

    def _wake_particles(self, marked: np.ndarray) -> np.ndarray:
        """Wake the islands of the sleeping particles of mask ``marked`` (and the bodies of
        those islands); returns the mask of the particles woken."""
        p = self.particles
        labels = np.unique(p.island[marked & ~p.awake])
        woken = p.wake_islands(labels)
        b = self.bodies
        if b.count and (labels < b.count).any() and not b.awake.all():
            b.wake_islands(labels)  # an island of both: its bodies get the body stage's kick
        return woken

    def _substep_bodies(self, dt: float):
        """The body stage of one substep: ``body_step`` picks the method."""
        if self._body_step == "soft":
            return self._substep_bodies_soft(dt)
        return self._substep_bodies_impulses(dt)

    def _substep_bodies_impulses(self, dt: float):
        """The rigid bodies' substep: kick (gravity, forces, torques), contacts, the solver's
        body stage on velocities, drift (x += v·dt, the free rotation), then its position
        half. Particles with a radius that touch a body join the stage as bodies without
        inertia (``rigid/particle_body.py``); with none touching, the stage sees the bodies
        alone, as in a world without particles. Sleeping bodies are skipped throughout
        (``rigid/sleep.py``)."""
        b = self.bodies
        kept, acc = self._apply_body_forces(dt)
        p = self.particles
        self._force_dt = dt
        try:  # the kick, and that of bodies woken while finding contacts, read the forces
            self._kick(dt, b.awake)
            packed, acc = self._body_contacts(dt, dt, acc)
            self._packed = packed  # the islands read its particles (``_fall_asleep``)
        finally:
            if kept is not None:
                b.force[:], b.torque[:] = kept
        if packed is None:
            rows = self.solver.solve_bodies(b, self.body_contacts, acc, self.body_impulses, dt,
                                            self.joints)
        else:  # ``acc`` came back extended to the packed particles
            rows = self.solver.solve_bodies(packed, self.body_contacts, acc,
                                            self.body_impulses, dt, self.joints)
            packed.take_velocities(b, p, dt)
        bad = integrate_positions(b.position, b.orientation, b.velocity, b.angular_velocity,
                                  b.inv_inertia, b.inv_inertia_world, dt, b.awake)
        if bad >= 0:
            raise FloatingPointError(
                f"body {bad} became non-finite at t = {self.time:.6g} s (position "
                f"{b.position[bad].tolist()}, velocity {b.velocity[bad].tolist()})")
        if packed is None:
            self.solver.project_bodies(b, rows, self.body_impulses, self.joints)
        else:
            packed.give_positions(b, p)
            self.solver.project_bodies(packed, rows, self.body_impulses, self.joints)
            packed.take_positions(b, p)
        # what the rows did not foresee (an impulse sent a body where no row looked)
        planes = [g for g in self.contact_generators if isinstance(g, Plane)]
        exclude = self.joints.pair_keys(b.count) if self.joints else None
        live = b.awake if self._sleep and not b.awake.all() else None
        rows.position_passes += project_late(b, planes, exclude, self._late_contacts, dt,
                                            self.body_contacts.key, live)
        self._body_rows = rows
        return rows

    def _substep_bodies_soft(self, dt: float):
        """The rigid bodies' substep: the first kick (gravity, forces, torques over
        dt / ``body_soft.SUBSTEPS``), contacts once, then the soft step's substeps
        (``solver/body_soft.py``: kick, warm start, soft solve, drift, relax; restitution).
        Particles with a radius that touch a body join the stage as bodies without inertia
        (``rigid/particle_body.py``); with none touching, the stage sees the bodies alone, as
        in a world without particles. Sleeping bodies are skipped throughout
        (``rigid/sleep.py``)."""
        b = self.bodies
        h = dt / body_soft.SUBSTEPS
        kept, acc = self._apply_body_forces(dt)
        p = self.particles
        self._force_dt = dt
        try:  # the first kicks (here, and of woken bodies) give the forces of the whole dt
            self._kick(h, b.awake)
            packed, acc = self._body_contacts(h, dt, acc)
            self._packed = packed  # the islands read its particles (``_fall_asleep``)
            view = b
            if packed is not None:
                view = packed
                # the particles' own step gave them the whole dt's kick: keep one substep's
                sel = packed.selected
                packed.velocity[b.count:] -= p.acceleration[sel] * (dt - h)
            rows = body_soft.step(view, b, self.body_contacts, acc, self.body_impulses, dt,
                                  self.solver.restitution_threshold, self._gravity,
                                  self.joints if self.joints else None)
        finally:
            if kept is not None:
                b.force[:], b.torque[:] = kept
        if packed is not None:
            packed.take_positions(b, p)
            b.velocity[:] = packed.velocity[:b.count]
            p.velocity[packed.selected] = packed.velocity[b.count:]
        self._body_rows = rows
        return rows

    def _apply_body_forces(self, dt: float):
        """Let the body force generators add to the user's forces for this substep, wake the
        bodies they push, and return (the user's own forces and torques to put back after the
        substep, or None; what the forces alone give each body [m/s²], for the resting-contact
        trick)."""
        b = self.bodies
        kept = None
        if self.body_forces:
            kept = b.force.copy(), b.torque.copy()
            try:
                for generator in self.body_forces:
                    generator.apply(b, dt)
            except BaseException:
                b.force[:], b.torque[:] = kept
                raise
        if self._sleep:
            sleeping.wake_pushed(b)
        w = b.inv_mass[:, None]
        return kept, np.where(w > 0.0, self._gravity + b.force * w, 0.0)

    def _kick(self, dt: float, which: np.ndarray) -> None:
        """The velocity half of the bodies' integration, for the bodies of mask ``which``:
        gravity and damping over ``dt``; forces and torques over ``self._force_dt`` (the whole
        step's for the soft step's first kick, so each force acts once, at the points and
        poses it was computed at: a body spring spread over the substeps would push bodies
        that have moved, and change Σ x × p + Iω by 3e-3 in 2.5 s)."""
        b = self.bodies
        scale = self._force_dt / dt
        force, torque = (b.force, b.torque) if scale == 1.0 else (b.force * scale,
                                                                   b.torque * scale)
        spun = integrate_velocities(b.velocity, b.angular_velocity, force, torque,
                                    b.inv_mass, b.inv_inertia, b.inv_inertia_world,
                                    b.linear_damping, b.angular_damping, self._gravity, dt, which)
        if spun >= 0:
            raise spin_error(b, spun, dt, self.time)

    def _body_contacts(self, h: float, dt: float, acc: np.ndarray):
        """This substep's body rows, then the particle–body rows; returns the packed view (or
        None) and ``acc`` extended to it. A sleeping island that a row wakes gets its first
        kick (of h) and the rows are made again, until no row touches a sleeping body that
        should wake."""
        b = self.bodies
        p = self.particles
        planes = [g for g in self.contact_generators if isinstance(g, Plane)]
        links = self._links() if self._sleep else None
        exclude = self.joints.pair_keys(b.count) if self.joints else None
        while True:
            if b.wakes != self._wakes_seen:  # islands woke (here, or by hand since)
                self._wakes_seen = b.wakes
                self.sleeping_impulses.give_back(self.body_impulses, b.awake)
            live = sleeping.active(b) if self._sleep and not b.awake.all() else None
            if live is not None and not live.any():  # all asleep or still: nothing to find
                self.body_contacts.resize(0)
            else:
                generate_body_contacts(b, planes, dt, self.body_contacts, active=live,
                                       exclude=exclude)
            packed = add_particle_contacts(b, p, dt, self.body_contacts, self._particle_friction,
                                           self._particle_restitution)
            full = acc if packed is None else np.concatenate(
                [acc, p.acceleration[packed.selected]])
            if packed is not None and self._sleep and not p.awake.all():
                # a moving body wakes the sleeping particles it touches; the rows that still
                # reach a sleeping particle are left out (``particle_sleep.py``)
                c = self.body_contacts
                out = np.zeros(p.count, np.bool_)
                movers = sleeping.active(b) if live is None else live
                if psleep.touched_by_bodies(b.count, c.a, c.b, c.normal, c.depth,
                                            packed.selected, p.velocity, b.velocity,
                                            b.angular_velocity, c.r_b, p.awake, movers,
                                            float(dt), out):
                    was = b.awake.copy()
                    self._wake_particles(out)
                    if (b.awake & ~was).any():
                        self._kick(dt, b.awake & ~was)
                    continue  # again, with the woken
                slot = c.a >= b.count
                reach = np.zeros(c.a.shape[0], np.bool_)
                reach[slot] = ~p.awake[packed.selected[c.a[slot] - b.count]]
                if reach.any():
                    c.keep(~reach)
            if live is None:
                return packed, full
            assert links is not None  # ``live`` is only set with sleeping on, as ``links``
            woken = sleeping.touched(b, self.body_contacts, packed, full, dt, links, live)
            if not woken.any():
                sleeping.leave_sleepers_out(b, self.body_contacts, packed)
                return packed, full
            self._kick(h, b.wake_islands(np.unique(b.island[woken])))

    def _links(self) -> np.ndarray:
        """The body pairs (K, 2) that share an island: ``island_links`` and every joint's."""
        links = sleeping.check_links(self.island_links, self.bodies.count)
        if not self.joints:
            return links
        return np.concatenate([links, self.joints.body_pairs()])

    def _fall_asleep(self, dt: float) -> None:
        """End of a step: islands of bodies and particles still for long enough fall asleep
        (``rigid/sleep.py``, ``particle_sleep.py``)."""
        b = self.bodies
        packed = self._packed if b.count else None
        slept, self._longest_still = psleep.fall_asleep(
            b, self.body_contacts, None if packed is None else packed.selected,
            self._links if b.count else partial(np.zeros, (0, 2), np.int64), self.particles,
            self.contacts, self._particle_links, dt)
        if slept is not None:
            self.sleeping_impulses.put_away(self.body_impulses, slept)

    # -- measurements ---------------------------------------------------------------------------
    def kinetic_energy(self) -> float:
        """Total kinetic energy of particles and rigid bodies (translation and rotation) [J]."""
        energy = self.particles.kinetic_energy()
        return energy + self.bodies.kinetic_energy() if self.bodies.count else energy

    def potential_energy(self) -> float:
        """Gravitational potential energy of particles and rigid bodies (world gravity, zero at
        y = 0) plus the energy stored by force generators that report it (springs, gravity
        generators) [J]."""
        energy = 0.0
        for store in (self.particles, self.bodies):
            moving = store.inv_mass > 0
            heights = store.position[moving] @ self._gravity
            energy -= float(np.sum(heights / store.inv_mass[moving]))
        energy += sum(f.potential_energy(self.bodies) for f in self.body_forces)
        return energy + sum(f.potential_energy(self.particles) for f in self.forces)
