"""The soft step's continuous collision (``solver/body_continuous.py``): a fast body is put back
where its step first brings it within the slop of a static body or a plane, with its
velocities kept; and, with it, how many of issue 30's random scenes end a step deep in
something (the thin wall, issue 26 point 7, is in test_thin_wall.py).

The stage is checked against the geometry of the sweep: a box translating at a wall stops with
its face ``SLOP`` from it (the advancement's tolerance apart), a spinning box stops where its
corner would pass the slop, and a body that only slides or rests is left where it is."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.contacts import BodyContacts
from pointmass.rigid.quaternion import quat_from_axis_angle
from pointmass.rigid.shapes import SPHERE, Box, Sphere
from pointmass.solver.body_continuous import sweep_back

sys.path.insert(0, str(Path(__file__).resolve().parents[3] / "benchmarks"))
import rigid_fuzz as fuzz

#: The continuous stage's slop (``SolverSettings.continuous_slop``) and its advancement's
#: tolerance (a quarter of it, ``b2TimeOfImpact``'s)
SLOP = pm.SolverSettings().continuous_slop
TOLERANCE = 0.25 * SLOP
DT = 1.0 / 60.0


def _world(shape, at, velocity=(0.0, 0.0, 0.0), spin=(0.0, 0.0, 0.0),
           orientation=(1.0, 0.0, 0.0, 0.0)):
    """A 0.1 m body at ``at`` by a ground plane y = 0, no gravity, the soft step."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    ground = pm.Ground(0.0)
    world.add(ground)
    body = world.add_body(shape, at, orientation, mass=1.0, velocity=velocity,
                          angular_velocity=spin)
    return world, ground, body


def _sweep(world, ground, x_start, q_start):
    return sweep_back(world.bodies, [ground], None, x_start, q_start, DT)


def test_a_box_that_ends_through_the_ground_stops_at_the_slop_with_its_velocity():
    # a 0.1 m box falling at 60 m/s (1 m a step), put where its straight step would end
    world, ground, body = _world(Box((0.05, 0.05, 0.05)), (0.3, 0.5, 0.0),
                                 velocity=(3.0, -60.0, 0.0))
    b = world.bodies
    x0, q0 = b.position.copy(), b.orientation.copy()
    b.position[0] += b.velocity[0] * DT
    velocity, spin = b.velocity.copy(), b.angular_velocity.copy()
    assert _sweep(world, ground, x0, q0) == 1
    # the lowest face SLOP above the ground, on the straight line of the step
    gap = body.position[1] - 0.05
    assert SLOP - 1e-12 <= gap <= SLOP + TOLERANCE
    t = (0.5 - body.position[1]) / (60.0 * DT)
    assert body.position[0] == pytest.approx(0.3 + 3.0 * DT * t, rel=1e-12)
    # positions only: the momentum and spin the solve gave are kept
    assert b.velocity.tolist() == velocity.tolist()
    assert b.angular_velocity.tolist() == spin.tolist()


def test_a_box_spinning_into_the_ground_stops_before_its_corner_passes_the_slop():
    # resting face down on the ground, turned by 0.9 rad about z in one step: a corner digs
    # 0.05·(√2·sin(0.9 + π/4) − 1) ≈ 2.1 cm below the ground at the step's end
    world, ground, _ = _world(Box((0.05, 0.05, 0.05)), (0.0, 0.05, 0.0),
                                 spin=(0.0, 0.0, 0.9 / DT))
    b = world.bodies
    x0, q0 = b.position.copy(), b.orientation.copy()
    b.orientation[0] = quat_from_axis_angle(np.array([0.0, 0.0, 1.0]), 0.9)
    assert _sweep(world, ground, x0, q0) == 1
    # the turn it stopped at: its lowest corner SLOP below where it started (at the ground)
    angle = 2.0 * math.atan2(np.linalg.norm(b.orientation[0, 1:]), b.orientation[0, 0])
    depth = 0.05 * (math.sqrt(2.0) * math.sin(angle + math.pi / 4.0) - 1.0)
    assert SLOP - TOLERANCE <= depth <= SLOP
    assert 0.0 < angle < 0.9
    assert b.position[0].tolist() == [0.0, 0.05, 0.0]  # it did not move: only turned
    assert b.angular_velocity[0] == pytest.approx([0.0, 0.0, 0.9 / DT], abs=1e-9)


