"""The soft step (``World()``'s body stage, ``solver/body_soft.py``) under issue 30's random
scenes and issue 26's drops: how many force-free scenes gain kinetic energy in a step and how
many end a step with a deep overlap (ratchets at the measured counts; issue 30's targets are 0
and 1 %), and that a bounce returns e² of the height it fell from.

The random scenes are benchmarks/rigid_fuzz.py's (boxes and spheres of 0.05–2 m and
1 g–10 t at up to 50 m/s, spins to 20 rad/s, friction and restitution in [0, 1], static
bodies, particles, walls), those without joints (joints: ``joint_soft``'s docstring). A
failure names its seed: ``rigid_fuzz.run(seed)`` replays it.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

import pointmass as pm
from pointmass.rigid.shapes import Box, Sphere

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "benchmarks"))
import rigid_fuzz as fuzz

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
    fuzz.run(_scenes(1, force_free=True)[0], steps=2)  # compile before anything times


def _gaining(seeds: list[int], steps: int) -> dict[int, float]:
    """The seeds whose scene had a step gaining > 1e-9 of its kinetic energy, with the largest
    gain of a step."""
    gaining = {}
    for seed in seeds:
        o = fuzz.run(seed, steps)
        assert o.force_free
        assert o.refused is None, f"seed {seed}: {o.refused}"
        assert o.explosion is None, f"seed {seed}: {o.speed:.3g} m/s at step {o.explosion}"
        if o.gain is not None:
            gaining[seed] = o.worst_gain
    return gaining


# Force-free joint-free scenes with a step gaining > 1e-9 of the kinetic energy: issue 30 asks
# for none. Measured: none of the first 100 such scenes (seeds 0–753, 40 steps) nor of the 37
# of seeds 0–299 at 300 steps. Before ``soft_energy.friction_cone``: 27 of 100 (3 > 1e-3, the
# worst step +2.9 %) and 15 of 37; with it, before ``soft_energy.limit_scenery``: 2 of 100
# (+1.2e-7) and 2 of 37 (+6.3e-4).


def test_force_free_random_scenes_gain_no_energy():
    gaining = _gaining(_scenes(100, force_free=True), steps=40)
    assert not gaining, gaining


@pytest.mark.slow
def test_force_free_random_scenes_gain_no_energy_300_steps():
    gaining = _gaining(_scenes(37, force_free=True), steps=fuzz.STEPS)  # seeds 0–299
    assert not gaining, gaining


def test_friction_warm_started_on_separating_points_gives_no_energy():
    # rigid_fuzz seed 38, step 10: a box (spinning, 47 m/s) leaves the ground the step after
    # it struck it; the warm start gives its points 8.4 × its kinetic energy, friction
    # included. The soft solve lets the normals go; the friction used to ride through the
    # drift and be taken off by the relax in the next pose: +2.9 % in that step. Clamped to
    # the solve's cone in the pose it was given in, no step of the scene gains.
    o = fuzz.run(38, 40)
    assert o.force_free and o.refused is None
    assert o.gain is None, f"step {o.gain} gained {o.worst_gain:.3g}"


def test_body_on_scenery_gains_no_energy_from_its_turning_inertia():
    # rigid_fuzz seed 297, step 275: a box on the walls alone, its contacts' arms fixed; the
    # soft solve's push-out, held through the drift, turned it and its inertia, and the relax
    # took the push back at I⁻¹ of the new pose: +6.3e-4 of the kinetic energy in the step
    # (``soft_energy.limit_scenery``). Now no step of the 300 gains.
    o = fuzz.run(297, fuzz.STEPS)
    assert o.force_free and o.refused is None
    assert o.gain is None, f"step {o.gain} gained {o.worst_gain:.3g}"


def test_limit_scenery_scales_only_bodies_alone_on_scenery_to_their_start_energy():
    import numpy as np

    from pointmass.solver import soft_energy

    # rows: body 0 on scenery; bodies 1 and 2 touch each other, 2 also scenery; 3 touches none
    alone = soft_energy.scenery_only(4, np.array([0, 1, 2]), np.array([-1, 2, -1]))
    assert alone.tolist() == [True, False, False, False]
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    for k in range(4):
        world.add_body(Box((0.6, 0.2, 0.4)), (3.0 * k, 0.0, 0.0), (0.9, 0.3, 0.2, 0.1),
                       mass=2.0, velocity=(1.0, 2.0, 3.0), angular_velocity=(3.0, -1.0, 2.0))
    b = world.bodies
    start = np.zeros(4)
    soft_energy.body_energies(np.ones(4, np.bool_), b.velocity, b.angular_velocity,
                              b.orientation, b.inv_mass, b.inv_inertia, start)
    assert start[0] == pytest.approx(soft_energy.kinetic_energy(b) / 4, rel=1e-14)
    b.velocity[:] *= 1.01
    b.angular_velocity[:] *= 1.01
    v, w = b.velocity.copy(), b.angular_velocity.copy()
    assert soft_energy.limit_scenery(alone, start, b.velocity, b.angular_velocity,
                                     b.orientation, b.inv_mass, b.inv_inertia) == 1
    after = np.zeros(4)
    soft_energy.body_energies(np.ones(4, np.bool_), b.velocity, b.angular_velocity,
                              b.orientation, b.inv_mass, b.inv_inertia, after)
    assert after[0] == pytest.approx(start[0], rel=1e-14)
    assert np.allclose(b.velocity[0], v[0] / 1.01) and np.allclose(b.angular_velocity[0],
                                                                     w[0] / 1.01)
    assert np.array_equal(b.velocity[1:], v[1:]) and np.array_equal(b.angular_velocity[1:],
                                                                    w[1:])


def test_limit_islands_caps_a_free_contact_island_keeping_both_momenta():
    import numpy as np

    from pointmass.solver import soft_energy

    # rows: bodies 0 and 1 touch each other (a free island); 2 and 3 touch each other and 3
    # the ground (a grounded one); 4 is on the ground alone (``limit_scenery``'s); 5 in none
    ca, cb = np.array([0, 2, 3, 4]), np.array([1, 3, -1, -1])
    alone = soft_energy.scenery_only(6, ca, cb)
    label = np.empty(6, np.int64)
    grounded = np.empty(6, np.bool_)
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    for k in range(6):
        world.add_body(Box((0.6, 0.2, 0.4)), (3.0 * k, 0.5 * k, 0.0), (0.9, 0.3, 0.2, 0.1),
                       mass=2.0 + k, velocity=(1.0, 2.0 - k, 3.0),
                       angular_velocity=(3.0, -1.0, 2.0 * k))
    b = world.bodies
    count = soft_energy.islands(6, np.empty(0, np.int64), np.empty(0, np.int64), ca, cb,
                                b.inv_mass, alone, label, grounded)
    assert count == 2 and label.tolist() == [0, 0, 1, 1, -1, -1]
    assert grounded[:2].tolist() == [False, True]
    start = np.zeros(2)
    soft_energy.island_energies(label, b.velocity, b.angular_velocity, b.orientation,
                                b.inv_mass, b.inv_inertia, start)

    def momenta():
        m = 1.0 / b.inv_mass[:2, None]
        spin = [np.linalg.solve(b.inv_inertia_world[i], b.angular_velocity[i])
                for i in range(2)]
        return (m * b.velocity[:2]).sum(axis=0), (np.cross(b.position[:2], m * b.velocity[:2])
                                                  + spin).sum(axis=0)

    p0, l0 = momenta()
    # what a substep's rows might leave: more energy in both islands, the same momenta in the
    # free one (equal and opposite impulses at one point)
    push = np.array([0.7, -0.3, 0.2])
    arm = np.array([1.5, 0.25, 0.1])
    for i, sign in ((0, 1.0), (1, -1.0)):
        b.velocity[i] += sign * push * b.inv_mass[i]
        b.angular_velocity[i] += sign * b.inv_inertia_world[i] @ np.cross(
            arm - (b.position[i] - b.position[0]), push)
    b.velocity[2:4] *= 1.02
    b.angular_velocity[2:4] *= 1.02
    v, w = b.velocity.copy(), b.angular_velocity.copy()
    p1, l1 = momenta()
    assert np.allclose(p1, p0, rtol=0, atol=1e-12) and np.allclose(l1, l0, rtol=0, atol=1e-12)
    after = np.zeros(2)
    soft_energy.island_energies(label, b.velocity, b.angular_velocity, b.orientation,
                                b.inv_mass, b.inv_inertia, after)
    assert (after > start * (1 + 1e-6)).all()
    assert soft_energy.limit_islands(label, grounded[:2], start, b.position, b.velocity,
                                     b.angular_velocity, b.orientation, b.inv_mass,
                                     b.inv_inertia) == 2
    soft_energy.island_energies(label, b.velocity, b.angular_velocity, b.orientation,
                                b.inv_mass, b.inv_inertia, after)
    assert after == pytest.approx(start, rel=1e-13)
    p2, l2 = momenta()  # the free island keeps both momenta (its rigid motion is kept)
    assert np.abs(p2 - p0).max() <= 1e-12 * np.abs(p0).max()
    assert np.abs(l2 - l0).max() <= 1e-12 * np.abs(l0).max()
    # the grounded island is scaled whole; the bodies of no island are left
    assert np.allclose(b.velocity[2:4], v[2:4] / 1.02, rtol=1e-13)
    assert np.array_equal(b.velocity[4:], v[4:]) and np.array_equal(b.angular_velocity[4:],
                                                                    w[4:])


def test_a_pair_parted_by_the_continuous_stage_then_gains_no_energy_in_its_contact():
    # rigid_fuzz seed 380 (force-free, no joints: three boxes, a sphere, two static spheres,
    # three particles): with the continuous stage parting deep moving pairs, step 24 gained
    # 4.2e-7 in the soft solve of two boxes' contact, an island no joint holds, which
    # ``limit_islands`` did not cap; now it caps every island that rows link (measured
    # 3.3e-15 at worst over 300 steps)
    o = fuzz.run(380, 40)
    assert o.force_free and o.joints == 0 and o.refused is None
    assert o.gain is None, f"step {o.gain} gained {o.worst_gain:.3g}"


#: Largest fraction of joint-free scenes (with and without gravity) that may end a step with
#: an overlap > 2 cm. Issue 30 asks for 1 %; measured with the soft step on these 40 scenes
#: (seeds 0–140, 60 steps): 0, since the continuous stage parts pairs of moving bodies that a
#: step left deep (``body_continuous``; before: 2, seeds 79 and 140; before the stage itself,
#: 37 of 91 over seeds 0–299).
SOFT_DEEP = 0.0


def test_overlaps_of_random_scenes_stay_bounded():
    seeds = _scenes(40)
    deep = []
    for seed in seeds:
        o = fuzz.run(seed, 60)
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
    apex, contact = drop(shape, height)
    assert contact == pytest.approx(0.25, rel=0.03)
    assert apex == pytest.approx(0.25, rel=0.04)


def test_friction_cone_takes_back_unsupported_friction_exactly():
    # Two tilted boxes, one resting on the other with gravity off, their inertia not a
    # sphere's: a warm start of friction and twist with no normal impulse under it, then the
    # cone (μ·Σλ = 0) takes all of it back in the same pose: velocities, both momenta and
    # the kinetic energy as before the warm start, to round-off.
    import numpy as np

    from pointmass.solver import body_soft as bs
    from pointmass.solver import soft_energy

    world = pm.World(gravity=(0.0, 0.0, 0.0))
    q = (0.99, 0.1, 0.05, 0.02)
    world.add_body(Box((0.6, 0.2, 0.4)), (0.0, 0.0, 0.0), q, mass=2.0, friction=0.7)
    world.add_body(Box((0.3, 0.25, 0.5)), (0.1, 0.43, 0.05), q, mass=3.0, friction=0.7,
                   velocity=(0.3, -0.1, 0.2), angular_velocity=(1.0, -2.0, 0.5))
    world.step(DT)
    b = world.bodies
    c = world.body_contacts
    assert c.count >= 3
    r = bs._Rows(c)
    bs._refresh(b, c, r)
    r.impulse[:] = 0.0
    r.jt1[:], r.jt2[:], r.jtw[:] = 5.0, -3.0, 0.7
    v0, w0 = b.velocity.copy(), b.angular_velocity.copy()
    energy = soft_energy.kinetic_energy(b)
    bs.warm_start(r.start, c.a, c.b, c.normal, r.t1, r.t2, b.inv_mass, b.velocity,
                  b.angular_velocity, r.impulse, r.jt1, r.jt2, r.jtw, r.arm, r.farm)
    assert np.abs(b.velocity - v0).max() > 1.0  # the warm start did move them
    clamped = soft_energy.friction_cone(r.start, c.a, c.b, c.normal, r.t1, r.t2, r.fmu,
                                        r.radius, r.mass_n, b.inv_mass, b.velocity,
                                        b.angular_velocity, r.impulse, r.jt1, r.jt2, r.jtw,
                                        r.farm)
    assert clamped == len(r.jt1)
    assert not (r.jt1.any() or r.jt2.any() or r.jtw.any())
    assert np.allclose(b.velocity, v0, rtol=0.0, atol=1e-13)
    assert np.allclose(b.angular_velocity, w0, rtol=0.0, atol=1e-13)
    assert soft_energy.kinetic_energy(b) == pytest.approx(energy, rel=1e-13)


def test_friction_cone_leaves_friction_inside_it():
    # A box resting on the ground under gravity: its friction is within μ·Σλ, so the cone
    # changes nothing (the towers' and the pyramid's friction is left to the relax).
    import numpy as np

    from pointmass.solver import body_soft as bs
    from pointmass.solver import soft_energy

    world = pm.World(gravity=(0.0, -G, 0.0))
    world.add(pm.Ground(friction=0.5))
    world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.5, 0.0), mass=1.0, friction=0.5)
    world.step(DT)
    b = world.bodies
    c = world.body_contacts
    r = bs._Rows(c)
    bs._refresh(b, c, r)
    r.impulse[:] = 1.0
    r.jt1[:], r.jt2[:], r.jtw[:] = 1.0, -1.0, 0.1  # |jt| 1.41 within μ·Σλ = 2
    v0, w0 = b.velocity.copy(), b.angular_velocity.copy()
    clamped = soft_energy.friction_cone(r.start, c.a, c.b, c.normal, r.t1, r.t2, r.fmu,
                                        r.radius, r.mass_n, b.inv_mass, b.velocity,
                                        b.angular_velocity, r.impulse, r.jt1, r.jt2, r.jtw,
                                        r.farm)
    assert clamped == 0
    assert (r.jt1 == 1.0).all() and (r.jt2 == -1.0).all() and (r.jtw == 0.1).all()
    assert np.array_equal(b.velocity, v0) and np.array_equal(b.angular_velocity, w0)
