"""The world: particles, force generators, contact generators, and the step that runs them."""

from __future__ import annotations

import itertools
import math
from functools import partial
from typing import Any

import numpy as np

from . import _validate as check
from . import body_stage
from . import wake_loop as wake
from .contacts import ContactBuffer, ContactGenerator, friction_value, restitution_value
from .forces import ForceGenerator, fold
from .particle_integration import integrate_particles
from .particle_sleep import active as moving_particles
from .particles import Particles
from .rigid import sleep as sleeping
from .rigid.bodies import Bodies, Body
from .rigid.contacts import BodyContacts
from .rigid.forces import BodyForceGenerator
from .rigid.joint_set import Joints
from .rigid.joints import Joint
from .rigid.shapes import Box, Sphere
from .solver import ImpulseHistory, Solver, SolverSettings, SolveStats
from .stability import SpringCheck, jump_check, needs_jump_check
from .step_stats import StepStats


class World:
    """Particles, rigid bodies and everything acting on them.

    The particles' contacts and links are solved by ``solver.Solver`` (the cookbook's
    resolver, made converging); the rigid bodies', with the particles that touch them, by
    Box2D v3's soft step (``solver/body_soft.py``: after one collision pass,
    ``settings.soft_substeps`` substeps of soft contacts and joints (``solver/joint_soft.py``)
    and relax, then restitution; it keeps linear and angular momentum exactly, stands towers
    of 30 boxes and holds joints per substep), then its continuous collision
    (``solver/body_continuous.py``).

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
        settings: The solver's tuning numbers (``pm.SolverSettings``; its defaults when None):
            tolerances, caps on passes, when the exact solve and the threads are used, the
            soft step's substeps, contact and joint stiffness, push-out speed and slop.
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
                 substeps: int = 1, sleep: bool = True,
                 settings: SolverSettings | None = None) -> None:
        self.particles = Particles()
        #: Rigid bodies (``add_body``); they meet each other, every ``Plane``/``Ground`` and every
        #: particle with radius > 0 (``rigid/particle_body.py``).
        self.bodies = Bodies()
        self.body_contacts = BodyContacts()
        #: The warm start of rigid-body contact points (clear it with ``impulses``).
        self.body_impulses = ImpulseHistory()
        self._body_rows = None
        self._packed = None  # the last substep's particle–body view (or None)
        #: The longest still-time of an awake particle after the last step [s].
        self._longest_still = 0.0
        self._plinks: np.ndarray | None = None
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
        self.solver = Solver(settings=settings)
        #: What each keyed contact needed last step (the solver's warm start); clear it after
        #: restoring a snapshot so a replay is bit-identical.
        self.impulses = ImpulseHistory()
        self.gravity = gravity
        self.iterations = iterations
        self.resolver = resolver
        self.restitution_threshold = restitution_threshold
        self.substeps = substeps
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
    def settings(self) -> SolverSettings:
        """The solver's tuning numbers (``SolverSettings``, frozen: assign a new one, e.g.
        ``dataclasses.replace(world.settings, max_velocity_passes=30)``)."""
        return self.solver.settings

    @settings.setter
    def settings(self, value: SolverSettings) -> None:
        if not isinstance(value, SolverSettings):
            raise TypeError(f"settings must be a pm.SolverSettings, got {type(value).__name__}")
        self.solver.settings = value

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
        if b.count and not b.all_awake():
            b.wake_islands(np.unique(b.island[~b.awake]))
        p = self.particles
        if p.count and not p.awake.all():
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
                resolutions, velocity, position = self._substep(h)
                iterations += resolutions
                velocity_passes += velocity
                position_passes += position
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
            wake.fall_asleep(self, float(dt))
        self._steps += 1
        pen = self.contacts.penetration
        b = self.bodies
        awake = b.awake_movable() if b.count else 0
        deepest = float(pen.max()) if pen.size and pen.max() > 0 else 0.0
        rows = self._body_rows
        if rows is not None:
            deepest = max(deepest, rows.deepest)
        for probe in self.probes:
            probe.record(self)
        return StepStats.made(contacts=self.contacts.count, iterations=iterations,
                              max_penetration=deepest, mode=self.solver.mode,
                              velocity_passes=velocity_passes, position_passes=position_passes,
                              body_contacts=self.body_contacts.count, awake_bodies=awake,
                              _energy=partial(self._energy_after, self._steps))

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

    def _substep(self, dt: float) -> tuple[int, int, int]:
        """One substep of the particle and body stages; returns their (resolutions, velocity
        passes, position passes), for ``StepStats``."""
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

        self.contacts.clear()
        self.contacts.dt = dt
        resolutions = velocity = position = 0
        if p.count:
            solved = self._substep_particles(g, k1, k2, dt)
            resolutions = solved.resolutions
            velocity, position = solved.velocity_passes, solved.position_passes
        else:  # what the particle stages do with no particles: no rows, nothing kept
            self.impulses.clear()
        if self.bodies.count:
            rows = body_stage.step(self, dt)
            velocity += rows.velocity_passes
            position += rows.position_passes
        return resolutions, velocity, position

    def _substep_particles(self, g: np.ndarray, k1: float, k2: float,
                           dt: float) -> SolveStats:
        """The particles' stages of a substep: integration, their contacts, their solve."""
        p = self.particles
        # Integrate: v += a·dt, then p += v·dt (semi-implicit Euler, the cookbook's order).
        # The acceleration is stored only where it is read: the resting-contact test of the
        # particle solver and of the body stage.
        after = bool(self.contact_generators) or self.bodies.count > 0
        sleepers = self._sleep and wake.wake_disturbed(self, dt)
        integrate_particles(p, g, k1, k2, dt, after, self.time)

        # Find contacts: every contact generator appends to the buffer. With particles
        # asleep: none when nothing can disturb them, else the rows wake what they touch and
        # those left reaching a sleeper are left out (``particle_sleep.py``).
        live = moving_particles(p) if sleepers else None
        if live is None or live.any():
            for generator in self.contact_generators:
                generator.generate(p, self.contacts)
        if live is not None:  # particles asleep (``sleepers``)
            wake.wake_touched(self, live, g, dt)

        # Resolve them: impacts, resting contacts and links, then interpenetration.
        return self.solver.solve(p, self.contacts, self.impulses, dt)

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
