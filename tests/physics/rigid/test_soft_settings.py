"""The soft step's tuning numbers are ``SolverSettings`` fields (issue 26: one frozen value on
``World`` replaces the module constants): each one given through ``World(settings=...)``
changes the step the way its docstring says, against the physics it stands for, and a bad
value is refused naming the field and its range."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.joints import BallJoint
from pointmass.rigid.shapes import Box, Sphere
from pointmass.solver.body_continuous import sweep_back

DT = 1 / 60
G = 9.81


def _settings(**changes) -> pm.SolverSettings:
    return dataclasses.replace(pm.SolverSettings(), **changes)


def _pendulum_energy_band(substeps: int) -> float:
    """A 1 m ball-joint pendulum (1 kg bob, no damping) released level, 5 s: the spread of its
    total energy over m·g·L."""
    world = pm.World(settings=_settings(soft_substeps=substeps), sleep=False)
    body = world.add_body(Box((0.1, 0.1, 0.1)), (1.0, 0.0, 0.0), mass=1.0)
    world.add(BallJoint(body, (-1.0, 0.0, 0.0)))
    energies = []
    for _ in range(300):
        world.step(DT)
        energies.append(world.kinetic_energy() + world.potential_energy())
    return (max(energies) - min(energies)) / (1.0 * G * 1.0)


def test_fewer_substeps_widen_a_pendulums_energy_band_in_proportion_to_h_squared():
    """The tree's joints add nothing to the energy (``joint_soft``): the pendulum's energy
    swings as leapfrog at h = dt / ``soft_substeps`` swings it, by O((ω·h)²), so one substep a
    step (h = dt) swings 16 times as far as the default 4 and 8 a quarter as far (measured
    0.00101, 6.33e-5, 1.58e-5 of m·g·L; semi-implicit Euler, before the leapfrog, swung
    0.0457, 0.0114, 0.0057: first order)."""
    one, four, eight = (_pendulum_energy_band(n) for n in (1, 4, 8))
    assert four < 1e-4  # the default
    assert one / four == pytest.approx(16.0, rel=0.02)
    assert four / eight == pytest.approx(4.0, rel=0.02)


def _sag(**changes) -> float:
    """How far a unit box (1 kg) resting face down on the ground has sunk after 2 s [m]."""
    world = pm.World(settings=_settings(**changes))
    world.add(pm.Ground(friction=0.5))
    world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.5, 0.0), mass=1.0)
    for _ in range(120):
        world.step(DT)
    assert np.abs(world.bodies.velocity).max() < pm.SolverSettings().soft_tolerance
    return 0.5 - float(world.bodies.position[0, 1])


def _spring_sag(hertz: float) -> float:
    """A unit box's static sag on four corner rows of normal mass m_n = 1/4 kg against
    scenery, each a spring k = m_n·ω² at twice the contact's hertz: m·g / (4·m_n·(2ω)²)."""
    omega = 2.0 * math.pi * hertz
    return 1.0 * G / (4 * 0.25 * (2.0 * omega) ** 2)


def test_a_softer_contact_lets_a_resting_box_sink_deeper_by_its_spring():
    """``contact_hertz`` is the contact spring's frequency: a quarter of it (60 Hz) is a
    sixteenth of the stiffness and sixteen times the sag, each as the spring's m·g/k
    (measured 1.0785 µm and 17.256 µm); a cap on it (``contact_hertz_cap`` × the substep
    rate, 0.25 × 240 Hz) acts as that lower hertz."""
    stiff = _sag()
    soft = _sag(contact_hertz=60.0)
    assert stiff == pytest.approx(_spring_sag(240.0), rel=1e-3)
    assert soft == pytest.approx(_spring_sag(60.0), rel=1e-3)
    assert soft / stiff == pytest.approx(16.0, rel=1e-3)
    assert _sag(contact_hertz_cap=0.25) == pytest.approx(soft, rel=1e-6)


@pytest.mark.parametrize("speed", [0.3, 3.0])
def test_an_overlap_is_pushed_out_no_faster_than_the_contact_speed(speed):
    """``contact_speed`` caps the push-out: a box started 10 cm inside the ground (no gravity)
    rises by contact_speed·dt a step while the spring would push it faster (at 0.3 m/s,
    5 mm a step, every step of 8), never by more; with the default 3 m/s it is out in 8 steps
    (50 mm, then the spring's own rate: 40.5, 8.1, 1.2 mm, ...). The relax pass takes the
    push-out's velocity back each substep, so it is never launched: at rest between steps."""
    world = pm.World(gravity=(0.0, 0.0, 0.0), settings=_settings(contact_speed=speed))
    world.add(pm.Ground())
    world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.4, 0.0), mass=1.0)
    rises = []
    last = 0.4
    for _ in range(8):
        world.step(DT)
        y = float(world.bodies.position[0, 1])
        rises.append(y - last)
        assert np.abs(world.bodies.velocity).max() < 1e-9
        last = y
    assert rises[0] == pytest.approx(speed * DT, rel=1e-5)
    assert max(rises) <= speed * DT * (1.0 + 1e-5)
    if speed == 0.3:
        assert rises == pytest.approx([speed * DT] * 8, rel=1e-5)
    else:
        assert rises[1] < 0.9 * speed * DT
        assert 0.0 < 0.1 - sum(rises) < 1e-5


