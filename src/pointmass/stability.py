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
``UnstableStepError`` before anything has moved.

Springs can be unstable together with each inside its own bound: two damped bungees on a 38 g
particle, each at h²ω² + 2hγ ≈ 3.7, put 7 on their shared mode, and the step grows the amplitude
by a constant factor until it overflows hundreds of steps later. So before a step the world
checks the springs together (``particle_check``), on S = h²·A + 2h·B with A = M^-½·K·M^-½ and
B = M^-½·C·M^-½ (mass-weighted stiffness and damping, each spring's 3×3 block k·n·nᵀ or c·n·nᵀ
along its direction n; linear drag k₁ adds k₁·w on the diagonal of B). Its largest eigenvalue
is the one-mode test's h²ω² + 2hγ of the fastest mode (exactly, when stiffness and damping share
their modes, as a cloth's do):

1. *screen*, every step: Gershgorin's theorem bounds it by the largest row sum,
   Σ_s (h²kₛ + 2h·cₛ)·(wᵢ + √(wᵢ·wⱼ)) + 2h·k₁·wᵢ over the springs s from particle i to j
   (wⱼ = 0 for an anchor), with √(wᵢ·wⱼ) ≤ (wᵢ + wⱼ)/2. Below 4 the step goes on: no mode can
   be unstable. Exact for one spring between equal masses and for an anchored spring; a uniform
   cloth's row sum is the checkerboard mode's value in a flat 1-D chain, above its real one.
2. *measure*, only past the screen: power iteration on S (a fixed start, so deterministic)
   gives the fastest mode's h²ω² + 2hγ, from below; at or above 4 the step is refused, naming
   the particle that mode moves most, the generators on it and the largest stable step.
   (The 40×40 cloth at k = 400 N/m: screen 5.9, measured below 4, and it runs, as before; at
   damping 1 N·s/m, measured above 4: refused, where it used to blow up until the jump check
   caught it.)

A single spring past its own bound is named as the spring kernels name it. Nothing is cached
(a spring constant, mass or dt changed between steps is always seen); the screen's cost is in
``tests/physics/test_particle_stability.py``'s docstring.

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
def _pair_rows(inv_mass, a, b, k, c, h, out):
    """Add the Gershgorin row sums of h²·K + 2h·C of springs a[s]–b[s] to both ends
    (``particle_check``), with √(wᵢ·wⱼ) ≤ (wᵢ + wⱼ)/2 (exact for equal masses, and no square
    root: this screen runs every step)."""
    for s in range(a.shape[0]):
        i = a[s]
        j = b[s]
        e = 0.5 * (h * h * k[s] + 2.0 * h * c[s])
        wi = inv_mass[i]
        wj = inv_mass[j]
        out[i] += e * (3.0 * wi + wj)
        out[j] += e * (3.0 * wj + wi)


@njit(cache=True, nogil=True)
def _anchored_rows(inv_mass, idx, k, c, h, out):
    """The same for springs from particles idx[s] to fixed anchors (no off-diagonal term)."""
    for s in range(idx.shape[0]):
        i = idx[s]
        out[i] += (h * h * k[s] + 2.0 * h * c[s]) * inv_mass[i]


@njit(cache=True, nogil=True)
def _largest_row(out, inv_mass, k1, h):
    """The largest row sum, linear drag k1 added (2h·k1·w on the diagonal); NaN wins."""
    largest = -1.0
    for i in range(out.shape[0]):
        value = out[i] + 2.0 * h * k1 * inv_mass[i]
        if not value <= largest:
            largest = value
    return largest


class SpringCheck:
    """The world's check of its springs together (the module docstring), with what it keeps
    between steps: the screen's row sums and the fastest mode measured for them, so a scene
    past the screen but stable (the stiffest cloth) is measured again only when its springs,
    masses or dt change, or its mode came within ``REUSE_MARGIN`` of the limit; the mode
    starts the next measurement (a few power iterations instead of dozens)."""

    def __init__(self) -> None:
        self._sums: np.ndarray | None = None
        self._measured = math.inf
        self._mode: np.ndarray | None = None

    def __call__(self, forces, particles: Particles, k1: float, h: float) -> None:
        particle_check(forces, particles, k1, h, self)


