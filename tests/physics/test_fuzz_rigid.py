"""Rigid bodies and joints under any input (issue 30; issue 31's contacts that made energy).

Random rigid scenes from ``benchmarks/rigid_fuzz.py`` (boxes and spheres of 0.05–2 m and
1 g–10 t at up to 50 m/s, static bodies, ball and hinge joints, particles, walls; with and
without gravity), each run 300 steps at 1/60 s under a wall-clock watchdog: every step returns,
no speed passes 1e4 m/s without an error, a force-free scene never gains more than 1e-9 of its
kinetic energy in a step, few scenes end a step with bodies more than 2 cm inside each other,
and a rerun gives the same bits. A failure names its seed: ``rigid_fuzz.run(seed)`` replays it.

A quick profile by default; 1 000 scenes under ``slow``.
"""

from __future__ import annotations

import faulthandler
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pointmass as pm
from pointmass.rigid.joints import BallJoint, HingeJoint
from pointmass.rigid.shapes import Box, Sphere

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
import rigid_fuzz as fuzz

DT = 1.0 / 60.0
#: A step that has not returned after this long [s] is a hang: the watchdog dumps every
#: thread's stack and ends the process (a numba loop cannot be interrupted). Generous: a step
#: of these scenes takes ~2 ms of CPU, ~5 s of wall time at worst measured on a 2-core machine
#: shared at load 10; the hangs this catches never returned.
WATCHDOG = 120.0


#: Largest fraction of scenes that may end a step with an overlap > 2 cm: issue 30's 1 %, of
#: every run of scenes (the slow run's four parts of 250 each, so of its 1 000 too). Measured
#: with the soft step (``World()``'s body stage since stop 39) and a sphere's normal on a box
#: turning with the box (``body_soft.normals``, stop 40): seeds 1000–1999 at 120 steps, 4 of
#: 1 000 (5 before ``normals``); seeds 0–999 at 300 steps, 8 (13 before). With the turn's
#: sagitta no longer capped in a joint's aim (``joint_predict``, stop 41): 5 of 1 000 (1076,
#: 1341, 1465, 1650, 1941: at most 2 in a part, the bound), 7 in seeds 0–999. At stop 46,
#: with particles round in the soft step and two boxes' face normals turning with their
#: reference face: 5 (1076, 1138, 1341, 1465, 1941); seeds 0–999 and 2000–2999 at 300 steps,
#: 7 and 8 (10 and 10 before, in the same session). With the earlier
#: "impulses" stage it was 2 % of the joint-free and 15 % of the jointed scenes (bounds 0.07
#: and 0.25 then).
DEEP = 0.01


@pytest.fixture(scope="module", autouse=True)
def _compiled():
    fuzz.warm_up()  # compile every kernel before the watchdog times steps


def _scenes(seeds, steps: int) -> list[fuzz.Outcome]:
    outcomes = []
    for seed in seeds:
        o = fuzz.run(seed, steps, watchdog=WATCHDOG)
        assert o.explosion is None, (
            f"seed {seed}: a speed of {o.speed:.3g} m/s at step {o.explosion} without an error")
        assert o.gain is None, (
            f"seed {seed} (force-free): step {o.gain} gained {o.worst_gain:.3g} of the kinetic "
            "energy")
        if o.refused is not None:  # refused steps must leave a finite world (run() checks it)
            assert "UnstableStepError" in o.refused or "FloatingPointError" in o.refused
        outcomes.append(o)
    # Overlaps > 2 cm after a step: at most ``DEEP`` of the scenes, jointed or not
    deep = [(o.seed, o.joints) for o in outcomes if o.deep is not None]
    assert len(deep) <= DEEP * len(outcomes), (
        f"{len(deep)} of {len(outcomes)} scenes ended a step with an overlap > 2 cm (seed, "
        f"joints): {deep}")
    return outcomes


def _reruns_identical(seeds, steps: int) -> None:
    for seed in seeds:
        first = fuzz.run(seed, steps, watchdog=WATCHDOG)
        again = fuzz.run(seed, steps, watchdog=WATCHDOG)
        assert first.final == again.final, f"seed {seed}: a rerun gave different bits"