def test_a_body_turned_back_keeps_its_spin_in_its_own_frame_and_its_energy():
    # a flat box spinning about a tilted axis, its step ending through the ground: turned
    # back, its kinetic energy ½ω·Iω (I not isotropic) and |I·ω| are unchanged
    world, ground, _ = _world(Box((0.2, 0.05, 0.1)), (0.0, 0.3, 0.0),
                              velocity=(1.0, -30.0, 0.0), spin=(20.0, 35.0, -10.0))
    b = world.bodies
    x0, q0 = b.position.copy(), b.orientation.copy()
    b.position[0] += b.velocity[0] * DT
    b.orientation[0] = quat_from_axis_angle(np.array([0.3, 0.8, -0.2]) / np.linalg.norm(
        [0.3, 0.8, -0.2]), 0.7)
    b.update_world_inertia()
    energy = world.kinetic_energy()
    spin = np.linalg.norm(np.linalg.solve(b.inv_inertia_world[0], b.angular_velocity[0]))
    assert _sweep(world, ground, x0, q0) == 1
    assert world.kinetic_energy() == pytest.approx(energy, rel=1e-12)
    after = np.linalg.norm(np.linalg.solve(b.inv_inertia_world[0], b.angular_velocity[0]))
    assert after == pytest.approx(spin, rel=1e-12)


@pytest.mark.parametrize("shape", [Box((0.05, 0.05, 0.05)), Sphere(0.05)])
def test_a_body_sliding_fast_on_the_ground_is_left_alone(shape):
    # 30 m/s along the ground (0.5 m a step, 10 half-extents), touching it 0.1 mm deep
    world, ground, _ = _world(shape, (0.0, 0.0499, 0.0), velocity=(30.0, 0.0, 0.0))
    b = world.bodies
    x0, q0 = b.position.copy(), b.orientation.copy()
    b.position[0, 0] += 30.0 * DT
    end = b.position.copy()
    assert _sweep(world, ground, x0, q0) == 0
    assert b.position.tolist() == end.tolist()


def test_a_fast_box_stops_at_a_static_box_wall_it_would_pass():
    # a 0.1 m box at 500 m/s (8.3 m a step) through a 5 cm static wall centred at x = 0
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.add_body(Box((0.025, 1.0, 1.0)), (0.0, 0.0, 0.0), mass=math.inf)
    turned = quat_from_axis_angle(np.array([0.0, 1.0, 0.0]), 0.4)
    body = world.add_body(Box((0.05, 0.05, 0.05)), (-1.0, 0.0, 0.0), turned, mass=1.0,
                          velocity=(500.0, 0.0, 0.0))
    b = world.bodies
    x0, q0 = b.position.copy(), b.orientation.copy()
    b.position[1, 0] += 500.0 * DT
    assert sweep_back(b, [], None, x0, q0, DT) == 1
    # the turned box's leading edge, 0.05·(cos 0.4 + sin 0.4) ahead of its centre, SLOP (the
    # face-axis gap, exact here) short of the wall's face
    lead = 0.05 * (math.cos(0.4) + math.sin(0.4))
    gap = -0.025 - (body.position[0] + lead)
    assert SLOP - 1e-12 <= gap <= SLOP + TOLERANCE


