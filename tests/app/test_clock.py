"""The window's playback clock (real time to simulated seconds) and the Simulation's one
advance (simulated seconds to fixed steps), without a window."""

import pytest

import pointmass as pm
from pointmass.app.clock import TIME_SCALES, PlaybackClock


def _falling(dt=0.01):
    world = pm.World()
    world.add_particle((0, 100, 0))
    return pm.Simulation(pm.Scene(world, dt=dt))


def test_advance_runs_whole_steps_and_carries_the_remainder():
    sim = _falling(0.01)
    assert sim.advance(0.025) == 2
    assert sim.advance(0.006) == 1          # 0.005 carried over + 0.006
    assert sim.time == pytest.approx(0.03)
    assert sim.advance(0.0) == 0


def test_many_short_advances_take_the_steps_of_one_long_one():
    frames = _falling(1 / 120)
    steps = sum(frames.advance(1 / 60) for _ in range(600))
    assert steps == 1200
    once = _falling(1 / 120)
    assert once.advance(10.0) == 1200
    assert (frames.world.particles.position == once.world.particles.position).all()


def test_a_step_cap_drops_the_backlog_instead_of_spiralling():
    sim = _falling(0.01)
    assert sim.advance(0.2, max_steps=5) == 5          # would be 20
    assert sim.dropped == pytest.approx(0.15)
    assert sim.advance(0.01, max_steps=5) == 1         # no catch-up burst afterwards


def test_a_time_budget_drops_steps_too():
    sim = _falling(0.01)
    assert sim.advance(1.0, max_wall_seconds=0.0) == 1
    assert sim.dropped == pytest.approx(0.99)


@pytest.mark.parametrize("bad", [-1.0, float("nan"), float("inf")])
def test_advance_refuses_bad_seconds(bad):
    with pytest.raises(ValueError, match="seconds"):
        _falling().advance(bad)


def test_playback_scales_and_clips_real_time():
    clock = PlaybackClock(max_frame_time=0.25)
    assert clock.seconds(0.1) == pytest.approx(0.1)
    assert clock.seconds(10.0) == pytest.approx(0.25)  # a stall is not a burst of catch-up
    clock.time_scale = 0.5
    assert clock.seconds(0.1) == pytest.approx(0.05)
    clock.time_scale = 2.0
    assert clock.seconds(0.1) == pytest.approx(0.2)


def test_pause_and_single_step():
    clock = PlaybackClock(paused=True)
    assert clock.seconds(1.0) == 0.0
    assert clock.take_single_steps() == 0
    clock.single_step()
    clock.single_step()
    assert clock.take_single_steps() == 2
    assert clock.take_single_steps() == 0
    clock.toggle_pause()
    assert not clock.paused
    clock.single_step()                      # pauses, as MuJoCo's step key does
    assert clock.paused


def test_time_scale_steps_through_the_list_and_clamps():
    clock = PlaybackClock()
    clock.faster()
    assert clock.time_scale == 2.0
    for _ in range(10):
        clock.faster()
    assert clock.time_scale == TIME_SCALES[-1]
    for _ in range(20):
        clock.slower()
    assert clock.time_scale == TIME_SCALES[0]
    clock.time_scale = 0.3                     # from the panel slider: between entries
    clock.slower()
    assert clock.time_scale == 0.25


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan"), float("inf")])
def test_bad_time_scale_is_refused(bad):
    with pytest.raises(ValueError, match="time_scale"):
        PlaybackClock().time_scale = bad
