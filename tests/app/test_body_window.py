"""Grabbing rigid bodies in a real window (under Xvfb, dispatched events): Ctrl+drag on a box
of the box tower, and the same trajectory with physics overlapped with drawing or not."""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_window import frames, press_key, send, to_window

import pointmass as pm

pytestmark = pytest.mark.window


def _turned_deg(q0, q1) -> float:
    """The angle [deg] of the rotation from orientation q0 to q1 (unit quaternions)."""
    return 2 * math.degrees(math.acos(min(1.0, abs(float(np.dot(q0, q1))))))


def _press_on_top_box(w, sim, offset=(15, -10)):
    """Ctrl+press a little off the centre of the tower's top box; returns the window point."""
    from pyglet.window import key, mouse

    v = w.viewer
    top = sim.world.bodies.count - 1
    px, py = v.camera.project(sim.world.bodies.position[top][None], v.renderer.size)[0]
    x, y = to_window(w, px + offset[0], py + offset[1])
    send(w, "on_mouse_motion", x, y, 0, 0)
    send(w, "on_mouse_press", x, y, mouse.LEFT, key.MOD_CTRL)
    return x, y


def test_ctrl_drag_moves_and_turns_a_box_toward_the_cursor_and_releases(open_viewer):
    from pyglet.window import key, mouse

    sim = pm.Simulation("box_tower", overrides=["count=4"])
    w = open_viewer(sim, paused=False)
    press_key(w, "TAB")                          # panel away: the view is the whole window
    frames(w, 10)
    v = w.viewer
    v.join_physics()
    top = sim.world.bodies.count - 1
    start, q0 = sim.world.bodies.position[top].copy(), sim.world.bodies.orientation[top].copy()
    x, y = _press_on_top_box(w, sim)
    grab = v.mouse.grab
    assert grab is not None and (grab.kind, grab.index) == ("body", top)
    held = grab.spring.point(sim.world)
    local = grab.spring.local                    # the point clicked, on the box's surface
    assert np.abs(local).max() == pytest.approx(0.5, abs=1e-9)
    for k in range(1, 11):                       # 150 px right and 100 px up, as a hand would
        send(w, "on_mouse_drag", x + 15 * k, y + 10 * k, 15, 10, mouse.LEFT, key.MOD_CTRL)
        frames(w)
    frames(w, 90)
    v.join_physics()
    target = grab.spring.target
    pull = target - held
    moved = sim.world.bodies.position[top] - start
    assert moved @ pull / (pull @ pull) > 0.7, moved            # it went with the cursor
    # the held point follows the cursor: within the sag under its weight, g/ω² = 6.8 cm
    assert np.linalg.norm(grab.spring.point(sim.world) - target) < 0.12
    assert _turned_deg(q0, sim.world.bodies.orientation[top]) > 10.0   # held off-centre
    assert len(v.mouse.extra_lines()) == 1
    send(w, "on_mouse_release", x + 150, y + 100, mouse.LEFT, key.MOD_CTRL)
    assert v.mouse.grab is None and v.mouse.extra_lines() == []
    assert not sim.world.body_forces


def _grab_run(open_viewer, *, overlap: bool) -> pm.Probe:
    """The box tower in a window with irregular frames; the top box grabbed at frame 5,
    dragged for 20 frames, let go at frame 40; returns the bodies' recorded states."""
    from pyglet.window import key, mouse

    sim = pm.Simulation("box_tower", overrides=["count=4"])
    probe = sim.add_probe(pm.Probe(position=lambda w: w.bodies.position.copy(),
                                   orientation=lambda w: w.bodies.orientation.copy()))
    w = open_viewer(sim, paused=False)
    w.viewer.overlap = overlap
    # Steps past the frame's wall-clock budget are dropped (slow motion), and a frame that
    # compiles a kernel runs past it: the trajectory would depend on the machine's timing.
    w.viewer.physics_budget = None
    press_key(w, "TAB")
    rng = np.random.default_rng(3)
    x = y = 0
    for frame in range(60):
        w.dispatch_events()
        if frame == 5:
            x, y = _press_on_top_box(w, sim)
            assert w.viewer.mouse.grab is not None
        elif 5 < frame <= 25:
            x, y = x + 6, y + 4
            send(w, "on_mouse_drag", x, y, 6, 4, mouse.LEFT, key.MOD_CTRL)
        elif frame == 40:
            send(w, "on_mouse_release", x, y, mouse.LEFT, key.MOD_CTRL)
        w.tick(float(rng.uniform(0.005, 0.04)))
    w.viewer.join_physics()
    w.switch_to()
    assert w.ctx.error == "GL_NO_ERROR"
    w.close()                                    # one ImGui context at a time
    return probe


def test_a_grab_takes_the_same_trajectory_with_overlap_on_and_off(open_viewer):
    on, off = (_grab_run(open_viewer, overlap=overlap) for overlap in (True, False))
    steps = min(len(on), len(off))
    assert steps > 60 and len(on) == len(off)
    for name in ("position", "orientation"):
        assert np.array_equal(on[name][:steps], off[name][:steps]), name
    moved = np.linalg.norm(on["position"][-1][-1] - on["position"][0][-1])
    assert moved > 0.3                           # the grab did move the top box


def test_ctrl_click_on_a_static_body_says_it_is_fixed(open_viewer):
    from pyglet.window import key, mouse

    from pointmass.rigid.shapes import Box

    sim = pm.Simulation("box_tower", overrides=["count=2"])
    wall = sim.world.add_body(Box((0.4, 0.4, 0.4)), (0.0, 3.0, 0.0), mass=math.inf)
    w = open_viewer(sim, paused=True)
    press_key(w, "TAB")
    frames(w, 2)
    v = w.viewer
    px, py = v.camera.project(wall.position[None], v.renderer.size)[0]
    x, y = to_window(w, px, py)
    send(w, "on_mouse_press", x, y, mouse.LEFT, key.MOD_CTRL)
    send(w, "on_mouse_release", x, y, mouse.LEFT, key.MOD_CTRL)
    frames(w, 2)
    assert v.mouse.grab is None and not sim.world.body_forces
    assert v.messages[-1] == f"body {wall.index} is fixed in place: it cannot be grabbed"