def _fast_boxes():
    """0.1 m boxes at ±60 m/s (12 of their half-extents a step), off centre, one spinning, no
    gravity, e 0, μ 0.5 (issue 26 point 8 with fast bodies)."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.add_body(Box((0.05, 0.05, 0.05)), (-1.0, 0.02, 0.0), mass=1.0,
                   velocity=(60.0, 0.0, 0.0))
    world.add_body(Box((0.05, 0.05, 0.05)), (1.0, -0.02, 0.01), mass=2.0,
                   velocity=(-60.0, 0.0, 0.0), angular_velocity=(5.0, 0.0, 0.0))
    return world


def _momenta(world):
    b = world.bodies
    m = 1.0 / b.inv_mass[:, None]
    p = (m * b.velocity).sum(axis=0)
    spin = [np.linalg.solve(b.inv_inertia_world[i], b.angular_velocity[i])
            for i in range(b.count)]
    return p, (np.cross(b.position, m * b.velocity) + spin).sum(axis=0)


def test_two_fast_moving_boxes_collide_rather_than_pass_through_each_other():
    # before the stage rewound moving pairs, the rows let these end their first step 6 mm
    # deep and still closing at 47 m/s, and the next step the boxes passed through each other
    # untouched (on at +8.3 and −34.1 m/s): rewound to SLOP apart, they collide (e 0: the
    # light box is carried back, both near the common velocity −20 m/s; measured −18.2 and
    # −20.9, the boxes glancing off each other's edges)
    world = _fast_boxes()
    p0, _ = _momenta(world)
    for _ in range(30):
        world.step(DT)
        assert fuzz.overlap(world, fuzz.BodyContacts()) < SLOP
    b = world.bodies
    assert b.velocity[:, 0] == pytest.approx([-20.0, -20.0], abs=3.0)
    p1, _ = _momenta(world)
    assert np.abs(p1 - p0).max() <= 1e-9 * np.abs(p0).max() + 1e-12


@pytest.mark.xfail(strict=True, reason=(
    "the kick's spin cap (rigid/step.py's MAX_ROTATION, Box2D's maxRotation: π/4 a substep, "
    "188 rad/s at h = 1/240) slows the light box, which the off-centre hit spins to 249 "
    "rad/s: |L| 3.79 -> 3.00 (-21 %) in steps 2-3; measured stage by stage, every contact "
    "stage, the island cap and the rewind keep L to 1e-15. Before the rewind the boxes "
    "passed through each other untouched, which kept it trivially."))
def test_two_fast_moving_boxes_keep_their_angular_momentum_through_the_collision():
    world = _fast_boxes()
    _, l0 = _momenta(world)
    for _ in range(30):
        world.step(DT)
    _, l1 = _momenta(world)
    assert np.abs(l1 - l0).max() <= 1e-9 * np.linalg.norm(l0) + 1e-12


def _moving_pair(end_b):
    """Two 0.1 m boxes, no gravity: A from x = −0.5 at 60 m/s (1 m a step), B from 0.5 at
    −3 m/s, put where a step that let A through its rows would leave them (A at 0.5, B at
    ``end_b``)."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.add_body(Box((0.05, 0.05, 0.05)), (-0.5, 0.0, 0.0), mass=1.0,
                   velocity=(60.0, 0.0, 0.0))
    world.add_body(Box((0.05, 0.05, 0.05)), (0.5, 0.0, 0.0), mass=2.0,
                   velocity=(-3.0, 0.0, 0.0), angular_velocity=(0.0, 0.0, 1.0))
    b = world.bodies
    x0, q0 = b.position.copy(), b.orientation.copy()
    b.position[0, 0] = 0.5
    b.position[1, 0] = end_b
    return world, x0, q0


