"""A million particles in a dust storm, lifted in a whirlwind's core and falling outside it.

Round and round, shadows and all.

Each particle is dragged toward the local wind (a drag force k·m·(wind − v), k per second) under
gravity. The wind is a Rankine vortex (a core of radius ``core`` turning as a solid body at
``swirl`` m/s at its rim, the speed falling off as 1/r outside) with an updraft in the core that
dies out toward the storm's ``top``, inflow near the ground (where friction slows the swirl) and
outflow aloft, so dust circulates through the funnel; a soft floor (a damped spring) keeps it
off the ground. One parallel pass per step (numba), the same cost per particle as the world's
own integration.

It exists to show what the renderer's hardware path does with 1 000 000 spheres (``count``); a
software rasterizer (llvmpipe) draws it at a few frames a second: ``--set count=20000`` there.

Run: pointmass run particle_storm
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit, prange

from pointmass import CameraHint, ForceGenerator, Scene, World, tweak

TITLE = "Particle storm (1 000 000 particles)"
#: The storm's height [m] and the radius [m] the dust starts within.
TOP = 14.0
START_RADIUS = 9.0
RADIUS = 0.05


@dataclass
class Params:
    swirl: float = tweak(9.0, 0.0, 20.0, "Wind speed at the core's rim [m/s]")
    core: float = tweak(2.5, 0.5, 6.0, "Core radius [m]")
    updraft: float = tweak(16.0, 0.0, 30.0, "Updraft at the core's centre [m/s]")
    coupling: float = tweak(1.5, 0.1, 5.0, "Drag toward the wind k [1/s]")
    count: int = tweak(1_000_000, 1000, 2_000_000, "Particles", rebuild=True)
    seed: int = tweak(7, 0, 9999, "Random seed", rebuild=True)


@njit(cache=True, parallel=True, nogil=True)
def _storm_forces(pos, vel, force, inv_mass, swirl, core, updraft, inflow, top, k):
    """Add k·m·(wind(x) − v) and the soft floor's force to every movable particle."""
    for i in prange(pos.shape[0]):
        w = inv_mass[i]
        if w <= 0.0:
            continue
        # Grains of different sizes feel the wind differently (k from 0.5 to 1.5 times its
        # value, fixed per particle): the dust spreads through the funnel instead of cycling
        # in step.
        m = 1.0 / w
        kk = k * (0.5 + ((i * 2654435761) % 1000) / 1000.0)
        x, y, z = pos[i, 0], pos[i, 1], pos[i, 2]
        r = math.sqrt(x * x + z * z) + 1e-9
        h = min(max(y / top, 0.0), 1.5)
        # Rankine vortex: solid-body rotation inside the core, 1/r outside; slowed by the
        # ground within a few metres of it, where the inflow then carries dust to the core.
        spin = swirl * (r / core if r < core else core / r) * min(1.0, 0.1 + y / 3.0)
        lift = updraft * math.exp(-(r / core) ** 2) * (1.0 - h)
        # Inflow near the ground, outflow aloft, and a pull back in far out.
        radial = -inflow * (1.0 - 2.0 * h) - inflow * (r / (3.0 * top)) ** 2
        wx = (radial * x - spin * z) / r
        wz = (radial * z + spin * x) / r
        force[i, 0] += kk * m * (wx - vel[i, 0])
        force[i, 1] += kk * m * (lift - vel[i, 1])
        force[i, 2] += kk * m * (wz - vel[i, 2])
        if y < RADIUS:                                  # the soft floor
            force[i, 1] += m * (4000.0 * (RADIUS - y) - 60.0 * min(vel[i, 1], 0.0))


class StormWind(ForceGenerator):
    """The whirlwind's drag on every particle (see the module's docstring)."""

    bounded = True      # a drag toward a bounded wind, k·dt ≪ 1: no jumps to check

    def __init__(self, p: Params) -> None:
        self.params = p

    def apply(self, particles, dt: float) -> None:
        p = self.params
        _storm_forces(particles.position, particles.velocity, particles.force,
                      particles.inv_mass, p.swirl, p.core, p.updraft, 0.25 * p.swirl, TOP,
                      p.coupling)


def build(p: Params) -> Scene:
    rng = np.random.default_rng(p.seed)
    world = World(gravity=(0.0, -9.81, 0.0))
    # Dust lying in a disc round the storm (denser toward the middle), a little off the ground.
    r = START_RADIUS * np.sqrt(rng.uniform(0.0, 1.0, p.count)) ** 1.3
    a = rng.uniform(0.0, 2.0 * np.pi, p.count)
    pos = np.c_[r * np.cos(a), rng.uniform(RADIUS, 2.5, p.count), r * np.sin(a)]
    world.add_particles(pos, radii=RADIUS)
    wind = world.add(StormWind(p))
    # Sand to rust by starting distance from the axis: the layers show how the dust mixes.
    t = (r / START_RADIUS)[:, None]
    colors = (1.0 - t) * np.array([0.93, 0.80, 0.55]) + t * np.array([0.62, 0.30, 0.16])
    colors *= rng.uniform(0.85, 1.1, (p.count, 1))
    return Scene(world, camera=CameraHint(target=(0.0, 3.5, 0.0), distance=21.0, yaw=20.0,
                                          pitch=14.0, fov=50.0),
                 colors=np.clip(colors, 0.0, 1.0), point_radius=RADIUS, dt=1.0 / 60.0,
                 show_links=False, handles={"wind": wind, "params": p})


def apply(scene: Scene, p: Params) -> None:
    scene.handles["wind"].params = p
    scene.handles["params"] = p


def check(scene: Scene) -> None:
    """The oracle: the dust turns the wind's way at about its speed, and the storm holds
    together (inside 3 × its starting radius, below 1.5 × its top, no grain sunk more than
    its diameter into the soft floor)."""
    p = scene.handles["params"]
    parts = scene.world.particles
    pos, vel = parts.position, parts.velocity
    if not (np.isfinite(pos).all() and np.isfinite(vel).all()):
        raise AssertionError("non-finite particle state")
    r = np.hypot(pos[:, 0], pos[:, 2])
    far = float(np.mean(r > 3.0 * START_RADIUS))
    if far > 0.001 or pos[:, 1].max() > 1.5 * TOP or pos[:, 1].min() < -2.0 * RADIUS:
        raise AssertionError(f"the storm came apart: {far:.2%} beyond {3 * START_RADIUS} m, "
                             f"heights {pos[:, 1].min():.2f}..{pos[:, 1].max():.2f} m")
    # Tangential speed against the vortex's own at each particle's radius.
    tangential = (pos[:, 0] * vel[:, 2] - pos[:, 2] * vel[:, 0]) / np.maximum(r, 1e-9)
    wind = p.swirl * np.where(r < p.core, r / p.core, p.core / np.maximum(r, 1e-9)) \
        * np.minimum(1.0, 0.1 + pos[:, 1] / 3.0)
    ratio = float(tangential.sum() / wind.sum())
    if not 0.6 <= ratio <= 1.1:
        raise AssertionError(f"the dust turns at {ratio:.2f} × the wind's speed, expected "
                             "0.6-1.1")