def test_the_continuous_stage_stops_a_fast_body_at_the_settings_slop():
    """``continuous_slop`` is the separation a time of impact stops a fast body at (Box2D's
    linear slop): a sphere whose step ended through the ground is put back on its line with
    its lowest point that far above the ground, to the advancement's tolerance (a quarter
    of the slop)."""
    for slop in (0.005, 0.02):
        world = pm.World(gravity=(0.0, 0.0, 0.0))
        ground = pm.Ground(0.0)
        world.add(ground)
        world.add_body(Sphere(0.05), (0.3, 0.5, 0.0), mass=1.0, velocity=(3.0, -60.0, 0.0))
        b = world.bodies
        x0, q0 = b.position.copy(), b.orientation.copy()
        b.position[0] += b.velocity[0] * DT  # where its straight step would end: 0.5 m deep
        assert sweep_back(b, [ground], None, x0, q0, DT, settings=_settings(
            continuous_slop=slop)) == 1
        gap = b.position[0, 1] - 0.05
        assert slop - 1e-12 <= gap <= 1.25 * slop


def test_the_world_passes_its_settings_to_the_soft_step():
    """The settings assigned to ``world.settings`` are the ones its next step uses: the same
    scene with the same settings gives the same bits, with other ones other bits."""
    def run(settings):
        world = pm.World(settings=settings)
        world.add(pm.Ground(friction=0.5))
        for k in range(3):
            world.add_body(Box((0.2, 0.2, 0.2)), (0.05 * k, 0.3 + 0.45 * k, 0.0), mass=1.0,
                           friction=0.5)
        for _ in range(60):
            world.step(DT)
        return world.bodies.position.copy()

    base = run(pm.SolverSettings())
    assert np.array_equal(base, run(pm.SolverSettings()))
    for change in ({"soft_solve_passes": 1, "soft_relax_passes": 1},
                   {"soft_relaxation": 1.0}, {"contact_damping_ratio": 1.0},
                   {"soft_tolerance": 1e-2}):
        assert not np.array_equal(base, run(_settings(**change))), change


@pytest.mark.parametrize(("field", "value", "message"), [
    ("soft_substeps", 0, "soft_substeps must be >= 1"),
    ("soft_substeps", 1001, r"soft_substeps must be in \[1, 1000\]"),
    ("soft_substeps", 2.0, "soft_substeps must be an int"),
    ("contact_hertz", 0.0, "contact_hertz must be a finite number > 0"),
    ("contact_hertz", math.inf, "contact_hertz must be a finite number > 0"),
    ("contact_hertz_cap", -1.0, "contact_hertz_cap must be a finite number > 0"),
    ("contact_damping_ratio", -0.1, "contact_damping_ratio must be a finite number >= 0"),
    ("contact_speed", 0.0, "contact_speed must be a finite number > 0"),
    ("soft_solve_passes", 0, "soft_solve_passes must be >= 1"),
    ("soft_relax_passes", 0, "soft_relax_passes must be >= 1"),
    ("soft_tolerance", float("nan"), "soft_tolerance must be a finite number > 0"),
    ("soft_relaxation", 2.0, r"soft_relaxation must be in \(0, 2\)"),
    ("soft_relaxation", 0.0, "soft_relaxation must be a finite number > 0"),
    ("joint_hertz", 0.0, "joint_hertz must be a finite number > 0"),
    ("joint_damping_ratio", -1.0, "joint_damping_ratio must be a finite number >= 0"),
    ("joint_hertz_cap", 0.0, "joint_hertz_cap must be a finite number > 0"),
    ("joint_passes", 0, "joint_passes must be >= 1"),
    ("joint_tolerance", 0.0, "joint_tolerance must be a finite number > 0"),
    ("continuous_slop", 0.0, "continuous_slop must be a finite number > 0"),
    ("continuous_safety", -0.5, "continuous_safety must be a finite number > 0"),
])
def test_bad_soft_step_settings_are_refused_naming_the_field_and_its_range(field, value,
                                                                         message):
    with pytest.raises((ValueError, TypeError), match=message):
        pm.SolverSettings(**{field: value})