def test_a_pair_of_moving_bodies_that_ends_deep_is_rewound_about_its_centre_of_mass():
    # A's step ends 5 cm past B's centre, the pair still moving on at 63 m/s: their relative
    # motion is rewound along it, each by its inverse-mass share (A 2/3, B 1/3), to where
    # the gap is SLOP; velocities and orientations kept, so momentum, angular momentum and
    # energy are the solve's
    world, x0, q0 = _moving_pair(0.45)
    b = world.bodies
    velocity, spin = b.velocity.copy(), b.angular_velocity.copy()

    def momenta():
        m = 1.0 / b.inv_mass[:, None]
        spins = [np.linalg.solve(b.inv_inertia_world[k], b.angular_velocity[k])
                 for k in range(b.count)]
        return (m * b.velocity).sum(axis=0), (np.cross(b.position, m * b.velocity)
                                             + spins).sum(axis=0)

    p0, l0 = momenta()
    energy = world.kinetic_energy()
    assert sweep_back(b, [], None, x0, q0, DT) == 2
    gap = b.position[1, 0] - b.position[0, 0] - 0.1
    assert SLOP - 1e-12 <= gap <= SLOP + TOLERANCE
    assert 1.0 * b.position[0, 0] + 2.0 * b.position[1, 0] == pytest.approx(1.4, abs=1e-12)
    assert b.position[:, 1:].tolist() == x0[:, 1:].tolist()  # along the relative velocity
    assert b.velocity.tolist() == velocity.tolist()
    assert b.angular_velocity.tolist() == spin.tolist()
    p1, l1 = momenta()
    assert np.abs(p1 - p0).max() == 0.0
    assert np.abs(l1 - l0).max() <= 1e-14 * np.linalg.norm(l0)
    assert world.kinetic_energy() == energy


def test_a_pair_of_moving_bodies_that_ends_touching_is_left_to_its_rows():
    # the same step ending with the faces touching (as a bounce the rows caught): unchanged
    world, x0, q0 = _moving_pair(0.6)
    b = world.bodies
    end = b.position.copy()
    assert sweep_back(b, [], None, x0, q0, DT) == 0
    assert b.position.tolist() == end.tolist()


def test_the_random_scene_of_a_small_sphere_sliding_round_a_large_one_stays_out():
    """rigid_fuzz seed 140 (gravity, six walls, five spheres of 4 cm–0.95 m at 7–50 m/s):
    a 4.3 cm, 30 kg sphere sliding at 10 m/s round a 0.79 m, 4.75 kg one that is moving too.
    The step's row keeps the normal of its start, a tangent plane the small sphere slides
    along, 0.17 m a step, into the curved surface (≈ L²/2R = 1.7 cm a step): before the
    stage swept moving pairs it ended step 20 4.1 cm inside, 3.8 cm after step 21."""
    o = fuzz.run(140, 40)
    assert o.refused is None
    assert o.deepest < fuzz.DEEP, f"{o.deepest:.4f} m inside at step {o.deep}"


# --- issue 30: random scenes that end a step deep in something --------------------------------

def _joint_free(first: int, last: int) -> list[int]:
    return [s for s in range(first, last) if not len(fuzz.build(s)[0].joints)]


def _deep(seeds: list[int], steps: int) -> list[int]:
    deep = []
    for seed in seeds:
        o = fuzz.run(seed, steps)
        assert o.refused is None, f"seed {seed}: {o.refused}"
        if o.deep is not None:
            deep.append(seed)
    return deep


#: Joint-free scenes where, before this stage, a fast body ended a step > 2 cm inside a wall
#: or the ground within 20 steps (seed: that step): boxes of 2.5–35 cm at 1.4–26 of their
#: half-extents a step, spinning up to 190 rad/s.
EARLY_DEEP = {31: 7, 54: 15, 71: 15, 79: 9, 103: 5, 128: 1, 189: 12, 211: 16, 216: 15,
              223: 14, 243: 18, 265: 3, 278: 12, 297: 10}


def test_random_scenes_that_went_deep_in_a_wall_do_not():
    deep = _deep(sorted(EARLY_DEEP), 20)
    assert deep == [], deep


