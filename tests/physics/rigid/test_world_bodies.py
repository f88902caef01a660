"""Rigid bodies in ``World``: the same substep as particles; free bodies move exactly as the
stand-alone stepper moves them; bad input names its parameter."""

import numpy as np
import pytest

import pointmass as pm
from pointmass.keys import body_pair_key, body_plane_key
from pointmass.rigid.bodies import Bodies
from pointmass.rigid.shapes import Box, Sphere
from pointmass.rigid.step import integrate_positions, integrate_velocities

#: The solver's tuning numbers as World() has them (``pm.SolverSettings``)
DEFAULTS = pm.SolverSettings()


def _tumbling_box(world):
    """A tumbling, drifting box in ``world`` and its twin alone in a ``Bodies`` store."""
    q = (0.9, 0.1, -0.3, 0.2)
    body = world.add_body(Box((0.3, 0.5, 0.9)), (1.0, 2.0, 3.0), q, velocity=(1.0, 2.0, 0.0),
                          angular_velocity=(0.3, 4.0, 0.2), mass=2.0)
    alone = Bodies()
    alone.add_box((0.3, 0.5, 0.9), (1.0, 2.0, 3.0), q, velocity=(1.0, 2.0, 0.0),
                  angular_velocity=(0.3, 4.0, 0.2), mass=2.0)
    return body, alone


def _leapfrog(b: Bodies, dt: float, kicks: int, torque, g, half) -> None:
    """One step of ``World()``'s soft stage for free bodies, from the stepper's own kernels:
    leapfrog over ``kicks`` substeps of h. ``half`` holds the half-step velocity and spin the
    last step drifted with (None before the first step: it opens with a half kick from the
    velocity given); the body is left with the synchronised ones, a closing half kick on."""
    h = dt / kicks

    def kick(size):
        b.torque[:] = torque
        integrate_velocities(b.velocity, b.angular_velocity, b.force, b.torque, b.inv_mass,
                             b.inv_inertia, b.inv_inertia_world, b.linear_damping,
                             b.angular_damping, g, size, b.awake)

    if half:
        b.velocity[:], b.angular_velocity[:] = half
        kick(h)
    else:
        kick(h / 2)
    for k in range(kicks):
        if k > 0:
            kick(h)
        integrate_positions(b.position, b.orientation, b.velocity, b.angular_velocity,
                            b.inv_inertia, b.inv_inertia_world, h, b.awake)
    half[:] = b.velocity.copy(), b.angular_velocity.copy()
    kick(h / 2)
    b.clear_accumulators()


def test_free_bodies_in_the_soft_step_move_as_leapfrog_and_fall_on_the_exact_parabola():
    """A free body in the soft step (``World()``) moves bit for bit as leapfrog (velocity
    Verlet) over its substeps, composed from the stepper's kernels (``_leapfrog``): its
    position on the exact parabola y(t) = y₀ + v₀t − g·t²/2 and its velocity v₀ − g·t (to
    rounding; semi-implicit Euler at h = dt/4 fell g·t·h/2 further, 0.041 m in 2 s, and
    reported the velocity of half a substep earlier)."""
    g = np.array([0.0, -9.81, 0.0])
    world = pm.World(gravity=tuple(g))
    body, alone = _tumbling_box(world)
    half: list = []
    for _ in range(120):
        body.add_torque((0.0, 0.0, 0.5))
        stats = world.step(1 / 60)
        _leapfrog(alone, 1 / 60, DEFAULTS.soft_substeps, (0.0, 0.0, 0.5), g, half)
    assert stats.body_contacts == 0
    for name in ("position", "orientation", "velocity", "angular_velocity"):
        assert np.array_equal(getattr(world.bodies, name), getattr(alone, name)), name
    assert not world.bodies.torque.any()  # accumulators last one step
    t = 2.0
    assert world.bodies.position[0] == pytest.approx([1.0 + t, 2.0 + 2.0 * t - 9.81 * t * t / 2,
                                                      3.0], abs=1e-12)
    assert world.bodies.velocity[0] == pytest.approx([1.0, 2.0 - 9.81 * t, 0.0], abs=1e-12)


def test_particles_and_bodies_share_the_step():
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    world.add(pm.Ground(0.0, restitution=0.0, friction=0.5))
    p = world.add_particle((3.0, 1.0, 0.0), radius=0.1)
    body = world.add_body(Sphere(0.25), (0.0, 1.0, 0.0), mass=1.0)
    for _ in range(120):
        world.step(1 / 60)
    assert world.particles.position[p, 1] == pytest.approx(0.1, abs=1e-3)
    assert body.position[1] == pytest.approx(0.25, abs=1e-3)


def test_default_density_is_water():
    world = pm.World()
    assert world.add_body(Box((0.5, 0.5, 0.5))).mass == pytest.approx(1000.0)


@pytest.mark.parametrize(("kwargs", "word"), [
    ({"shape": None}, "shape"),
    ({"friction": -0.1}, "friction"),
    ({"restitution": 1.5}, "restitution"),
    ({"mass": -1.0}, "mass"),
    ({"orientation": (0.0, 0.0, 0.0, 0.0)}, "orientation"),
])
def test_bad_input_names_the_parameter(kwargs, word):
    world = pm.World()
    args = {"shape": Box((0.5, 0.5, 0.5)), **kwargs}
    with pytest.raises(ValueError, match=word):
        world.add_body(**args)


def test_body_keys_are_distinct_and_never_particle_keys():
    keys = {body_pair_key(1, 2, 5), body_pair_key(2, 1, 5), body_pair_key(1, 2, 6),
            body_plane_key(1, 2, 5), body_plane_key(1, 3, 5)}
    assert len(keys) == 5
    assert all(k >= 1 << 60 and k < 1 << 61 for k in keys)


def test_a_bare_scene_reset_puts_bodies_back():
    """Simulation(Scene).rebuild restores the bodies (added ones dropped) and their warm start:
    the rerun is the bits of a fresh world's run."""
    world = pm.World()
    world.add(pm.Ground(friction=0.5))
    box = world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 2.0, 0.0), mass=1.0)
    sim = pm.Simulation(pm.Scene(world))
    sim.advance(1.0)
    world.add_body(Sphere(0.2), (3.0, 1.0, 0.0))
    assert box.position[1] < 1.0 and world.bodies.count == 2
    sim.rebuild()
    assert world.bodies.count == 1 and box.position[1] == 2.0 and sim.time == 0.0
    sim.advance(1.0)
    again = pm.Simulation(pm.Scene(_fresh_box_world()))
    again.advance(1.0)
    assert np.array_equal(box.position, again.world.bodies.position[0])


def _fresh_box_world():
    world = pm.World()
    world.add(pm.Ground(friction=0.5))
    world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 2.0, 0.0), mass=1.0)
    return world


def test_world_energies_count_rigid_bodies():
    """World.kinetic_energy and potential_energy include bodies: ½mv² + ½ω·Iω and m·g·h."""
    from pointmass.rigid.shapes import Box

    world = pm.World(gravity=(0.0, -10.0, 0.0))
    world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 3.0, 0.0), mass=2.0, velocity=(3.0, 0.0, 0.0),
                   angular_velocity=(0.0, 2.0, 0.0))
    inertia = 2.0 * (0.5**2 + 0.5**2) / 3.0                     # m(b² + c²)/3, half-extents
    assert world.kinetic_energy() == pytest.approx(0.5 * 2.0 * 9.0 + 0.5 * inertia * 4.0)
    assert world.potential_energy() == pytest.approx(2.0 * 10.0 * 3.0)
