"""The panel's particle count (no window): live particles, not the pool size."""

import numpy as np

import pointmass as pm
from pointmass.app.stats import particle_count
from pointmass.demo import Simulation, load_demo


def test_fireworks_count_the_live_particles_of_the_pool():
    """The fireworks' pool is 1024 particles whatever is alive; the count follows the bursts."""
    sim = Simulation(load_demo("fireworks"))
    assert particle_count(sim.scene) == "0 live / 1024"
    for _ in range(120):
        sim.advance(1 / 30)
    live = int((~sim.scene.hidden).sum())
    assert 0 < live < 1024
    assert particle_count(sim.scene) == f"{live} live / 1024"


def test_a_scene_that_hides_nothing_shows_the_plain_count():
    world = pm.World()
    world.add_particles(np.zeros((3, 3)))
    assert particle_count(pm.Scene(world)) == "3"


def test_a_short_hidden_mask_counts_the_rest_as_live():
    """A demo that grew its world without growing its mask: the new particles are drawn."""
    world = pm.World()
    world.add_particles(np.zeros((4, 3)))
    scene = pm.Scene(world, hidden=np.array([True, False]))
    assert particle_count(scene) == "3 live / 4"