def test_random_rigid_scenes_quick():
    outcomes = _scenes(range(24), fuzz.STEPS)
    assert sum(o.joints > 0 for o in outcomes) >= 10  # the generator makes jointed scenes
    assert sum(o.force_free for o in outcomes) >= 6  # ... and force-free ones
    _reruns_identical(range(0, 24, 8), fuzz.STEPS)


#: The slow run's scenes and steps (see the test's docstring for the time they take).
SLOW_SCENES = 1000
SLOW_STEPS = 120


@pytest.mark.slow
@pytest.mark.parametrize("part", range(4))
def test_1000_random_rigid_scenes(part):
    """1 000 scenes of 120 steps (2 s) each in four parts (each under the suite's 600 s
    timeout on a loaded machine), every 50th run twice: ~210 s of CPU in all (measured: 0.5 s
    of CPU per 300-step scene); all 300 steps would take ~8.5 min."""
    seeds = range(1000 + part * SLOW_SCENES // 4, 1000 + (part + 1) * SLOW_SCENES // 4)
    _scenes(seeds, SLOW_STEPS)
    _reruns_identical(seeds[::50], SLOW_STEPS)


# -- the examples of issue 30 ------------------------------------------------------------------
def _watched_steps(world: pm.World, steps: int) -> list[float]:
    """Step ``world`` under the watchdog; the largest speed after each step [m/s]."""
    speeds = []
    for _ in range(steps):
        faulthandler.dump_traceback_later(WATCHDOG, exit=True)
        try:
            world.step(DT)
        finally:
            faulthandler.cancel_dump_traceback_later()
        speeds.append(fuzz.speed(world))
    return speeds


def test_a_body_held_by_two_joints_and_hit_hard_keeps_stepping():
    """Issue 30's hang: a 55 g box held by a ball joint and a hinge to two world points (its
    two joint points 16 cm apart, the anchors 105 cm apart and not on the hinge's axis: the
    joints cannot all hold), hit from below by a 2.3 kg box at 16 m/s. Before: the first step
    took 0.36 s and step 3 never returned (the joints spun the box up without bound, and the
    free rotation split its turn into h·|ω| pieces: 1e56 of them)."""
    world = pm.World()
    box = world.add_body(Box((0.1, 0.05, 0.08)), (0.0, 1.0, 0.0), mass=0.055)
    world.add(BallJoint(box, (0.08, 0.0, 0.0), None, (0.5, 1.5, 0.5)))
    world.add(HingeJoint(box, (-0.08, 0.0, 0.0), None, (-0.2, 0.6, 0.4), axis=(0.6, 0.0, 0.8)))
    world.add_body(Box((0.2, 0.1, 0.2)), (0.02, 0.5, 0.01), mass=2.3, velocity=(0.0, 16.0, 0.0))
    limit = world.kinetic_energy() + 2.355 * 9.81 * 20.0  # what the blow and a 20 m fall give
    for _ in range(120):
        _watched_steps(world, 1)
        assert world.kinetic_energy() < limit
    assert np.isfinite(world.bodies.position).all()


def test_a_force_free_jointed_scene_does_not_explode():
    """Issue 30's silent explosion, as the generator makes it: seed 677 is force-free, six
    bodies (a 2.3 t, a 3.4 g, a 24 kg, a 3.7 kg and a 1.8 kg one, one static), three joints
    to world points (a hinge and a ball joint on one body, a ball joint on another), four
    particles, a ground; 1.55e5 J. Before: 6.7e7 m/s at step 5, finite, no error. Now no step
    gains energy (issue 30's 1e-9) with ``World()``'s soft step (``solver/soft_energy.py``'s
    ``limit_islands``; before it, +2.1e-5 at step 2; measured now: at most +5.8e-16,
    rounding)."""
    world, force_free = fuzz.build(677)
    assert force_free and world.bodies.count == 6 and len(world.joints) == 3  # that scene
    assert world.kinetic_energy() == pytest.approx(1.5486e5, rel=1e-4)
    o = fuzz.run(677, 120, watchdog=WATCHDOG)
    assert o.refused is None and o.explosion is None
    assert o.gain is None
    assert o.speed < 100.0


# -- the soft step's jointed scenes (issue 26's blocker 1) ---------------------------------------
#: Jointed scenes that exploded with the soft step (``World()``'s, > 1e4 m/s, no error; seeds
#: 0–199, 300 steps), with the step they exploded in: most hold a light body by two joints to
#: one other body (a ball and a hinge, two hinges on different axes: over-constrained) at arms
#: of 4–9 m (the generator's joint point on B is where A's is), with mass ratios to 1e5.
#: What threw them (``solver/joint_soft.py``'s docstring): the warm start of the Gauss–Seidel
#: rows' impulses in a turned pose (the self-stress of an over-constrained set, which no pass
#: could take back within its cap), the tree solve's geometric stiffness (another metric than
#: the rows and contacts on the same bodies) and the aim at the end pose of a fast-turning
#: long arm (Newton's first step, unbounded).
SOFT_EXPLODED = {6: 68, 14: 81, 24: 20, 33: 15, 52: 8, 53: 3, 170: 16, 171: 19, 176: 9,
                 194: 3, 196: 1}


@pytest.mark.parametrize("seed", sorted(SOFT_EXPLODED))
def test_soft_step_jointed_scenes_that_exploded_hold(seed):
    """Every step returns, no speed passes 1e4 m/s and no step leaves a state that is not
    finite, through all 300 steps (measured: fastest 4.8e3 and 4.2e3 m/s, seeds 33 and 53:
    a 1.4 g and a 2 g box on over-constrained pairs; the others ≤ 540 m/s)."""
    o = fuzz.run(seed, fuzz.STEPS, watchdog=WATCHDOG)
    assert o.refused is None, o.refused
    assert o.explosion is None, f"seed {seed}: {o.speed:.3g} m/s at step {o.explosion}"
    assert o.steps == fuzz.STEPS


def test_soft_step_refuses_a_velocity_it_cannot_square_in_the_step():
    """A body whose velocity the step leaves too large to square (its energy is not a finite
    number) is refused by that step, naming it: before, a jointed scene (seed 196) left
    1e158 rad/s after its first step and only the next step's kick caught it."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    fast = world.add_body(Sphere(0.1), (0.0, 0.0, 0.0))
    held = world.add_body(Sphere(0.1), (3.0, 0.0, 0.0))
    world.add(BallJoint(held, (0.0, 0.0, 0.0), None, (3.0, 0.0, 0.0)))  # the jointed loop
    world.step(DT)
    # what a blow-up leaves (no kick or drift sees it: the spin and the position stay finite)
    world.bodies.velocity[fast] = (1e160, 0.0, 0.0)
    with pytest.raises(FloatingPointError, match="body 0 was left with a velocity"):
        world.step(DT)


#: The jointed scenes of seeds 0–199 with the soft step (143, 300 steps each; ~190 s of CPU).
#: Measured now (before the fixes of ``solver/joint_soft.py``'s warm start, tree metric and
#: aim: 11 explosions, 6 in 0–99 and 5 in 100–199): 0 explosions; of the 61 force-free ones,
#: 51 have a step gaining > 1e-9 of the kinetic energy and 17 > 1e-3 (issue 30's target: 0),
#: 40 end a step with an overlap > 2 cm. With the continuous stage (``body_continuous``,
#: joint groups moved back together) and the friction cone before the joints' solve: 47 and
#: 15 gain, 9 end a step deep. With the restitution's budget, the scenery limit and the
#: islands' limit with joints (``solver/soft_energy.py``): none gains (issue 30's target met),
#: 9 end a step deep (2 of them other seeds), the fastest 2.2e3 m/s (seed 53; 3.2e3 before).
#: With the islands' limit on every island that rows link (contacts too), the continuous
#: stage parting deep moving pairs and the tree's angular rows rigid through the tree
#: (``solver/joint_soft.py``, "Angular rows"): none gains (seed 88's 8.2e-9, in an island of
#: contacts alone, went with the contacts' cap), 7 end a step deep (24, 33, 53, 163, 180, 181,
#: 197). With the continuous stage parting pairs with a jointed body (each joint group moved
#: whole) and keeping a fast body already > SLOP in a wall from ending deeper
#: (``body_continuous`` items 4 and 6): none gains, 1 ends a step deep (163: 6.1 cm at step
#: 268); 24, 33, 53, 180, 181, 197 no longer. With a body the rows stopped at a wall left
#: there (``body_continuous._held``, Cyclone's R10; stop 38): 2 (163 and 176, whose trajectory
#: the gate changed; over seeds 1000–1999 at 120 steps it left the count at 5 of 1 000).
#: Since the leapfrog's start (stop 42: a body's first step opens with a half kick; a whole
#: one gives the trajectories of before, bit for bit, and 163 alone): 3, 163 and two of the
#: heavy-on-light class on other paths (56: a 10 kg box into a 0.15 kg sphere at step 45;
#: 176: a 1.3 kg sphere into a 2.3 t one at step 268).
#: The deep count is a ratchet; issue 30's target is ≤ 1 % of scenes.
SOFT_JOINTED_GAINS = (0, 0)
SOFT_JOINTED_DEEP = 3


@pytest.mark.slow
def test_soft_step_jointed_fuzz_counts():
    outcomes = []
    for seed in range(200):
        world, _ = fuzz.build(seed)
        if not len(world.joints):
            continue
        outcomes.append(fuzz.run(seed, fuzz.STEPS, watchdog=WATCHDOG))
    assert len(outcomes) == 143
    exploded = [o.seed for o in outcomes if o.explosion is not None]
    assert not exploded, exploded
    free = [o for o in outcomes if o.force_free]
    assert sum(o.gain is not None for o in free) <= SOFT_JOINTED_GAINS[0]
    assert sum(o.gain_1e3 is not None for o in free) <= SOFT_JOINTED_GAINS[1]
    assert sum(o.deep is not None for o in outcomes) <= SOFT_JOINTED_DEEP


# -- energy from contacts (issue 31, item 2) ----------------------------------------------------
def _three_spheres(e: float) -> pm.World:
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    for x in (-2.46, 2.46):
        world.add_body(Sphere(1.0), (x, 0.0, 0.0), mass=7061.0, restitution=e, friction=0.0)
    world.add_body(Sphere(0.77), (0.0, 0.0, 0.0), mass=0.0125,
                   velocity=(147.5, -20.9, -0.15), restitution=e, friction=0.0)
    return world


@pytest.mark.parametrize("e", [1.0, 0.5])
def test_a_light_sphere_between_heavy_ones_gains_no_energy(e):
    """Issue 31: a 12.5 g sphere between two 7 061 kg ones, frictionless, no gravity: one step
    took 139 J to 1.99e7 J (e = 0.5: ×13 000). Its bounce off the sphere ahead aimed at
    −e·vs while the one behind let it close only by its gap: the rows fought and pushed the
    heavy spheres apart. Now the step is redone the way that cannot gain (body_energy)."""
    world = _three_spheres(e)
    energy = world.kinetic_energy()
    for _ in range(60):
        before = world.kinetic_energy()
        world.step(DT)
        assert world.kinetic_energy() <= before * (1 + 1e-9)
    if e == 1.0:  # elastic: the bounces keep the energy (not merely no gain)
        assert world.kinetic_energy() > 0.99 * energy
    light = world.bodies.velocity[2]
    assert abs(light[0]) > 10.0  # it bounced off them and flew on (−20.9 m/s in y took it out)


@pytest.mark.parametrize(("e", "mu"), [(1.0, 1.0), (0.75, 0.5)])
def test_a_spinning_box_bouncing_on_the_ground_gains_no_energy(e, mu):
    """Issue 31: a spinning 1 kg box dropped onto a plane, e = 1, μ = 1: its total energy went
    152 J → 371 J in the first contact (e = 0.75, μ = 0.5: ×1.43). Friction changed the
    normal velocity of the points after their bounce targets were set. The orientation is
    (w, x, y, z), w first: it reproduces the 152 J → 371 J (x, y, z, w gives 186 J)."""
    world = pm.World()
    world.add(pm.Ground(0.0, restitution=e, friction=mu))
    world.add_body(Box((0.894, 0.781, 0.335)), (0.0, 1.284, 0.0),
                   (0.5495, 0.3706, -0.7415, 0.1041), mass=1.0, velocity=(-1.0, -5.8, 1.2),
                   angular_velocity=(14.2, 4.1, -27.2), restitution=e, friction=mu)
    start = world.kinetic_energy() + world.potential_energy()
    assert start == pytest.approx(152.44, abs=0.01)
    for _ in range(120):
        before = world.kinetic_energy() + world.potential_energy()
        world.step(DT)
        after = world.kinetic_energy() + world.potential_energy()
        assert after <= before + 1e-9 * start
    assert world.bodies.position[0, 1] > 0.0  # still above the ground


_SHAPE = st.sampled_from(["sphere", "box"])


@st.composite
def contact_scenes(draw):
    """Two or three bodies (spheres and boxes of 0.1–2 m, masses 1e-3–1e3 kg: ratios to 1e6)
    close together and closing, spinning, e and μ in [0, 1] each; sometimes a ground."""
    n = draw(st.integers(2, 3))
    bodies = []
    for i in range(n):
        size = draw(st.floats(0.05, 1.0))
        shape = Sphere(size) if draw(_SHAPE) == "sphere" else Box(
            (size, draw(st.floats(0.05, 1.0)), draw(st.floats(0.05, 1.0))))
        bodies.append(dict(
            shape=shape, x=1.6 * i + draw(st.floats(-0.3, 0.3)),
            yz=(draw(st.floats(-0.5, 0.5)), draw(st.floats(-0.5, 0.5))),
            q=[draw(st.floats(-1, 1)) for _ in range(4)],
            mass=10.0 ** draw(st.floats(-3, 3)),
            v=[draw(st.floats(-30, 30)) for _ in range(3)],
            w=[draw(st.floats(-20, 20)) for _ in range(3)],
            e=draw(st.floats(0, 1)), mu=draw(st.floats(0, 1))))
    ground = draw(st.booleans())
    return bodies, ground, draw(st.floats(0, 1)), draw(st.floats(0, 1))


def _contact_world(scene) -> pm.World:
    bodies, ground, ge, gmu = scene
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    if ground:
        world.add(pm.Ground(-1.5, restitution=ge, friction=gmu))
    centre = np.mean([b["x"] for b in bodies])
    for b in bodies:
        q = np.array(b["q"])
        q = q / np.linalg.norm(q) if np.linalg.norm(q) > 1e-3 else np.array([1.0, 0, 0, 0])
        v = np.array(b["v"])
        v[0] += 20.0 * np.sign(centre - b["x"])  # towards the others
        world.add_body(b["shape"], (b["x"], *b["yz"]), q, mass=b["mass"], velocity=v,
                       angular_velocity=b["w"], restitution=b["e"], friction=b["mu"])
    return world


def _no_step_gains(scene, steps: int = 40) -> None:
    world = _contact_world(scene)
    for n in range(steps):
        before = world.kinetic_energy()
        world.step(DT)
        after = world.kinetic_energy()
        assert math.isfinite(after)
        assert after <= before * (1.0 + 1e-9), (n, before, after)


@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(contact_scenes())
def test_random_contact_scenes_gain_no_energy(scene):
    _no_step_gains(scene)


@pytest.mark.slow
@settings(max_examples=1000, deadline=None, suppress_health_check=list(HealthCheck))
@given(contact_scenes())
def test_1000_random_contact_scenes_gain_no_energy(scene):
    _no_step_gains(scene)
