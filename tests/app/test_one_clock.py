"""One simulation, one clock: a probe run, a recording and the window take the same fixed
steps of the same demo, so their trajectories are bit-identical (issue 12)."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm

DEMO = "ballistic"          # on_step fires and kills pooled rounds: hooks, hidden slots, trails
SECONDS = 1.5


def _watched(name: str = DEMO) -> tuple[pm.Simulation, pm.Probe]:
    sim = pm.Simulation(name)
    probe = sim.add_probe(pm.Probe(
        position=lambda w: w.particles.position.copy(),
        velocity=lambda w: w.particles.velocity.copy()))
    return sim, probe


def _same(a: pm.Probe, b: pm.Probe, steps: int) -> None:
    assert len(a) >= steps and len(b) >= steps, (len(a), len(b), steps)
    for name in ("position", "velocity"):
        assert np.array_equal(a[name][:steps], b[name][:steps]), name
    assert np.array_equal(a.t[:steps], b.t[:steps])


def test_world_time_is_the_only_clock():
    sim, _ = _watched()
    sim.advance(0.25)
    assert sim.time == sim.world.time == sim.scene.time
    assert not hasattr(sim.scene, "keys_down")


def test_a_probe_run_in_one_call_matches_one_frame_at_a_time():
    whole, a = _watched()
    whole.advance(SECONDS)
    framed, b = _watched()
    for _ in range(round(SECONDS * 25)):        # 25 fps frames do not divide dt = 1/120
        framed.advance(1 / 25)
    steps = round(SECONDS / whole.dt)
    _same(a, b, steps)


@pytest.mark.gl
def test_a_recording_takes_the_probe_runs_steps(in_egl, tmp_path):
    from pointmass.render.recording import record

    reference, a = _watched()
    reference.advance(SECONDS)
    recorded, b = _watched()
    in_egl(lambda ctx: record(recorded, tmp_path / "clip.mp4", seconds=SECONDS, fps=30,
                              size=(96, 64), progress=False, ctx=ctx))
    _same(a, b, round((SECONDS - 1 / 30) / reference.dt))


@pytest.mark.window
def test_the_window_takes_the_probe_runs_steps(open_viewer):
    reference, a = _watched()
    reference.advance(SECONDS)
    shown, b = _watched()
    w = open_viewer(shown, paused=False)
    rng = np.random.default_rng(7)
    while shown.time < SECONDS - 0.05:          # irregular frames, as a real display gives
        w.dispatch_events()
        w.tick(float(rng.uniform(0.005, 0.04)))
    _same(a, b, len(b))
    assert len(b) >= round((SECONDS - 0.05) / reference.dt)


def test_probes_follow_the_simulation_through_a_reset():
    sim, probe = _watched()
    sim.advance(0.5)
    world_before = sim.world
    sim.rebuild()
    assert sim.world is not world_before and len(probe) == 0
    sim.advance(0.25)
    assert len(probe) == round(0.25 / sim.dt)
    assert probe.t[0] == pytest.approx(sim.dt)


def test_held_keys_reach_the_demo_through_the_simulation():
    held, still = pm.Simulation("bridge"), pm.Simulation("bridge")
    held.keys_down.add("D")                     # walk the load along the deck
    held.advance(0.5)
    still.advance(0.5)
    moved = np.subtract(held.scene.handles["box"].center, still.scene.handles["box"].center)
    assert abs(moved[0]) > 0.5, moved