#: Joint-free scenes of seeds 0–299 (91 scenes, issue 30's count), 300 steps, with a step
#: ending > 2 cm deep. Target ≤ 1 %. Measured: none, with ``soft_energy.limit_islands`` on
#: contact islands too (before it, 1 of 91: seed 79, from step 210 a 7.8 t sphere pressing a
#: 10 kg box into the ground, 2.5–7.6 cm, a mass ratio of 770 that the rows' passes do not
#: carry; with the cap its deepest is 1.96 cm, just inside the bound: the class is not fixed).
#: Before the stage parted moving pairs: 5 (seeds 79, 128, 140, 217, 265), each a pair of
#: moving bodies; before the stage itself 28, 27 of them a fast body in a wall or the ground
#: (the default stage: 4). With a body the rows stopped at a wall left there (``_held``,
#: Cyclone's R10; stop 38): 1 (seed 217, a 4 g box 1.9 m across under a 119 kg sphere spinning
#: at 85 rad/s, a pair of moving bodies: the gate changed its trajectory). Over seeds
#: 1000–1999 at 120 steps the gate left the count as it was: 5 of 1 000 deep with it and
#: without (1263, 1420, 1650, 1781, 1941 against 1263, 1650, 1767, 1781, 1810).
SLOW_DEEP = 1


@pytest.mark.slow
def test_random_scenes_deep_overlaps_ratchet_300_steps():
    deep = _deep(_joint_free(0, 300), fuzz.STEPS)
    assert len(deep) <= SLOW_DEEP, deep


def test_bodies_held_by_a_joint_go_back_together():
    # two 0.1 m boxes ball-jointed edge to edge, falling at 60 m/s in a straight line, one
    # lower than the other: only the lower one reaches the ground this step; both go back to
    # its time of impact, so the joint is where it was (moved back alone, the lower box left
    # its neighbour 0.55 m out of place: the ragdoll demo's bones opened 14–46 mm)
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    ground = pm.Ground(0.0)
    world.add(ground)
    low = world.add_body(Box((0.05, 0.05, 0.05)), (0.0, 0.5, 0.0), mass=1.0,
                         velocity=(0.0, -60.0, 0.0))
    high = world.add_body(Box((0.05, 0.05, 0.05)), (0.1, 1.2, 0.0), mass=1.0,
                          velocity=(0.0, -60.0, 0.0))
    from pointmass.rigid.joints import BallJoint
    world.add(BallJoint(high, (-0.05, -0.5, 0.0), low, None))  # met at (0.05, 0.7, 0)
    b = world.bodies
    x0, q0 = b.position.copy(), b.orientation.copy()
    b.position[:] += b.velocity * DT  # the step as the solve left it: 1 m down, rigidly
    exclude = world.joints.pair_keys(b.count)
    assert sweep_back(b, [ground], exclude, x0, q0, DT) == 2
    gap = low.position[1] - 0.05
    assert SLOP - 1e-12 <= gap <= SLOP + TOLERANCE
    # the same fraction of the step for both: the pair keeps its shape (0.1, 0.7, 0)
    assert (b.position[1] - b.position[0]).tolist() == pytest.approx([0.1, 0.7, 0.0],
                                                                       abs=1e-12)
    assert world.joints.separations().max() < 1e-12
    # without the joint, only the low box goes back
    b.position[:] = x0 + b.velocity * DT
    assert sweep_back(b, [ground], None, x0, q0, DT) == 1
    assert b.position[1].tolist() == pytest.approx((x0[1] + b.velocity[1] * DT).tolist())


@pytest.mark.parametrize("shape", [Sphere(0.05), Box((0.05, 0.05, 0.05))],
                         ids=["sphere", "box"])
