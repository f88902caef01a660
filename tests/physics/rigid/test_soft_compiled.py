"""The soft step's two orchestrations of the same kernels give the same bits: without joints
the whole step is one compiled call (``body_soft.contact_step``); with joints the stages run
from Python (``body_soft.step``'s loop, which calls out for the joints and the force
generators). A fix made in one and not the other (the sphere anchors of ``refresh``, the
energy bound of the bounce), or a ``SolverSettings`` field read by one and not the other,
shows up here as a difference. (Until this test's scene lost its ``BodySpring``, a force
generator, both of its runs took the loop: it compared the loop with itself.)"""

from __future__ import annotations

import functools

import numpy as np
import pytest

import pointmass as pm
from pointmass.solver import body_soft


def _scene(settings: pm.SolverSettings):
    """Boxes and spheres tumbling onto the ground and each other, bouncy and rough, with
    particles landing on them (the packed view): every stage of the step acts."""
    rng = np.random.default_rng(7)
    world = pm.World(sleep=False, settings=settings)
    world.add(pm.Ground(restitution=0.3))
    for k in range(6):
        shape = pm.Box((0.3, 0.2, 0.25)) if k % 2 else pm.Sphere(0.2)
        q = rng.normal(size=4)
        at = (0.35 * (k % 3), 0.4 + 0.5 * k, 0.3 * (k // 3))
        world.add_body(shape, at, q / np.linalg.norm(q), velocity=rng.uniform(-1, 1, 3),
                       angular_velocity=rng.uniform(-3, 3, 3), mass=1.0 + k, friction=0.2 * k,
                       restitution=0.1 * k)
    world.add_particles([(0.1 * i, 3.5 + 0.3 * i, 0.1) for i in range(4)], radii=0.05)
    return world


def _run(compiled: bool, monkeypatch, settings: pm.SolverSettings) -> tuple:
    calls = [0]
    fused = body_soft._contact_step

    def counted(*args):
        calls[0] += 1
        return fused(*args)

    with monkeypatch.context() as patch:
        patch.setattr(body_soft, "step", functools.partial(body_soft.step, compiled=compiled))
        patch.setattr(body_soft, "_contact_step", counted)
        world = _scene(settings)
        for _ in range(150):
            # a push off the centre, given before each step: its force and torque in every
            # substep's kick (a force generator, found again each substep, always takes the
            # loop, so the scene has none)
            world.bodies.add_force_at_point(1, (3.0, 0.0, -2.0),
                                            world.bodies.position[1] + (0.0, 0.1, 0.1))
            world.step(1 / 60)
    assert (calls[0] > 0) == compiled  # the compiled call ran, or the loop alone did
    b, p = world.bodies, world.particles
    return (b.position.copy(), b.orientation.copy(), b.velocity.copy(),
            b.angular_velocity.copy(), p.position.copy(), p.velocity.copy(),
            world.body_contacts.impulse.copy())


#: Settings other than the defaults in every field the two orchestrations read
OTHER = pm.SolverSettings(soft_substeps=3, contact_hertz=120.0, contact_hertz_cap=0.9,
                          contact_damping_ratio=2.0, contact_speed=1.0, soft_solve_passes=4,
                          soft_relax_passes=6, soft_tolerance=1e-4, soft_relaxation=1.2)


@pytest.mark.parametrize("settings", [pm.SolverSettings(), OTHER], ids=["defaults", "other"])
def test_the_compiled_step_and_the_loop_give_the_same_bits(monkeypatch, settings):
    """... with the default settings and with others: both read the same fields."""
    fused = _run(True, monkeypatch, settings)
    loop = _run(False, monkeypatch, settings)
    assert fused[0][:, 1].max() < 1.0  # the bodies fell and landed: the contacts acted
    for name, a, b in zip(("position", "orientation", "velocity", "spin", "particle position",
                           "particle velocity", "step impulses"), fused, loop, strict=True):
        assert np.array_equal(a, b), name