#: A measured mode below (1 − REUSE_MARGIN) × 4 is trusted while the screen's row sums stay the
#: same bits (only the springs' directions changed). Measured on the 40×40 cloth demo at
#: k = 400 N/m over its first second: 2.926 to 2.940, at most 0.07 % apart 4 steps apart.
REUSE_MARGIN = 0.05


def particle_check(forces, particles: Particles, k1: float, h: float,
                   kept: SpringCheck | None = None) -> None:
    """Raise ``UnstableStepError`` before a step of ``h`` if the springs, bungees, anchored
    springs and linear drag ``k1`` on the particles, summed, put the fastest mode past the
    stability limit (the module docstring): the Gershgorin bound screens; past it, the mode is
    measured (``kept`` remembers it, see ``SpringCheck``). Names the particle that mode moves
    most, the generators acting on it and the largest stable step; a single spring past its own
    bound is named as the spring kernels name it. Nothing moves."""
    springs = [g for g in forces if hasattr(g, "stiffness_rows")]
    n = particles.count
    if n == 0 or (not springs and k1 == 0.0):
        return
    w = particles.inv_mass
    h = float(h)
    sums = np.zeros(n)
    rows = [(g, *g.stiffness_rows(particles)) for g in springs]
    for _, a, b, k, c in rows:
        if b is None:
            _anchored_rows(w, a, k, c, h, sums)
        else:
            _pair_rows(w, a, b, k, c, h, sums)
    sums += 2.0 * h * k1 * w
    if _largest_row(sums, w, 0.0, h) < 4.0:
        return
    if (kept is not None and kept._sums is not None and kept._sums.shape == sums.shape
            and kept._measured < 4.0 * (1.0 - REUSE_MARGIN) and np.array_equal(kept._sums, sums)):
        return
    for g, a, b, k, c in rows:  # one spring past its own (exact) bound: name it as it would
        pair = w[a] if b is None else w[a] + w[b]
        over = np.flatnonzero((h * h * k + 2.0 * h * c) * pair >= 4.0)
        if over.size:
            s = int(over[0])
            ends = (f"particle {int(a[s])} to its anchor" if b is None
                    else f"particles {int(a[s])}–{int(b[s])}")
            raise spring_too_stiff(g, s, ends, float(k[s]), float(c[s]), float(pair[s]), h)
    start = kept._mode if kept is not None else None
    stiff, damped, mode = _fastest_mode(rows, particles, float(k1), h, start)
    largest = h * h * stiff + 2.0 * h * damped
    if kept is not None:
        kept._sums, kept._measured, kept._mode = sums, largest, mode
    if largest < 4.0:
        return
    i = int(np.argmax(np.einsum("ij,ij->i", mode, mode)))
    h_max = largest_stable_step(stiff, damped)
    on_it = []
    for g, a, b, _, _ in rows:
        hits = np.flatnonzero((a == i) if b is None else (a == i) | (b == i))
        if hits.size:
            listed = ", ".join(str(int(s)) for s in hits[:6]) + (", …" if hits.size > 6 else "")
            on_it.append(f"{type(g).__name__} spring{'s' if hits.size > 1 else ''} {listed}")
    if k1 > 0.0:
        on_it.append(f"linear drag k1 = {k1:.4g} N·s/m")
    substeps = math.ceil(2.0 * h / h_max) if h_max > 0 else math.inf
    smaller = (f"World(substeps={substeps}) or a smaller dt" if substeps <= 1000
               else "a smaller dt")
    raise UnstableStepError(
        f"this step would blow up: springs that are each stable alone are together too stiff "
        f"or too damped for dt = {h:.4g} s: their fastest mode, which moves particle {i} "
        f"(mass {_mass(w[i])}) most, has h²·ω² + 2·h·γ = {largest:.4g}, stable below 4 "
        f"(ω² = {stiff:.4g} 1/s², γ = {damped:.4g} 1/s). Acting on particle {i}: "
        f"{'; '.join(on_it)}. Remedies: a time step below {h_max:.3g} s, better "
        f"{h_max / 2:.3g} s ({smaller}), softer or less damped springs, heavier particles, or "
        "FakeSpring. The world is unchanged.")