def test_a_body_the_rows_stop_at_a_wall_is_left_touching_it(shape):
    """Cyclone's R10 scene with the soft step: a 0.1 m body at 300 m/s (5 m a step), no
    gravity, meets a 0.1 m static wall. The speculative row stops it at the face in its
    first step; the continuous stage saw a fast body whose sweep met the wall and moved it
    back to its time of impact, ``SLOP`` short of the face, where it stayed (at rest, 5 mm in
    the air: −0.105 m). A body the rows held at the surface is left there
    (``body_continuous._held``)."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.add_body(Box((0.05, 2.0, 2.0)), mass=math.inf)
    body = world.add_body(shape, (-3.0, 0.0, 0.0), velocity=(300.0, 0.0, 0.0), mass=0.1)
    for _ in range(60):
        world.step(1 / 60)
    assert body.position[0] == pytest.approx(-0.1, abs=1e-6)
    assert np.abs(body.velocity).max() < 1e-9


def _subscene(seed: int, keep: list[int]) -> pm.World:
    """The bodies ``keep`` of fuzz scene ``seed`` (their state, masses and materials), its
    planes, gravity and the joints among them, with the soft step."""
    full, _ = fuzz.build(seed)
    b = full.bodies
    world = pm.World(gravity=tuple(full.gravity.tolist()))
    for g in full.contact_generators:
        if isinstance(g, pm.Plane):
            world.add(pm.Plane(g.normal, g.offset, friction=g.friction,
                               restitution=g.restitution))
    index = {}
    for k in keep:
        shape = Sphere(float(b.size[k, 0])) if b.shape[k] == SPHERE \
            else Box(tuple(b.size[k].tolist()))
        index[k] = world.add_body(shape, b.position[k], b.orientation[k],
                                  velocity=b.velocity[k], angular_velocity=b.angular_velocity[k],
                                  mass=1.0 / b.inv_mass[k], friction=float(b.friction[k]),
                                  restitution=float(b.restitution[k]))
    for j in full.joints.items:
        if j.a in index and (j.b < 0 or j.b in index):
            other = None if j.b < 0 else index[j.b]
            world.add(type(j)(index[j.a], j.local_a, other, j.local_b if j.b < 0 else None,
                              axis=j.axis))
    return world


def test_a_free_box_driven_into_a_jointed_box_is_parted_and_its_joint_kept():
    # fuzz seed 1121 (force-free): a 25 g box at 48 m/s into a 10.5 kg box ball-jointed to a
    # 389 kg sphere. The pair stage skipped pairs with a jointed body: from step 5 the small
    # box ended 2.6–14.4 cm inside the big one (stop 37). Now the box and the jointed group
    # each go back along their sweeps to the pair's impact: none ends a step deep. Poses
    # only: no step gains kinetic energy, and the joint stays as shut as the solve leaves it.
    world = _subscene(1121, [1, 3, 5])
    contacts = BodyContacts()
    energy = world.kinetic_energy()
    deepest = gap = 0.0
    for _ in range(20):
        world.step(DT)
        deepest = max(deepest, fuzz.overlap(world, contacts))
        gap = max(gap, float(world.joints.separations().max()))
        now = world.kinetic_energy()
        assert now <= energy * (1.0 + 1e-9)
        energy = now
    assert deepest < 2.0 * SLOP  # measured 0 (before: 0.144 m)
    # measured 1.99 mm, the solve's in the first step (as before), < 10 µm from step 5; the
    # group swept back along its bodies' sweeps opened it by 2.5 cm
    assert gap < 5e-3


def test_a_light_plank_hinged_to_a_heavy_box_does_not_creep_into_a_wall():
    # fuzz seed 1264: a 2.8 g plank (0.87 × 0.05 × 0.16 m half-extents) hinged to an 805 kg
    # box on a 4 m arm, in a room. The box's turn presses the plank's end into a wall; the
    # contact's rows, with the plank's own mass, do not carry the box, and the plank, thrashed
    # fast by the rows, was let by the continuous stage end each step SLOP deeper than it
    # began: from step 5 it crept in 4 mm a step, to 9.3 cm. Now a fast body already deeper
    # than SLOP in a static body or plane ends no deeper: measured 7.2 mm at most in 120 steps.
    world = _subscene(1264, [3, 4])
    contacts = BodyContacts()
    deepest = 0.0
    for _ in range(120):
        world.step(DT)
        deepest = max(deepest, fuzz.overlap(world, contacts))
    assert deepest <= 2.0 * SLOP


def test_a_pair_rewound_into_the_ground_goes_back_along_its_sweeps_instead():
    """A 1 kg ball the ground bounced up (20 m/s) under a 1 t ball falling on it (5 m/s): the
    step ends with them 15 cm inside each other, the light ball 5 cm above the ground.
    Rewinding their relative motion (along their relative velocity, up) moves the light ball
    down, 10.5 cm into the ground (fuzz seed 278: a 74 kg box under a 1630 kg sphere, left
    2.7 cm in the ground); so both go back along their own sweeps to where they are ``SLOP``
    apart, each on a pose it passed through, above the ground."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    ground = pm.Ground(0.0)
    world.add(ground)
    world.add_body(Sphere(0.1), (0.0, 0.15, 0.0), mass=1.0, velocity=(0.0, 20.0, 0.0))
    world.add_body(Sphere(0.5), (0.0, 0.6, 0.0), mass=1000.0, velocity=(0.0, -5.0, 0.0))
    b = world.bodies
    x0 = np.array([[0.0, 0.2, 0.0], [0.0, 1.1, 0.0]])
    q0 = b.orientation.copy()
    velocity = b.velocity.copy()
    assert sweep_back(b, [ground], None, x0, q0, DT) == 2
    # the pair's gap along the sweeps: 0.3 − 0.45·t, SLOP at t = 0.295 / 0.45
    t = (0.3 - SLOP) / 0.45
    assert b.position[0, 1] == pytest.approx(0.2 - 0.05 * t, abs=TOLERANCE)
    assert b.position[1, 1] == pytest.approx(1.1 - 0.5 * t, abs=TOLERANCE)
    assert b.position[0, 1] - 0.1 > 0.0  # above the ground
    gap = b.position[1, 1] - b.position[0, 1] - 0.6
    assert SLOP - 1e-12 <= gap <= SLOP + TOLERANCE
    assert b.velocity.tolist() == velocity.tolist()


