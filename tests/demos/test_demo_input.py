"""Demos driven as a user drives them: keys held down (WASD loads, the blob), every ammunition
fired. Each demo's own oracle runs after every frame, not just at the end."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pointmass.demo import Simulation, load_demo

#: (keys held, frames at 30 fps): walk the load (or the blob) left, right, across, and rest.
WALK = [({"A"}, 45), ({"D"}, 90), ({"W", "D"}, 30), ({"S"}, 30), (set(), 30)]


def hold(sim: Simulation, keys: set[str], frames: int) -> None:
    sim.keys_down = set(keys)
    for _ in range(frames):
        sim.advance(1.0 / 30.0)
        sim.check()


@pytest.mark.parametrize("name", ["bridge", "platform"])
def test_heaviest_load_walked_across_keeps_the_structure_whole(name):
    """Walk the heaviest load allowed end to end: the bridge stays above the ground, the
    platform keeps its rods and stays out of the ground, after every frame."""
    sim = Simulation(load_demo(name), overrides=["load_mass=50"])
    for keys, frames in WALK:
        hold(sim, keys, frames)


def test_bridge_sags_where_the_load_stands():
    """The deck under the load hangs lower than the same deck with the load at the far end."""
    sim = Simulation(load_demo("bridge"), overrides=["load_mass=50"])
    hold(sim, {"A"}, 60)
    hold(sim, set(), 60)
    y = sim.world.particles.position[:, 1]
    left, right = y[:4].mean(), y[-4:].mean()
    hold(sim, {"D"}, 90)
    hold(sim, set(), 60)
    y = sim.world.particles.position[:, 1]
    assert y[-4:].mean() < right - 0.05 and y[:4].mean() > left + 0.05


def test_platform_tips_toward_the_load():
    """Load on the left end: the left corners go down; on the right end: the right ones."""
    sim = Simulation(load_demo("platform"), overrides=["load_mass=30"])
    hold(sim, {"A"}, 60)
    hold(sim, set(), 60)
    y = sim.world.particles.position[:, 1]
    assert y[2:4].mean() < y[4:6].mean()
    hold(sim, {"D"}, 90)
    hold(sim, set(), 60)
    y = sim.world.particles.position[:, 1]
    assert y[4:6].mean() < y[2:4].mean()


def test_blob_driven_with_wasd_holds_together_and_moves():
    """Push the head right, left, then up-right: the blob travels and never comes apart."""
    sim = Simulation(load_demo("blob"))
    hold(sim, set(), 30)
    start = sim.world.particles.position[:5, 0].mean()
    hold(sim, {"D"}, 60)
    assert sim.world.particles.position[:5, 0].mean() > start + 1.0
    for keys, frames in WALK:
        hold(sim, keys, frames)


def test_every_ammunition_follows_its_damped_ballistic_path():
    """Pick each ammunition by its key and fire it with Space and a click; the oracle checks
    each live round against its own mass, gravity and damping."""
    sim = Simulation(load_demo("ballistic"), overrides=["auto_fire_interval=0"])
    for key in "1234":
        sim.press(key)
        sim.press("SPACE")
        sim.advance(0.1)
        sim.press("CLICK")
        hold(sim, set(), 6)
    kinds = {k for k, hidden in zip(sim.scene.handles["kind"], sim.scene.hidden, strict=True)
             if not hidden}
    assert kinds == {"pistol", "artillery", "fireball", "laser"}
    hold(sim, set(), 155)  # 5.2 s: even the slow fireball has lived out its 5 s
    assert sim.scene.hidden.all(), "a round outlived 5 s"


def test_fireworks_depend_on_the_seed():
    """Same seed, same show (the demo's check); another seed, another show."""
    shows = []
    for seed in (1, 1, 2):
        sim = Simulation(load_demo("fireworks"), overrides=[f"seed={seed}"])
        for _ in range(60):
            sim.advance(1.0 / 30.0)
        sim.check()
        shows.append(sim.world.particles.position.copy())
    assert np.array_equal(shows[0], shows[1])
    assert not np.array_equal(shows[0], shows[2])


def fly(sim: Simulation, keys: set[str], seconds: float) -> None:
    sim.keys_down = set(keys)
    sim.advance(seconds)


def test_flightsim_held_keys_pitch_and_roll_the_aircraft():
    """Hold W: the nose pitches down (body pitch rate > 0); S: up; D rolls right, A left; X
    centres every control."""
    demo = load_demo("flightsim")
    rates = demo.module.body_rates
    for keys, axis, sign in (({"W"}, 2, 1), ({"S"}, 2, -1), ({"D"}, 0, 1), ({"A"}, 0, -1)):
        sim = Simulation(demo)
        fly(sim, set(), 2.0)
        level = rates(sim.scene.handles["plane"])[axis]
        fly(sim, keys, 0.4)
        turned = rates(sim.scene.handles["plane"])[axis]
        assert sign * (turned - level) > 0.05, (keys, level, turned)
        fly(sim, {"X"}, 1.0 / 60.0)
        assert all(sim.scene.handles["surfaces"][n].control == 0.0
                   for n in ("left", "right", "rudder"))
    sim.check()


def test_sailboat_held_rudder_turns_it_and_w_centres():
    """Hold A: the bow turns to port (heading grows); W puts the sail across and the rudder
    straight again."""
    demo = load_demo("sailboat")
    sim = Simulation(demo)
    fly(sim, set(), 3.0)
    start = demo.module.heading(sim.scene.handles["boat"])
    fly(sim, {"A", "Q"}, 3.0)
    assert demo.module.heading(sim.scene.handles["boat"]) > start + math.radians(10.0)
    fly(sim, {"W"}, 0.1)
    assert sim.scene.handles["rudder"].control == 0.0
    assert sim.scene.handles["sail_control"] == 1.0
    sim.check()


def test_fracture_space_reassembles_the_block_and_throws_the_next_ball():
    """After the break, SPACE gives back one whole 100 kg block and a new ball with another
    random velocity; it breaks again."""
    sim = Simulation(load_demo("fracture"))
    sim.advance(2.0)
    h = sim.scene.handles
    assert len(h["parts"]) == 8
    first = h["split"]["before"].copy()
    sim.press("SPACE")
    assert sim.world.bodies.count == 2 and h["split"] is None
    assert 1.0 / sim.world.bodies.inv_mass[h["block"]] == pytest.approx(100.0)
    sim.advance(2.0)
    assert len(h["parts"]) == 8
    assert not np.allclose(h["split"]["before"], first)
    sim.check()
