"""Springs: Hooke's law between particles, or between a particle and a fixed anchor.

One generator object holds many springs (index arrays ``a``, ``b``), as a cloth needs. The force
is *signed*: a stretched spring pulls its ends together and a compressed one pushes them apart.
(The cookbook and Cyclone use abs(extension), so their compressed springs pull too.) Bungees pull
only when stretched. An optional damping term resists the ends' relative speed along the spring.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from . import _validate as check
from .forces import ForceGenerator, _Selection
from .particles import Particles
from .stability import spring_too_stiff


@njit(cache=True, inline="always")
def _tension(dx, dy, dz, dvx, dvy, dvz, k, rest, c, pull_only):
    """The force of one spring on its end a, as a multiple f of the separation d = a - b:
    F_a = f·d [N] (F_b = -F_a), from d [m], the relative velocity dv = v_a - v_b [m/s], the
    spring constant k [N/m], rest length [m] and damping c [N·s/m]. Signed Hooke (a compressed
    spring pushes); 0 for coincident ends (no direction) and a slack bungee (pull_only).
    One body for the spring and the anchored spring (one reciprocal, not two divisions)."""
    length = math.sqrt(dx * dx + dy * dy + dz * dz)
    if length == 0.0:
        return 0.0
    extension = length - rest
    if pull_only and extension <= 0.0:
        return 0.0
    inv = 1.0 / length
    f = -k * extension
    if c != 0.0:
        f -= c * (dvx * dx + dvy * dy + dvz * dz) * inv  # damping of the closing speed
    return f * inv


@njit(cache=True, inline="always")
def _too_stiff(k, c, w, h):
    """Whether a spring of constant k and damping c on ends of total inverse mass w [1/kg] is
    past the stability bound h²·ω² + 2·h·γ < 4 at step h (stability.py)."""
    return (h * h * k + 2.0 * h * c) * w >= 4.0


@njit(cache=True, nogil=True)
def _spring_kernel(pos, vel, force, inv_mass, a, b, k, rest, damping, pull_only, h):
    """Add every spring's force; return the first spring too stiff for a step of h (its
    h²·ω² + 2·h·γ ≥ 4, see stability.py), or -1, before adding any. The check runs as a loop
    of its own: inside the force loop it cost 5 ns of 24 a spring, alone 2 (measured on the
    100 × 100 cloth)."""
    for s in range(a.shape[0]):
        if _too_stiff(k[s], damping[s], inv_mass[a[s]] + inv_mass[b[s]], h):
            return s
    for s in range(a.shape[0]):
        i = a[s]
        j = b[s]
        dx = pos[i, 0] - pos[j, 0]
        dy = pos[i, 1] - pos[j, 1]
        dz = pos[i, 2] - pos[j, 2]
        f = _tension(dx, dy, dz, vel[i, 0] - vel[j, 0], vel[i, 1] - vel[j, 1],
                     vel[i, 2] - vel[j, 2], k[s], rest[s], damping[s], pull_only)
        force[i, 0] += f * dx
        force[i, 1] += f * dy
        force[i, 2] += f * dz
        force[j, 0] -= f * dx
        force[j, 1] -= f * dy
        force[j, 2] -= f * dz
    return -1


@njit(cache=True, nogil=True)
def _anchored_kernel(pos, vel, force, inv_mass, idx, anchor, k, rest, damping, pull_only, h):
    """As ``_spring_kernel``, the other end fixed at ``anchor[s]``."""
    for s in range(idx.shape[0]):
        if _too_stiff(k[s], damping[s], inv_mass[idx[s]], h):
            return s
    for s in range(idx.shape[0]):
        i = idx[s]
        dx = pos[i, 0] - anchor[s, 0]
        dy = pos[i, 1] - anchor[s, 1]
        dz = pos[i, 2] - anchor[s, 2]
        f = _tension(dx, dy, dz, vel[i, 0], vel[i, 1], vel[i, 2], k[s], rest[s], damping[s],
                     pull_only)
        force[i, 0] += f * dx
        force[i, 1] += f * dy
        force[i, 2] += f * dz
    return -1


class _SpringSet(ForceGenerator):
    """Shared storage of spring constants, rest lengths and damping, one per spring."""

    _pull_only = False
    bounded = True  # checks its own stability as it runs (stability.py)

    def _init_params(self, count: int, spring_constant, rest_length, damping) -> None:
        self._count = count
        self.spring_constant = spring_constant
        self.rest_length = rest_length
        self.damping = damping

    def __len__(self) -> int:
        return self._count

    @property
    def spring_constant(self) -> np.ndarray:
        """Spring constants k [N/m], shape (K,); assign a number or an array."""
        return self._k

    @spring_constant.setter
    def spring_constant(self, value) -> None:
        self._k = check.scalar_array(value, "spring_constant", self._count, low=0.0)

    @property
    def rest_length(self) -> np.ndarray:
        """Rest lengths [m], shape (K,)."""
        return self._rest

    @rest_length.setter
    def rest_length(self, value) -> None:
        self._rest = check.scalar_array(value, "rest_length", self._count, low=0.0)

    @property
    def damping(self) -> np.ndarray:
        """Damping along the spring [N·s/m], shape (K,)."""
        return self._damping

    @damping.setter
    def damping(self, value) -> None:
        self._damping = check.scalar_array(value, "damping", self._count, low=0.0)

    def _energy(self, lengths: np.ndarray) -> float:
        ext = lengths - self._rest
        if self._pull_only:
            ext = np.maximum(ext, 0.0)
        return float(0.5 * np.sum(self._k * ext * ext))

    def _strain(self, lengths: np.ndarray) -> np.ndarray:
        return (lengths - self._rest) / np.maximum(self._rest, 1e-9)


class Spring(_SpringSet):
    """Springs between particle pairs ``a[s]``–``b[s]``.

    Args:
        a, b: Particle indices (ints or arrays of equal length K).
        spring_constant: k [N/m], ≥ 0 (one number or K).
        rest_length: l0 [m], ≥ 0.
        damping: Damping along the spring [N·s/m], ≥ 0 (default 0, as in the cookbook).
    """

    kind = "spring"

    def __init__(self, a, b, spring_constant: float = 10.0, rest_length: float = 1.0, *,
                 damping: float = 0.0) -> None:
        self._a_given = np.atleast_1d(np.asarray(a))
        self._b_given = np.atleast_1d(np.asarray(b))
        if self._a_given.shape != self._b_given.shape:
            raise ValueError(f"a and b must have the same length, got {self._a_given.shape[0]} "
                             f"and {self._b_given.shape[0]}")
        self.a = self._a_given.astype(np.int64)
        self.b = self._b_given.astype(np.int64)
        self._init_params(self.a.shape[0], spring_constant, rest_length, damping)

    def validate(self, particles: Particles) -> None:
        self.a = particles.check_indices(self._a_given, "a")
        self.b = particles.check_indices(self._b_given, "b")
        same = self.a == self.b
        if same.any():
            raise ValueError(f"a spring joins particle {int(self.a[same][0])} to itself")

    def apply(self, particles: Particles, dt: float) -> None:
        s = _spring_kernel(particles.position, particles.velocity, particles.force,
                           particles.inv_mass, self.a, self.b, self._k, self._rest,
                           self._damping, self._pull_only, float(dt))
        if s >= 0:
            a, b = int(self.a[s]), int(self.b[s])
            w = float(particles.inv_mass[a] + particles.inv_mass[b])
            raise spring_too_stiff(self, s, f"particles {a}–{b}", float(self._k[s]),
                                   float(self._damping[s]), w, dt)

    def stiffness_rows(self, particles: Particles):
        """(a, b, k, c): the springs' ends, constants and damping, for the world's
        per-particle stability check (``stability.particle_check``)."""
        return self.a, self.b, self._k, self._damping

    def lengths(self, particles: Particles) -> np.ndarray:
        """Current lengths [m], shape (K,)."""
        p = particles.position
        return np.linalg.norm(p[self.a] - p[self.b], axis=1)

    def potential_energy(self, particles: Particles) -> float:
        return self._energy(self.lengths(particles))

    def segments(self, particles: Particles):
        p = particles.position
        return p[self.a], p[self.b], self._strain(self.lengths(particles))


class Bungee(Spring):
    """Elastic cords between particle pairs: like ``Spring`` but pull only when stretched.

    (Cyclone's ParticleBungee flips the sign and pushes stretched ends apart.)
    """

    kind = "bungee"
    _pull_only = True


class AnchoredSpring(_SpringSet):
    """Springs from particles to fixed points (the cookbook's AnchoredSpringGenerator).

    Args:
        particles: Particle indices (an int or an array of K).
        anchor: Anchor positions [m], a 3-vector or shape (K, 3); the ``anchor`` attribute may be
            moved while the world runs.
        spring_constant, rest_length, damping: As for ``Spring``.
    """

    kind = "spring"

    def __init__(self, particles, anchor, spring_constant: float = 10.0,
                 rest_length: float = 1.0, *, damping: float = 0.0) -> None:
        self._given = np.atleast_1d(np.asarray(particles))
        self._sel = _Selection(self._given)
        count = self._given.shape[0]
        self.anchor = check.vec3_array(anchor, "anchor", count).copy()
        self._init_params(count, spring_constant, rest_length, damping)

    @property
    def particles(self) -> np.ndarray:
        return self._sel._checked if self._sel._checked is not None else self._given

    def validate(self, particles: Particles) -> None:
        self._sel.validate(particles)

    def apply(self, particles: Particles, dt: float) -> None:
        idx = self._sel.indices(particles)
        s = _anchored_kernel(particles.position, particles.velocity, particles.force,
                             particles.inv_mass, idx, self.anchor, self._k, self._rest,
                             self._damping, self._pull_only, float(dt))
        if s >= 0:
            i = int(idx[s])
            raise spring_too_stiff(self, s, f"particle {i} to its anchor", float(self._k[s]),
                                   float(self._damping[s]), float(particles.inv_mass[i]), dt)

    def stiffness_rows(self, particles: Particles):
        """(particles, None, k, c): as ``Spring.stiffness_rows``, the other end fixed."""
        return self._sel.indices(particles), None, self._k, self._damping

    def lengths(self, particles: Particles) -> np.ndarray:
        return np.linalg.norm(particles.position[self._sel.indices(particles)] - self.anchor,
                              axis=1)

    def potential_energy(self, particles: Particles) -> float:
        return self._energy(self.lengths(particles))

    def segments(self, particles: Particles):
        return (particles.position[self._sel.indices(particles)], self.anchor.copy(),
                self._strain(self.lengths(particles)))


class AnchoredBungee(AnchoredSpring):
    """Anchored elastic cords: pull toward the anchor only when stretched."""

    kind = "bungee"
    _pull_only = True


@njit(cache=True, nogil=True)
def _fake_spring_kernel(pos, vel, force, inv_mass, idx, anchor, k, d, dt, expect_pos,
                        expect_vel, exact_vel, valid):
    for s in range(idx.shape[0]):
        i = idx[s]
        w = inv_mass[i]
        if w <= 0.0:
            valid[s] = False
            continue
        # Semi-implicit Euler leaves the particle with the secant velocity (x1 - x0)/dt, not
        # the oscillator's velocity at t1. If nothing else moved the particle since our last
        # step (it is where we sent it), continue from the exact velocity we kept; otherwise
        # (other forces, a reset) start from the particle's own velocity.
        undisturbed = valid[s]
        if undisturbed:
            for c in range(3):
                tol = 1e-9 * (1.0 + abs(expect_pos[s, c]) + abs(expect_vel[s, c]))
                if (abs(pos[i, c] - expect_pos[s, c]) > tol
                        or abs(vel[i, c] - expect_vel[s, c]) > tol):
                    undisturbed = False
        # Solve x'' = -k·x - d·x' exactly over dt for x = p - anchor (k, d per unit mass),
        # then apply the constant acceleration that lands the particle on that solution.
        disc = 4.0 * k - d * d
        decay = math.exp(-0.5 * d * dt)
        for c in range(3):
            x0 = pos[i, c] - anchor[s, c]
            v0 = exact_vel[s, c] if undisturbed else vel[i, c]
            if disc > 0.0:  # under-damped: Millington's formula
                gamma = 0.5 * math.sqrt(disc)
                coef = (0.5 * d * x0 + v0) / gamma
                cs = math.cos(gamma * dt)
                sn = math.sin(gamma * dt)
                x1 = decay * (x0 * cs + coef * sn)
                v1 = -0.5 * d * x1 + decay * gamma * (coef * cs - x0 * sn)
            elif disc < 0.0:  # over-damped: hyperbolic, where Cyclone takes sqrt(<0) = NaN
                gamma = 0.5 * math.sqrt(-disc)
                coef = (0.5 * d * x0 + v0) / gamma
                ch = math.cosh(gamma * dt)
                sh = math.sinh(gamma * dt)
                x1 = decay * (x0 * ch + coef * sh)
                v1 = -0.5 * d * x1 + decay * gamma * (coef * ch + x0 * sh)
            else:  # critically damped
                x1 = decay * (x0 + (v0 + 0.5 * d * x0) * dt)
                v1 = -0.5 * d * x1 + decay * (v0 + 0.5 * d * x0)
            accel = (x1 - x0) / (dt * dt) - vel[i, c] / dt
            force[i, c] += accel / w
            expect_vel[s, c] = (x1 - x0) / dt
            expect_pos[s, c] = anchor[s, c] + x1
            exact_vel[s, c] = v1
        valid[s] = True


class FakeSpring(ForceGenerator):
    """Millington's fake stiff spring: a damped spring to an anchor, integrated analytically so
    very stiff values stay stable at large time steps.

    ``spring_constant`` and ``damping`` are per unit mass (as in the book): the particle follows
    x'' = -k·x - d·x' relative to the anchor. Under-, critically and over-damped springs are all
    handled (Cyclone produces NaN when d² > 4k). While nothing else acts on the particle it stays
    on the exact solution (the generator keeps the oscillator's velocity, which the integrator's
    secant velocity is not); other forces make it restart from the particle's velocity.

    Args:
        particles: Particle indices (an int or an array of K).
        anchor: Anchor positions [m], a 3-vector or shape (K, 3).
        spring_constant: k [1/s²], ≥ 0.
        damping: d [1/s], ≥ 0.
    """

    bounded = True  # integrated exactly: stable at any dt

    kind = "spring"

    def __init__(self, particles, anchor, spring_constant: float, damping: float = 0.0) -> None:
        self._given = np.atleast_1d(np.asarray(particles))
        self._sel = _Selection(self._given)
        count = self._given.shape[0]
        self.anchor = check.vec3_array(anchor, "anchor", count).copy()
        self.spring_constant = check.scalar(spring_constant, "spring_constant", low=0.0)
        self.damping = check.scalar(damping, "damping", low=0.0)
        # Where each particle should be after the step, and its exact oscillator velocity.
        self._expect_pos = np.zeros((count, 3))
        self._expect_vel = np.zeros((count, 3))
        self._exact_vel = np.zeros((count, 3))
        self._valid = np.zeros(count, np.bool_)

    def validate(self, particles: Particles) -> None:
        self._sel.validate(particles)

    def apply(self, particles: Particles, dt: float) -> None:
        _fake_spring_kernel(particles.position, particles.velocity, particles.force,
                            particles.inv_mass, self._sel.indices(particles), self.anchor,
                            self.spring_constant, self.damping, dt, self._expect_pos,
                            self._expect_vel, self._exact_vel, self._valid)

    def segments(self, particles: Particles):
        # A fake spring has no rest length, so no strain to colour by: draw it neutral.
        p = particles.position[self._sel.indices(particles)]
        return p, self.anchor.copy(), np.zeros(len(p))
