"""The fixed-step clock: accumulator, cap, pause, single step, time scale (no window)."""

import pytest

from pointmass.app.clock import TIME_SCALES, FixedStepClock


def test_steps_follow_real_time_and_keep_the_remainder():
    clock = FixedStepClock(0.01)
    assert clock.advance(0.025) == 2
    assert clock.advance(0.006) == 1          # 0.005 carried over + 0.006
    assert clock.accumulator == pytest.approx(0.001)


def test_many_frames_add_up_to_real_time():
    clock = FixedStepClock(1 / 120)
    steps = sum(clock.advance(1 / 60) for _ in range(600))
    assert steps == 1200


def test_cap_drops_backlog_instead_of_spiralling():
    clock = FixedStepClock(0.01, max_steps=5)
    assert clock.advance(0.2) == 5            # would be 20
    assert clock.accumulator == 0.0
    assert clock.dropped == pytest.approx(0.15)
    assert clock.advance(0.01) == 1           # no catch-up burst afterwards


def test_long_stall_is_clipped():
    clock = FixedStepClock(0.01, max_steps=1000, max_frame_time=0.25)
    assert clock.advance(10.0) == 25


def test_pause_and_single_step():
    clock = FixedStepClock(0.01, paused=True)
    assert clock.advance(1.0) == 0
    clock.single_step()
    assert clock.advance(1.0) == 1
    assert clock.advance(1.0) == 0
    clock.toggle_pause()
    assert not clock.paused
    assert clock.advance(0.01) == 1


def test_single_step_pauses_a_running_clock():
    clock = FixedStepClock(0.01)
    clock.advance(0.005)
    clock.single_step()
    assert clock.paused
    assert clock.advance(0.5) == 1


def test_time_scale_slower_and_faster():
    clock = FixedStepClock(0.01, max_steps=100)
    clock.time_scale = 0.5
    assert clock.advance(0.1) == 5
    clock.time_scale = 2.0
    assert clock.advance(0.1) == 20


def test_time_scale_keys_walk_the_list_and_clamp():
    clock = FixedStepClock(0.01)
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


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan")])
def test_bad_settings_are_refused(bad):
    with pytest.raises(ValueError, match="dt"):
        FixedStepClock(bad)
    with pytest.raises(ValueError, match="time_scale"):
        FixedStepClock(0.01).time_scale = bad
