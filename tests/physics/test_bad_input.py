"""Bad input fails at once, with an error naming the parameter and its range; never a NaN later."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm

DT = 1.0 / 60.0


@pytest.mark.parametrize("mass", [0.0, -1.0, math.nan, -math.inf])
def test_bad_mass_is_refused(mass):
    """Refuse a mass ≤ 0 or NaN, naming mass and the range (0, inf]."""
    world = pm.World()
    with pytest.raises(ValueError, match=r"mass must be in \(0, inf\]"):
        world.add_particle(mass=mass)
    i = world.add_particle()
    with pytest.raises(ValueError, match=r"mass must be in \(0, inf\]"):
        world.particles[i].mass = mass
    assert world.particles.count == 1


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_position_or_velocity_is_refused(bad):
    """Refuse non-finite positions and velocities, naming which."""
    world = pm.World()
    with pytest.raises(ValueError, match="position must be finite"):
        world.add_particle(position=(0, bad, 0))
    with pytest.raises(ValueError, match="velocity must be finite"):
        world.add_particle(velocity=(bad, 0, 0))
    with pytest.raises(ValueError, match="position must be finite"):
        world.add_particles([(0, 0, 0), (1, bad, 0)])
    i = world.add_particle()
    with pytest.raises(ValueError, match="velocity must be finite"):
        world.particles[i].velocity = (0, 0, bad)
    assert np.isfinite(world.particles.position).all()


def test_negative_radius_is_refused():
    """Refuse a negative radius, naming radius and [0, inf]."""
    world = pm.World()
    with pytest.raises(ValueError, match=r"radius must be in \[0, inf\]"):
        world.add_particle(radius=-0.1)
    i = world.add_particle(radius=0.1)
    with pytest.raises(ValueError, match=r"radius must be in \[0, inf\]"):
        world.particles[i].radius = -1.0


def test_negative_rest_length_is_refused():
    """Refuse negative spring rest lengths and non-positive link lengths, naming them."""
    with pytest.raises(ValueError, match=r"rest_length must be in \[0, inf\]"):
        pm.Spring(0, 1, spring_constant=1.0, rest_length=-1.0)
    with pytest.raises(ValueError, match=r"rest_length must be in \[0, inf\]"):
        pm.AnchoredSpring(0, (0, 0, 0), rest_length=-2.0)
    with pytest.raises(ValueError, match=r"spring_constant must be in \[0, inf\]"):
        pm.Spring(0, 1, spring_constant=-5.0)
    with pytest.raises(ValueError, match=r"max_length must be in \(0, inf\]"):
        pm.Cable(0, 1, max_length=0.0)
    with pytest.raises(ValueError, match=r"length must be in \(0, inf\]"):
        pm.Rod(0, 1, length=-1.0)


def test_index_that_is_not_a_particle_is_refused():
    """Refuse world.add(Spring(0, 99)) when there is no particle 99, naming b and the range."""
    world = pm.World()
    world.add_particles(np.zeros((2, 3)))
    with pytest.raises(IndexError, match=r"b: 99 is not a particle; indices must be in \[0, 1\]"):
        world.add(pm.Spring(0, 99))
    with pytest.raises(IndexError, match="a: -1 is not a particle"):
        world.add(pm.Rod(-1, 1, length=1.0))
    with pytest.raises(IndexError, match="particles: 5 is not a particle"):
        world.add(pm.Gravity(particles=[0, 5]))
    with pytest.raises(IndexError, match="particle: 7 is not a particle"):
        world.particles[7]
    with pytest.raises(ValueError, match="joins particle 0 to itself"):
        world.add(pm.Spring(0, 0))
    assert world.forces == [] and world.contact_generators == []


@pytest.mark.parametrize("dt", [0.0, -DT, math.nan, math.inf])
def test_bad_time_step_is_refused(dt):
    """Refuse dt ≤ 0 or non-finite, naming dt, and leave the world untouched."""
    world = pm.World()
    world.add_particle(position=(0, 1, 0))
    with pytest.raises(ValueError, match="dt must be a finite number of seconds > 0"):
        world.step(dt)
    assert world.time == 0.0 and world.particles.position[0, 1] == 1.0


@pytest.mark.parametrize("e", [-0.1, 1.5, math.nan])
def test_restitution_outside_zero_one_is_refused(e):
    """Refuse restitution outside [0, 1] everywhere it is accepted."""
    for make in (lambda: pm.Ground(restitution=e), lambda: pm.SphereCollisions(restitution=e),
                 lambda: pm.BoxContainer(restitution=e), lambda: pm.Cable(0, 1, 1.0, restitution=e),
                 lambda: pm.Plane((0, 1, 0), restitution=e)):
        with pytest.raises(ValueError, match=r"restitution must be in \[0, 1\]"):
            make()
    ground = pm.Ground()
    with pytest.raises(ValueError, match=r"restitution must be in \[0, 1\]"):
        ground.restitution = e


def test_other_settings_are_checked():
    """Refuse bad damping, drag, margin, world settings, each naming its parameter."""
    with pytest.raises(ValueError, match=r"damping must be in \[0, 1\]"):
        pm.World().add_particle(damping=1.5)
    with pytest.raises(ValueError, match=r"k1 must be in \[0, inf\]"):
        pm.Drag(-1.0, 0.1)
    with pytest.raises(ValueError, match=r"margin must be in \[0, inf\]"):
        pm.SphereCollisions(margin=-0.1)
    with pytest.raises(ValueError, match="substeps must be an int in"):
        pm.World(substeps=0)
    with pytest.raises(ValueError, match="resolver must be"):
        pm.World(resolver="fastest")
    with pytest.raises(ValueError, match="gravity must be finite"):
        pm.World(gravity=(0, math.nan, 0))


def test_a_spring_too_stiff_for_dt_is_refused_before_it_moves_anything():
    """k = 1e7 between 1 kg particles at 60 Hz threw them 1e6 m in one step and failed 41
    steps later with NaN everywhere. Now the first step refuses, names the generator and the
    remedies, and leaves the world exactly as it was; with the suggested substeps it runs."""
    world = pm.World(gravity=(0, 0, 0))
    a, b = world.add_particles([(0, 0, 0), (1.5, 0, 0)])
    world.add(pm.Spring(a, b, spring_constant=1e7, rest_length=1.0))
    before = world.particles.snapshot()
    with pytest.raises(pm.UnstableStepError, match=r"Spring spring 0 \(particles 0–1\) is too "
                       r"stiff for dt.*World\(substeps=75\).*FakeSpring.*unchanged"):
        world.step(DT)
    after = world.particles.snapshot()
    # Everything, the force accumulator too: a refused step leaves no half-added forces.
    assert all(np.array_equal(before[k], after[k]) for k in before)
    assert world.time == 0.0
    world.substeps = 75
    for _ in range(60):
        world.step(DT)
    assert np.isfinite(world.particles.position).all()
    assert abs(np.linalg.norm(world.particles.position[a] - world.particles.position[b])
               - 1.0) < 0.6


def test_the_stability_bound_is_the_exact_one_for_a_damped_oscillator():
    """Semi-implicit Euler on x'' = -ω²x - γx' is stable iff h²ω² + 2hγ < 4: just below the
    bound the amplitude stays bounded for 10 000 steps, and just above the guard refuses."""
    k, c, m = 50.0, 0.4, 0.038
    h_max = pm.stability.largest_stable_step(k / m, c / m)
    world = pm.World(gravity=(0, 0, 0))
    p = world.add_particle((0, -1.2, 0), mass=m)
    world.add(pm.AnchoredSpring(p, (0, 0, 0), spring_constant=k, rest_length=1.0, damping=c))
    for _ in range(10_000):
        world.step(0.999 * h_max)
    assert np.abs(world.particles.position[p]).max() < 1.3
    with pytest.raises(pm.UnstableStepError,
                       match=r"AnchoredSpring spring 0 \(particle 0 to its anchor\) is too stiff"):
        world.step(1.001 * h_max)


def test_a_user_force_that_would_throw_a_particle_is_refused_naming_it():
    """A CustomForce of 1e9 N on 1 kg: refused before the particle moves, naming CustomForce;
    with substeps the earlier substeps are undone too."""
    for substeps in (1, 4):
        world = pm.World(substeps=substeps)
        p = world.add_particle((0, 1, 0), velocity=(0, 3, 0))
        world.add(pm.CustomForce(lambda q: (0, 1e9 if q.position[1] > 1.02 else 0, 0)))
        before = world.particles.snapshot()
        with pytest.raises(pm.UnstableStepError, match="comes from CustomForce"):
            for _ in range(10):
                before, t = world.particles.snapshot(), world.time
                world.step(DT)
        after = world.particles.snapshot()
        # Everything but the force accumulator, which every step clears and rebuilds.
        assert all(np.array_equal(before[k], after[k]) for k in before if k != "force")
        assert world.time == t
        assert world.particles.position[p, 1] < 1.1


def test_a_kinetic_energy_that_overflows_raises():
    """|v| = 1e200 is finite but its square is not: the step's statistics say so instead of
    reporting kinetic_energy = inf."""
    world = pm.World(gravity=(0, 0, 0))
    world.add_particle(velocity=(1e200, 0, 0))
    stats = world.step(DT)
    with pytest.raises(FloatingPointError, match="kinetic energy overflowed"):
        _ = stats.kinetic_energy


def test_custom_force_returning_nan_is_refused():
    """Refuse a CustomForce result that is not a finite 3-vector, naming the particle."""
    world = pm.World()
    world.add_particle()
    world.add(pm.CustomForce(lambda p: (0.0, math.nan, 0.0)))
    with pytest.raises(ValueError, match="for particle 0; it must return a finite 3-vector"):
        world.step(DT)


@pytest.mark.parametrize("bad", [True, False, "1", b"1", [1.0, True], np.array([True])])
def test_a_mass_that_is_not_a_number_is_refused(bad):
    """``mass=True`` or ``mass="1"`` would silently become 1 kg through numpy: refuse them."""
    world = pm.World()
    with pytest.raises(ValueError, match="mass must be a number"):
        if isinstance(bad, list):
            world.add_particles([(0, 0, 0), (1, 0, 0)], masses=bad)
        else:
            world.add_particle(mass=bad)
    assert world.particles.count == 0


@pytest.mark.parametrize("mass", [5e-324, 1e-13, 1e19])
def test_a_mass_that_cannot_be_inverted_safely_is_refused(mass):
    """5e-324 kg inverts to inf (the first step would fail): refuse it when it is given."""
    with pytest.raises(ValueError, match=r"mass must be in \(0, inf\] kg: between 1e-12"):
        pm.World().add_particle(mass=mass)


@pytest.mark.parametrize("dt", [True, "0.1", None, [0.1]])
def test_a_dt_that_is_not_a_number_is_refused(dt):
    """``step(True)`` would run one whole second: refuse it."""
    world = pm.World()
    world.add_particle()
    with pytest.raises(ValueError, match="dt must be a finite number of seconds"):
        world.step(dt)
    assert world.time == 0.0


def test_the_same_generator_added_twice_is_refused():
    """Adding one generator twice would apply its forces twice: refuse, keep one."""
    world = pm.World()
    a, b = world.add_particles([(0, 0, 0), (1, 0, 0)])
    spring = world.add(pm.Spring(a, b, 10.0, 1.0))
    ground = world.add(pm.Ground())
    for generator in (spring, ground):
        with pytest.raises(ValueError, match="already in this world"):
            world.add(generator)
    assert world.forces == [spring] and world.contact_generators == [ground]


def test_a_generator_whose_particle_was_dropped_by_restore_fails_clearly():
    """After ``restore`` drops a particle, a spring to it would read a stale row beyond
    ``count`` and pull on nothing: the next step names the generator instead."""
    world = pm.World(gravity=(0, 0, 0))
    a = world.add_particle()
    snap = world.particles.snapshot()
    b = world.add_particle((2, 0, 0))
    world.add(pm.Spring(a, b, 10.0, 1.0))
    world.step(DT)
    world.particles.restore(snap)
    with pytest.raises(IndexError, match="Spring refers to a particle that no longer exists"):
        world.step(DT)
    world.particles.restore(world.particles.snapshot())  # still one particle: still refused
    world.add_particle((2, 0, 0))  # the row exists again: the world steps
    world.step(DT)