def test_the_leapfrog_sweep_in_one_call_is_the_three_calls_bit_for_bit():
    """``sweep_back(..., leapfrog=True)`` (the world's call: the leapfrog's swaps and the sweep
    in one compiled call, ``_leapfrog_clamp``) leaves every array as ``before_sweep``,
    ``sweep_back``, ``after_sweep`` called one after another do: a fast box swept back (its
    velocity turned), a slow one left alone, and a body asleep."""
    from pointmass.solver.body_continuous import after_sweep, before_sweep

    def scene():
        world, ground, _ = _world(Box((0.05, 0.05, 0.05)), (0.3, 0.5, 0.0),
                                  velocity=(3.0, -60.0, 0.0), spin=(0.0, 0.0, 40.0))
        world.add_body(Sphere(0.1), (2.0, 0.5, 0.0), mass=1.0, velocity=(0.5, -0.2, 0.0))
        world.add_body(Box((0.2, 0.2, 0.2)), (-2.0, 0.2, 0.0), mass=1.0)
        b = world.bodies
        b.awake[2] = False
        rng = np.random.default_rng(3)
        b.half_velocity[:] = b.velocity + rng.normal(0.0, 0.1, (3, 3))
        b.half_spin[:] = b.angular_velocity + rng.normal(0.0, 0.1, (3, 3))
        x0, q0 = b.position.copy(), b.orientation.copy()
        b.position[:] += b.half_velocity * DT  # where the straight step ends (in the ground)
        return world, ground, x0, q0

    one, ground, x0, q0 = scene()
    moved = sweep_back(one.bodies, [ground], None, x0, q0, DT, leapfrog=True)
    three, ground3, y0, r0 = scene()
    b = three.bodies
    before_sweep(b.velocity, b.angular_velocity, b.half_velocity, b.half_spin, b.left_velocity,
                 b.left_spin)
    assert sweep_back(b, [ground3], None, y0, r0, DT) == moved == 1
    after_sweep(b.awake, b.velocity, b.angular_velocity, b.half_velocity, b.half_spin,
                b.left_velocity, b.left_spin)
    for name in ("position", "orientation", "velocity", "angular_velocity", "left_velocity",
                 "left_spin"):
        assert np.array_equal(getattr(one.bodies, name), getattr(b, name)), name
