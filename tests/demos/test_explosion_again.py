"""The explosion demo goes off by itself and then again and again: whoever looks late (a window
still opening, a recording started later) still sees a blast."""

from __future__ import annotations

import numpy as np

from pointmass.demo import Simulation


def test_the_ring_is_put_back_and_blown_again():
    sim = Simulation("explosion", overrides=["auto_time=0.5", "again=2.0"])
    h = sim.scene.handles
    start = sim.world.bodies.position.copy()
    blasts, put_back = [], 0
    previous = None
    for _ in range(round(5.2 * 60)):
        sim.step()
        if h["at"] is not None and h["at"] != previous:
            blasts.append(h["at"])
        previous = h["at"]
        if h["at"] is None and blasts and abs(h["armed"] - (sim.time - sim.dt)) < 1e-9:
            # put back at the start of this step: the ring as it was built, one step later
            assert np.allclose(sim.world.bodies.position, start, atol=0.01)
            put_back += 1
    # blasts at 0.5 s, then 2 s after each blast plus 0.5 s from the rearm: 3.0 s, 5.5 s...
    assert len(blasts) == 2 and put_back == 2, (blasts, put_back)
    assert abs(blasts[0] - 0.5) < 0.02 and abs(blasts[1] - 3.0) < 0.05, blasts


def test_again_zero_blows_once():
    sim = Simulation("explosion", overrides=["auto_time=0.5", "again=0"])
    sim.advance(4.0)
    assert abs(sim.scene.handles["at"] - 0.5) < 0.02
