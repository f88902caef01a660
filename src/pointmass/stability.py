"""Catching blow-ups before they happen, so the world is left as it was.

Semi-implicit Euler on a damped oscillator x'' = -ω²·x - γ·x' is stable only while
h²·ω² + 2·h·γ < 4 (the Jury test on its characteristic polynomial λ² - (2 - hγ - h²ω²)·λ +
(1 - hγ)). Past that every step multiplies the amplitude: a spring of k = 1e7 between two 1 kg
particles at h = 1/60 (h²ω² = 5 556) throws them 1e6 m in one step; a stiff damped bungee on a
38 g particle grows by a constant factor a step until it overflows hundreds of steps later.

For a spring s between particles a and b, ω² = k·(w_a + w_b) and γ = c·(w_a + w_b) (w = 1/m).
In a network of springs the fastest mode is at least that fast: the stiffness matrix is the sum of
every spring's (positive semi-definite) matrix, so its largest mass-weighted eigenvalue is at
least each spring's own. A spring past the bound therefore *proves* the step unstable, and the
spring kernels check it as they add their forces (a fused test, no extra pass), raising
``UnstableStepError`` before anything has moved. (A cloth can be unstable with every spring
inside the bound; that rarer case is caught as a velocity jump or a non-finite value.)

Forces from user code (``CustomForce``, a subclass) are checked after they are accumulated and
before integration: a velocity change of orders of magnitude in one step is refused, naming
the generator that pushes hardest.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .particles import Particles


class UnstableStepError(FloatingPointError):
    """A step would blow up: raised before the world changes, so a smaller dt can go on."""


def spring_too_stiff(generator, s: int, ends: str, k: float, c: float, w: float,
                     h: float) -> UnstableStepError:
    """The error for spring ``s`` of ``generator`` (ω² = k·w, γ = c·w, w = Σ 1/m of its ends)."""
    h_max = largest_stable_step(k * w, c * w)
    # Suggest half the bound: just below it the step is stable but far from accurate (the
    # amplitude of semi-implicit Euler grows as 1/√(1 - h²ω²/4)).
    substeps = math.ceil(2.0 * h / h_max) if h_max > 0 else math.inf
    smaller = (f"World(substeps={substeps}) or a smaller dt" if substeps <= 1000
               else "a smaller dt")
    return UnstableStepError(
        f"this step would blow up: {type(generator).__name__} spring {s} ({ends}) is too stiff "
        f"for dt = {h:.4g} s: h²·ω² + 2·h·γ = {(h * h * k + 2 * h * c) * w:.4g}, stable below 4 "
        f"(k = {k:.4g} N/m, damping {c:.4g} N·s/m, Σ1/m = {w:.4g} 1/kg). Remedies: a time step "
        f"below {h_max:.3g} s, better {h_max / 2:.3g} s ({smaller}), a softer or less damped "
        "spring, heavier particles, or FakeSpring (integrated exactly, stable at any dt). "
        "The world is unchanged.")


def largest_stable_step(omega_sq: float, gamma: float) -> float:
    """The h solving h²·ω² + 2·h·γ = 4 [s] (inf when nothing is stiff)."""
    if omega_sq <= 0.0:
        return 2.0 / gamma if gamma > 0.0 else math.inf
    return (-gamma + math.sqrt(gamma * gamma + 4.0 * omega_sq)) / omega_sq


@njit(cache=True, nogil=True)
def _jump_kernel(force, velocity, inv_mass, g, h, factor, floor):
    """The first movable particle whose velocity change this step would be non-finite or
    larger than factor × (|v| + |g|·h) + floor, or -1."""
    g_norm = math.sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2])
    for i in range(force.shape[0]):
        w = inv_mass[i]
        if w <= 0.0:
            continue
        dvx = (g[0] + force[i, 0] * w) * h
        dvy = (g[1] + force[i, 1] * w) * h
        dvz = (g[2] + force[i, 2] * w) * h
        dv = math.sqrt(dvx * dvx + dvy * dvy + dvz * dvz)
        v = math.sqrt(velocity[i, 0] ** 2 + velocity[i, 1] ** 2 + velocity[i, 2] ** 2)
        if not math.isfinite(dv) or dv > factor * (v + g_norm * h) + floor:
            return i
    return -1


#: A velocity change larger than JUMP_FACTOR × (|v| + |g|·dt) + JUMP_FLOOR [m/s] in one step is
#: a blow-up, not physics: from rest at 60 Hz that is an acceleration above 6·10⁴ m/s².
JUMP_FACTOR = 1000.0
JUMP_FLOOR = 1000.0


def needs_jump_check(forces) -> bool:
    """Whether some generator's forces are unknown in advance (user code): built-in ones set
    ``bounded`` (their forces stay bounded within a step, or they check themselves)."""
    return any(not getattr(g, "bounded", False) for g in forces)


def jump_check(forces, particles: Particles, gravity: np.ndarray, h: float) -> None:
    """Raise ``UnstableStepError`` if this step's accumulated forces would throw a particle
    (called after the forces, before integration, so nothing has moved yet)."""
    i = _jump_kernel(particles.force, particles.velocity, particles.inv_mass, gravity, float(h),
                     JUMP_FACTOR, JUMP_FLOOR)
    if i < 0:
        return
    culprit, size = _largest_force_on(forces, particles, i, h)
    raise UnstableStepError(
        f"this step would blow up: particle {i} would change speed by more than "
        f"{JUMP_FACTOR:g}× its speed (force {particles.force[i].tolist()} N); the largest force "
        f"on it ({size:.4g} N) comes from {culprit}. Remedies: a smaller dt or World(substeps=…), "
        "a generator that returns finite, bounded forces, or FakeSpring for stiff springs. "
        "The world is unchanged.")


def _largest_force_on(forces, particles: Particles, i: int, h: float) -> tuple[str, float]:
    """Apply each generator alone to find which pushes particle ``i`` hardest (error path
    only: the accumulator is restored afterwards)."""
    saved = particles.force.copy()
    best = ("an unknown generator", -1.0)
    try:
        for generator in forces:
            particles.force[:] = 0.0
            try:
                generator.apply(particles, h)
            except Exception as error:
                return f"{type(generator).__name__} (it raised {error!r})", math.inf
            size = float(np.linalg.norm(particles.force[i]))
            if not math.isfinite(size) or size > best[1]:
                best = (type(generator).__name__, size if math.isfinite(size) else math.inf)
    finally:
        particles.force[:] = saved
    return best
