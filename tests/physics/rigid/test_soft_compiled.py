"""The soft step's two orchestrations of the same kernels give the same bits: without joints
the whole step is one compiled call (``body_soft.contact_step``); with joints the stages run
from Python (``body_soft.step``'s loop, which calls out for the joints). A fix made in one
and not the other (the sphere anchors of ``refresh``, the energy bound of the bounce) shows
up here as a difference."""

from __future__ import annotations

import functools

import numpy as np

import pointmass as pm
from pointmass.solver import body_soft


def _scene():
    """Boxes and spheres tumbling onto the ground and each other, bouncy and rough, with
    particles landing on them (the packed view), two on a spring: every stage of the step
    acts."""
    rng = np.random.default_rng(7)
    world = pm.World(body_step="soft", sleep=False)
    world.add(pm.Ground(restitution=0.3))
    for k in range(6):
        shape = pm.Box((0.3, 0.2, 0.25)) if k % 2 else pm.Sphere(0.2)
        q = rng.normal(size=4)
        at = (0.35 * (k % 3), 0.4 + 0.5 * k, 0.3 * (k // 3))
        world.add_body(shape, at, q / np.linalg.norm(q), velocity=rng.uniform(-1, 1, 3),
                       angular_velocity=rng.uniform(-3, 3, 3), mass=1.0 + k, friction=0.2 * k,
                       restitution=0.1 * k)
    world.add_particles([(0.1 * i, 3.5 + 0.3 * i, 0.1) for i in range(4)], radii=0.05)
    # a spring between two of them: its force and torque in every substep's kick
    world.add(pm.BodySpring(1, (0.1, 0.0, 0.0), 4, (0.0, 0.1, 0.0), k=20.0, rest=1.0,
                            damping=0.5))
    return world


def _run(compiled: bool, monkeypatch) -> tuple:
    with monkeypatch.context() as patch:
        patch.setattr(body_soft, "step", functools.partial(body_soft.step, compiled=compiled))
        world = _scene()
        for _ in range(150):
            world.step(1 / 60)
    b, p = world.bodies, world.particles
    return (b.position.copy(), b.orientation.copy(), b.velocity.copy(),
            b.angular_velocity.copy(), p.position.copy(), p.velocity.copy(),
            world.body_contacts.impulse.copy())


def test_the_compiled_step_and_the_loop_give_the_same_bits(monkeypatch):
    fused = _run(True, monkeypatch)
    loop = _run(False, monkeypatch)
    assert fused[0][:, 1].max() < 1.0  # the bodies fell and landed: the contacts acted
    for name, a, b in zip(("position", "orientation", "velocity", "spin", "particle position",
                           "particle velocity", "step impulses"), fused, loop, strict=True):
        assert np.array_equal(a, b), name
