"""Springs that are each stable alone but not together are refused before the step
(``stability.particle_check``): the issue's two damped bungees on a 38 g particle, and the
cloth demo past its stable damping; the stiffest stable cloth still runs.

Cost (measured on the shared 2-core machine, load ~10, best of 5 × 100 steps): the 40×40 cloth
demo (1 600 particles, 6 162 springs) steps in ~0.3 ms; the screen alone takes 0.018 ms of it.
At k = 400 N/m it is past the screen (5.9) and its mode is measured (2.93): 32 ms cold (power
iteration), then kept while the springs, masses and dt stay the same bits.
"""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm
from pointmass.demo import Simulation, load_demo

H = 0.02915


def _issue_bungees() -> pm.World:
    world = pm.World(gravity=(0, 0, 0))
    world.add_particle((0.61, 0.46, 1.85), (0.49, -1.74, -5.03), mass=0.0379)
    world.add_particle((0.6, 1.15, 0.63), (7.39, 9.81, 2.24), mass=11.19)
    world.add_particle((0.6, 0.54, 0.65), (0.9, 1.47, -9.64), mass=1.0)
    world.add(pm.Bungee(a=[1, 2], b=[0, 0], spring_constant=0.349, rest_length=1.274,
                        damping=2.37))
    return world


def test_each_bungee_passes_its_own_bound_but_not_together():
    """The premise: h²ω² + 2hγ of each bungee alone is below 4 (3.67 and 3.79); the light
    particle's two dampings together are not."""
    w = 1 / np.array([0.0379, 11.19, 1.0])
    for other in (1, 2):
        pair = w[0] + w[other]
        assert (H * H * 0.349 + 2 * H * 2.37) * pair < 4.0
    assert 2 * H * 2.37 * 2 * w[0] > 4.0


def test_springs_unstable_together_are_refused_before_step_one_with_the_world_unchanged():
    """It used to reach |x| = 4e17 m by step 50 and 5e103 m by step 250 without a word. Now
    the first step is refused, naming the particle, the bungees on it and a stable dt; with
    the dt it suggests, 3 000 steps stay bounded."""
    world = _issue_bungees()
    before = world.particles.snapshot()
    with pytest.raises(pm.UnstableStepError) as caught:
        world.step(H)
    text = str(caught.value)
    assert "particle 0 (mass 0.0379 kg)" in text
    assert "Bungee springs 0, 1" in text and "The world is unchanged" in text
    after = world.particles.snapshot()
    assert all(np.array_equal(before[k], after[k]) for k in before)
    assert world.time == 0.0
    h_max = float(text.split("a time step below ")[1].split(" s")[0])
    assert 0.005 < h_max < H
    for _ in range(3000):
        world.step(h_max / 2)
    spread = world.particles.position - world.particles.position.mean(axis=0)
    assert np.abs(spread).max() < 10.0


def test_the_suggested_substeps_run_it():
    """The same scene, World(substeps=…) as the message says: it runs."""
    world = _issue_bungees()
    with pytest.raises(pm.UnstableStepError, match=r"World\(substeps=\d+\)") as caught:
        world.step(H)
    world.substeps = int(str(caught.value).split("World(substeps=")[1].split(")")[0])
    for _ in range(500):
        world.step(H)
    spread = world.particles.position - world.particles.position.mean(axis=0)
    assert np.abs(spread).max() < 10.0  # the centre of mass drifts at its own speed


def test_the_stiffest_cloth_still_runs_and_an_overdamped_one_is_refused():
    """The cloth demo (dt 1/240, 20 g particles, 8 springs each) at the top of its stiffness
    range is past the Gershgorin screen but its measured fastest mode is stable: it runs as
    before. At damping 1 N·s/m it blew up (its wind, a user force, tripped the velocity-jump
    check some steps in); now the first step is refused as springs unstable together."""
    sim = Simulation(load_demo("cloth"), overrides=["size=10", "stiffness=400"])
    sim.advance(1.0)
    assert np.isfinite(sim.world.particles.position).all()
    assert np.abs(sim.world.particles.velocity).max() < 20.0
    sim = Simulation(load_demo("cloth"), overrides=["size=10", "stiffness=400", "damping=1"])
    with pytest.raises(pm.UnstableStepError, match="together too stiff or too damped"):
        sim.step()
    assert sim.world.time == 0.0
