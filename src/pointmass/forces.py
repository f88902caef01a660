"""Force generators: each adds forces to many particles at once, before integration.

The built-in generators act on index arrays through compiled loops (numba), never a Python loop
per particle. A generator built with ``particles=None`` acts on every particle of the world,
including particles added later. Springs live in ``springs.py``.

To write your own fast generator, subclass ``ForceGenerator`` and add to ``particles.force``
with numpy or numba. ``CustomForce`` takes a cookbook-style ``lambda particle: force`` instead:
convenient, but a Python call per particle per step (the slow path).

Gravity and drag on every particle are pure per-particle functions of the velocity: the world
folds them into its integration kernel (``ForceGenerator.fused_terms``, ``fold``) instead of
running a pass that writes the accumulator for the integration to read back. The forces are the
same; only where they are computed changes (free particles: one pass over memory, not two).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numba import njit

from . import _validate as check
from .particles import Particle, Particles


class ForceGenerator:
    """Adds forces to the accumulator ``particles.force`` once per (sub)step."""

    #: Drawing hint for renderers: "spring", "bungee" or None (not drawn as lines).
    kind: str | None = None
    #: True when the forces cannot jump by orders of magnitude within a step, or the generator
    #: checks its own stability. Otherwise (user code) the world checks the velocity change
    #: each step before integrating (``stability.jump_check``).
    bounded: bool = False

    def apply(self, particles: Particles, dt: float) -> None:
        raise NotImplementedError

    def fused_terms(self) -> FusedTerms | None:
        """What this generator adds to every movable particle, as terms the integration kernel
        evaluates itself (then the world does not call ``apply``); None (the default) when its
        forces must go through the accumulator. Only a generator acting on all particles
        whose force is a per-particle function of mass and velocity can say so."""
        return None

    def validate(self, particles: Particles) -> None:
        """Check particle indices when added to a world (raise naming the bad parameter)."""

    def potential_energy(self, particles: Particles) -> float:
        """Potential energy stored by this generator [J] (0 when it has none)."""
        return 0.0

    def segments(self, particles: Particles) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """Line segments a renderer may draw: (start (K,3), end (K,3), strain (K,)) or None."""
        return None


class FusedTerms(NamedTuple):
    """Forces the integration kernel computes itself, on every movable particle:
    a = acceleration + (F_accumulated - (k1 + k2·|v|)·v) / m, from the velocity before the step
    (as a generator applied before the integration sees it)."""

    #: A uniform acceleration [m/s²], shape (3,) (gravity: F = m·g), or None.
    acceleration: np.ndarray | None = None
    #: Linear drag coefficient [N·s/m].
    k1: float = 0.0
    #: Quadratic drag coefficient [N·s²/m²].
    k2: float = 0.0


def fold(generators, gravity: np.ndarray) -> tuple[list, np.ndarray, float, float]:
    """Split ``generators`` into those that add to the accumulator and those the integration
    takes over; returns (the former, gravity + their accelerations [m/s²] (3,), Σ k1, Σ k2)."""
    if not generators:
        return generators, gravity, 0.0, 0.0
    accumulating = []
    g, k1, k2 = gravity, 0.0, 0.0
    for generator in generators:
        terms = generator.fused_terms()
        if terms is None:
            accumulating.append(generator)
        else:
            if terms.acceleration is not None:
                g = g + terms.acceleration
            k1 += terms.k1
            k2 += terms.k2
    return accumulating, g, k1, k2


def _own_apply(generator, cls) -> bool:
    """Whether ``generator`` applies forces as ``cls`` does (a subclass that overrides ``apply``
    is not fused: its forces go through the accumulator, as it wrote them)."""
    return type(generator).apply is cls.apply


class _Selection:
    """The particles a generator acts on: given indices, or all (``None``) including later ones."""

    def __init__(self, particles) -> None:
        self._given = None if particles is None else np.asarray(particles)
        self._checked: np.ndarray | None = None
        self._all = np.zeros(0, np.int64)

    def validate(self, store: Particles, name: str = "particles") -> None:
        if self._given is not None:
            self._checked = store.check_indices(self._given, name)

    def indices(self, store: Particles) -> np.ndarray:
        if self._given is None:
            if self._all.shape[0] != store.count:
                self._all = np.arange(store.count, dtype=np.int64)
            return self._all
        if self._checked is None:
            self.validate(store)
        assert self._checked is not None  # validate sets it (or raises)
        return self._checked


@njit(cache=True, nogil=True)
def _gravity_kernel(force, inv_mass, idx, g):
    for k in range(idx.shape[0]):
        i = idx[k]
        w = inv_mass[i]
        if w > 0.0:  # immovable particles get no force (Cyclone adds g·REAL_MAX to them)
            m = 1.0 / w
            force[i, 0] += m * g[0]
            force[i, 1] += m * g[1]
            force[i, 2] += m * g[2]


class Gravity(ForceGenerator):
    """The cookbook's GravityGenerator: F = m·g on each selected movable particle.

    For gravity on everything, prefer the world's ``gravity`` setting (an acceleration, cheaper).

    Args:
        g: Gravitational acceleration [m/s²], a 3-vector (the cookbook's ``9.81`` strength is
            ``(0, -9.81, 0)``).
        particles: Indices to act on, or None for all.
    """

    bounded = True

    def __init__(self, g=(0.0, -9.81, 0.0), particles=None) -> None:
        self.g = check.vec3(g, "g")
        self._sel = _Selection(particles)

    def validate(self, particles: Particles) -> None:
        self._sel.validate(particles)

    def apply(self, particles: Particles, dt: float) -> None:
        _gravity_kernel(particles.force, particles.inv_mass, self._sel.indices(particles), self.g)

    def fused_terms(self) -> FusedTerms | None:
        if self._sel._given is None and _own_apply(self, Gravity):
            return FusedTerms(self.g)
        return None

    def potential_energy(self, particles: Particles) -> float:
        idx = self._sel.indices(particles)
        w = particles.inv_mass[idx]
        moving = w > 0
        heights = particles.position[idx][moving] @ self.g
        return float(-np.sum(heights / w[moving]))


@njit(cache=True, inline="always")
def drag_force(vx, vy, vz, k1, k2):
    """The cookbook's drag on velocity (vx, vy, vz) [m/s]: |F| = k1·|v| + k2·|v|² against v,
    i.e. F = -(k1 + k2·|v|)·v [N]. A pure function of scalars, shared by the generator's
    kernel and the integration kernel that fuses it (one formula, the same bits)."""
    c = k1 + k2 * np.sqrt(vx * vx + vy * vy + vz * vz)
    return -c * vx, -c * vy, -c * vz


@njit(cache=True, nogil=True)
def _drag_kernel(force, velocity, idx, k1, k2):
    for k in range(idx.shape[0]):
        i = idx[k]
        fx, fy, fz = drag_force(velocity[i, 0], velocity[i, 1], velocity[i, 2], k1, k2)
        force[i, 0] += fx
        force[i, 1] += fy
        force[i, 2] += fz


class Drag(ForceGenerator):
    """The cookbook's DragGenerator: |F| = k1·|v| + k2·|v|², opposite to the velocity.

    Args:
        k1: Linear coefficient [N·s/m], ≥ 0.
        k2: Quadratic coefficient [N·s²/m²], ≥ 0.
        particles: Indices to act on, or None for all.
    """

    bounded = True

    def __init__(self, k1: float = 0.1, k2: float = 0.1, particles=None) -> None:
        self.k1 = k1
        self.k2 = k2
        self._sel = _Selection(particles)

    @property
    def k1(self) -> float:
        """Linear drag coefficient [N·s/m]."""
        return self._k1

    @k1.setter
    def k1(self, value) -> None:
        self._k1 = check.scalar(value, "k1", low=0.0)

    @property
    def k2(self) -> float:
        """Quadratic drag coefficient [N·s²/m²]."""
        return self._k2

    @k2.setter
    def k2(self, value: float) -> None:
        self._k2 = check.scalar(value, "k2", low=0.0)

    def validate(self, particles: Particles) -> None:
        self._sel.validate(particles)

    def apply(self, particles: Particles, dt: float) -> None:
        _drag_kernel(particles.force, particles.velocity, self._sel.indices(particles),
                     self._k1, self._k2)

    def fused_terms(self) -> FusedTerms | None:
        # On every particle, the world computes it in the integration kernel (same formula).
        if self._sel._given is None and _own_apply(self, Drag):
            return FusedTerms(None, self._k1, self._k2)
        return None


@njit(cache=True, nogil=True)
def _buoyancy_kernel(force, position, idx, max_depth, volume, water_height, density, g):
    full = density * volume * g
    for k in range(idx.shape[0]):
        i = idx[k]
        y = position[i, 1]
        if y >= water_height + max_depth:
            continue  # out of the water
        if y <= water_height - max_depth:
            force[i, 1] += full  # fully submerged
        else:
            # Partly submerged: the fraction under water, 0 at the top and 1 at the bottom.
            # (Cyclone uses (y - s - h)/(2s), which is ≤ 0 and pushes the object down.)
            force[i, 1] += full * (water_height + max_depth - y) / (2.0 * max_depth)


class Buoyancy(ForceGenerator):
    """Archimedes' lift for particles near a horizontal water surface y = ``water_height``.

    A particle counts as an object of ``volume`` whose centre is ``max_depth`` below its top:
    fully submerged below ``water_height - max_depth`` (lift ρ·V·g), out of the water above
    ``water_height + max_depth``, and a linear fraction in between.

    Args:
        max_depth: Half the object's height [m], > 0.
        volume: Object volume [m³], > 0.
        water_height: Height of the water surface [m].
        liquid_density: Density ρ [kg/m³], ≥ 0 (water 1000).
        gravity: Magnitude of gravity g [m/s²], ≥ 0.
        particles: Indices to act on, or None for all.
    """

    bounded = True

    def __init__(self, max_depth: float, volume: float, water_height: float = 0.0,
                 liquid_density: float = 1000.0, gravity: float = 9.81, particles=None) -> None:
        self.max_depth = check.scalar(max_depth, "max_depth", low=0.0, low_open=True)
        self.volume = check.scalar(volume, "volume", low=0.0, low_open=True)
        self.water_height = check.scalar(water_height, "water_height")
        self.liquid_density = liquid_density
        self.gravity = check.scalar(gravity, "gravity", low=0.0)
        self._sel = _Selection(particles)

    @property
    def liquid_density(self) -> float:
        """Liquid density [kg/m³]."""
        return self._rho

    @liquid_density.setter
    def liquid_density(self, value: float) -> None:
        self._rho = check.scalar(value, "liquid_density", low=0.0)

    def validate(self, particles: Particles) -> None:
        self._sel.validate(particles)

    def apply(self, particles: Particles, dt: float) -> None:
        _buoyancy_kernel(particles.force, particles.position, self._sel.indices(particles),
                         self.max_depth, self.volume, self.water_height, self._rho, self.gravity)


class CustomForce(ForceGenerator):
    """A user callable in the cookbook's style: ``fn(particle) -> force`` [N].

    ``particle`` is a ``Particle`` handle (``.position``, ``.velocity``, ``.mass``). This is the
    slow path: one Python call per particle per step; fine for a handful of particles. For
    many, subclass ``ForceGenerator`` and work on the arrays.

    Args:
        fn: The force function; it must return a finite 3-vector.
        particles: Indices to act on, or None for all.
    """

    def __init__(self, fn: Callable[[Particle], object], particles=None) -> None:
        if not callable(fn):
            raise TypeError(f"fn must be callable (particle -> force), got {fn!r}")
        self.fn = fn
        self._sel = _Selection(particles)

    def validate(self, particles: Particles) -> None:
        self._sel.validate(particles)

    def apply(self, particles: Particles, dt: float) -> None:
        force = particles.force
        for i in self._sel.indices(particles).tolist():
            f = np.asarray(self.fn(Particle(particles, i)), dtype=np.float64)
            if f.shape != (3,) or not np.isfinite(f).all():
                raise ValueError(f"CustomForce {self.fn!r} returned {f!r} for particle {i}; "
                                 "it must return a finite 3-vector")
            force[i] += f