#: Power iterations at most for the fastest mode (``_fastest_mode``), and the relative change
#: of its eigenvalue estimate at which they stop.
MODE_ITERATIONS = 200
MODE_TOLERANCE = 1e-6


@njit(cache=True, nogil=True)
def _apply_pairs(pos, inv_mass, a, b, k, c, x, out_k, out_c):
    """out += the mass-weighted stiffness (and damping) matrix times x, for springs a–b: each
    spring's block is k·n·nᵀ along its current direction n (its linear response)."""
    for s in range(a.shape[0]):
        i = a[s]
        j = b[s]
        nx = pos[i, 0] - pos[j, 0]
        ny = pos[i, 1] - pos[j, 1]
        nz = pos[i, 2] - pos[j, 2]
        length = math.sqrt(nx * nx + ny * ny + nz * nz)
        if length == 0.0:
            continue
        nx /= length
        ny /= length
        nz /= length
        si = math.sqrt(inv_mass[i])
        sj = math.sqrt(inv_mass[j])
        d = (nx * (si * x[i, 0] - sj * x[j, 0]) + ny * (si * x[i, 1] - sj * x[j, 1])
             + nz * (si * x[i, 2] - sj * x[j, 2]))
        for axis, n in ((0, nx), (1, ny), (2, nz)):
            out_k[i, axis] += k[s] * si * d * n
            out_k[j, axis] -= k[s] * sj * d * n
            out_c[i, axis] += c[s] * si * d * n
            out_c[j, axis] -= c[s] * sj * d * n


@njit(cache=True, nogil=True)
def _apply_anchored(pos, inv_mass, idx, anchor, k, c, x, out_k, out_c):
    """The same for springs from particles idx[s] to fixed anchors."""
    for s in range(idx.shape[0]):
        i = idx[s]
        nx = pos[i, 0] - anchor[s, 0]
        ny = pos[i, 1] - anchor[s, 1]
        nz = pos[i, 2] - anchor[s, 2]
        length = math.sqrt(nx * nx + ny * ny + nz * nz)
        if length == 0.0:
            continue
        nx /= length
        ny /= length
        nz /= length
        w = inv_mass[i]
        d = w * (nx * x[i, 0] + ny * x[i, 1] + nz * x[i, 2])
        for axis, n in ((0, nx), (1, ny), (2, nz)):
            out_k[i, axis] += k[s] * d * n
            out_c[i, axis] += c[s] * d * n


def _fastest_mode(rows, particles: Particles, k1: float, h: float, start=None):
    """The mode of the largest h²·ω² + 2h·γ (power iteration on the mass-weighted
    h²·stiffness + 2h·damping, from a fixed start: deterministic), as (its ω² [1/s²], its γ
    [1/s], the mode (N, 3)). The estimate converges from below. Run only when the Gershgorin
    screen failed, so a scene well inside the bound never pays for it."""
    pos = particles.position
    w = particles.inv_mass
    n = particles.count
    idx = np.arange(n)
    if start is not None and start.shape == (n, 3):
        x = start.copy()  # last step's mode: the same bits for the same history
    else:
        x = np.column_stack([(-1.0) ** idx, 0.7 * (-1.0) ** (idx // 2),
                             0.4 * (-1.0) ** (idx // 3)])
    x[w == 0.0] = 0.0
    x /= max(float(np.linalg.norm(x)), 1e-300)
    estimate = 0.0
    for _ in range(MODE_ITERATIONS):
        stiff = np.zeros((n, 3))
        damped = k1 * w[:, None] * x
        for g, a, b, k, c in rows:
            if b is None:
                _apply_anchored(pos, w, a, g.anchor, k, c, x, stiff, damped)
            else:
                _apply_pairs(pos, w, a, b, k, c, x, stiff, damped)
        y = h * h * stiff + 2.0 * h * damped
        value = float(np.sum(x * y))
        size = float(np.linalg.norm(y))
        if size == 0.0 or abs(value - estimate) <= MODE_TOLERANCE * value:
            break
        estimate = value
        x = y / size
    return float(np.sum(x * stiff)), float(np.sum(x * damped)), x


def _mass(w: float) -> str:
    return f"{1.0 / w:.4g} kg" if w > 0 else "inf"


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
