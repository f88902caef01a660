"""The window steps physics in a worker thread while it draws (issue 9): the trajectory is bit
for bit that of stepping in line and of a script's ``Simulation.advance``, the picture is the
state captured before the frame's steps, and nothing that touches the simulation races the
worker."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm

pytestmark = pytest.mark.window

SECONDS = 1.0


def _watched(name: str, *overrides: str) -> tuple[pm.Simulation, pm.Probe]:
    sim = pm.Simulation(name, overrides=list(overrides))
    probe = sim.add_probe(pm.Probe(
        position=lambda w: w.particles.position.copy(),
        velocity=lambda w: w.particles.velocity.copy()))
    return sim, probe


def _run_window(open_viewer, sim, *, overlap: bool, seed: int = 7) -> None:
    w = open_viewer(sim, paused=False)
    w.viewer.overlap = overlap
    rng = np.random.default_rng(seed)
    while sim.time < SECONDS - 0.05:            # irregular frames, as a real display gives
        w.dispatch_events()
        w.tick(float(rng.uniform(0.005, 0.04)))
    w.switch_to()
    assert w.ctx.error == "GL_NO_ERROR"
    w.close()                                   # one ImGui context at a time


@pytest.mark.parametrize("demo", [("ballistic",), ("ball_pit", "count=300")],
                         ids=lambda d: d[0])
def test_overlap_on_and_off_and_a_script_take_the_same_trajectory(open_viewer, demo):
    script, a = _watched(*demo)
    script.advance(SECONDS)
    results = []
    for overlap in (True, False):
        sim, probe = _watched(*demo)
        _run_window(open_viewer, sim, overlap=overlap)
        results.append(probe)
    for probe in results:
        steps = len(probe)
        assert steps >= round((SECONDS - 0.05) / script.dt)
        for name in ("position", "velocity"):
            assert np.array_equal(a[name][:steps], probe[name]), name
        assert np.array_equal(a.t[:steps], probe.t)


def test_the_worker_steps_while_the_frame_is_drawn(open_viewer, sim):
    w = open_viewer(sim, paused=False)
    v = w.viewer
    assert v.overlap                              # on by default
    w.dispatch_events()
    sim.world.particles.velocity[:, 1] = 5.0     # thrown up: every step moves them
    before = sim.time
    state = v.renderer.capture(sim.scene, trails=sim.trails)
    assert v.update(0.05) == 0                    # overlap: the steps wait for the draw
    assert sim.time == before
    w.switch_to()
    w.on_draw()                                   # captures, starts the worker, draws
    shown = v.renderer.read_rgb()
    assert v.physics_running
    w.flip()
    v.join_physics()
    assert not v.physics_running and sim.time > before
    # What was drawn is the state before the steps (one frame behind the physics).
    v.renderer.render(sim.scene, v.camera, trails=sim.trails)
    assert not np.array_equal(shown, v.renderer.read_rgb())
    v.renderer.draw(state, v.camera)
    assert np.array_equal(shown, v.renderer.read_rgb())


def test_keys_and_the_panel_wait_for_the_worker(open_viewer, sim):
    from pyglet.window import key

    w = open_viewer(sim, paused=False)
    v = w.viewer
    for _ in range(3):
        w.dispatch_events()
        v.update(1 / 60)
        w.switch_to()
        w.on_draw()
        assert v.physics_running
        w.dispatch_event("on_key_press", key.R, 0)     # an event while the worker steps
        w.dispatch_pending_events()
        assert not v.physics_running
    v.update(1 / 60)
    w.switch_to()
    w.on_draw()
    assert v.physics_running
    v.act("reset")                                    # panel buttons join first too
    assert not v.physics_running and sim.time == 0.0
    v.update(1 / 60)
    w.switch_to()
    w.on_draw()
    v.set_param(*_first_live_param(sim))
    assert not v.physics_running


def _first_live_param(sim):
    from pointmass.params import param_specs

    spec = next(s for s in param_specs(sim.params) if not s.rebuild and s.kind is float)
    return spec.name, float(spec.low)


def test_overlap_can_be_turned_off(open_viewer, sim, monkeypatch):
    from pointmass.app.viewer import overlap_default

    monkeypatch.setenv("POINTMASS_OVERLAP", "0")
    assert overlap_default() is False
    w = open_viewer(sim, paused=False)
    v = w.viewer
    assert not v.overlap
    w.dispatch_events()
    assert v.update(0.05) > 0                     # in line: the steps run in update
    w.switch_to()
    w.on_draw()
    assert not v.physics_running
