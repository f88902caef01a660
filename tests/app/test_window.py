"""A real pyglet window (under Xvfb), driven by dispatched events and ``tick`` a fixed number of
times (never ``pyglet.app.run``)."""

from __future__ import annotations

import numpy as np
import pytest

pytestmark = pytest.mark.window

DT = 1 / 60


def frames(window, n: int = 1) -> None:
    for _ in range(n):
        window.dispatch_events()
        window.tick(DT)


def press_key(window, name: str, modifiers: int = 0) -> None:
    from pyglet.window import key

    symbol = getattr(key, name)
    window.dispatch_event("on_key_press", symbol, modifiers)
    window.dispatch_event("on_key_release", symbol, modifiers)
    window.dispatch_pending_events()   # pyglet queues dispatched events until then


def send(window, event: str, *args) -> None:
    window.dispatch_event(event, *args)
    window.dispatch_pending_events()


def to_window(window, px: float, py: float) -> tuple[int, int]:
    """Framebuffer pixels (top-left origin) to pyglet window points (bottom-left origin)."""
    w, h = window.get_size()
    fw, fh = window.get_framebuffer_size()
    return round(px * w / fw), round(h - py * h / fh)


def test_pause_single_step_and_resume(open_viewer, sim):
    w = open_viewer(sim, paused=True)
    frames(w, 5)
    assert sim.scene.time == 0.0
    press_key(w, "RIGHT")
    frames(w, 3)
    assert sim.scene.time == pytest.approx(sim.scene.dt)
    press_key(w, "P")                          # the demo took SPACE (fire); P still pauses
    frames(w, 6)
    assert sim.scene.time == pytest.approx(sim.scene.dt * 13, abs=sim.scene.dt * 1.01)
    press_key(w, "SPACE")
    assert sim.scene.handles["fired"] == 1
    assert not w.viewer.clock.paused


def test_keys_time_scale_reset_panel_contacts(open_viewer, sim):
    w = open_viewer(sim, paused=False)
    frames(w, 10)
    press_key(w, "MINUS")
    assert w.viewer.clock.time_scale == 0.5
    press_key(w, "EQUAL")
    press_key(w, "EQUAL")
    assert w.viewer.clock.time_scale == 2.0
    press_key(w, "BACKSPACE")
    assert sim.scene.time == 0.0
    press_key(w, "TAB")
    press_key(w, "C")
    press_key(w, "F1")
    frames(w, 2)
    assert (w.viewer.show_panel, w.viewer.show_contacts, w.viewer.show_help) == (
        False, True, True)


def test_world_settings_from_the_panel_survive_a_reset(open_viewer, sim):
    """Gravity, substeps and restitution set in the panel are kept when R rebuilds the scene."""
    w = open_viewer(sim, paused=False)
    frames(w, 3)
    w.viewer.set_world("gravity", (0.0, -3.0, 0.0))
    w.viewer.set_world("substeps", 3)
    w.viewer.set_world(("restitution", 0), 0.9)
    press_key(w, "R")
    frames(w, 2)
    world = sim.scene.world
    assert np.array_equal(world.gravity, [0.0, -3.0, 0.0])
    assert world.substeps == 3
    assert world.contact_generators[0].restitution == 0.9


def test_slider_drag_changes_a_parameter_and_rebuilds_the_scene(open_viewer, sim):
    w = open_viewer(sim)
    frames(w, 3)
    x0, y0, x1, y1 = w.viewer.panel.rects["count"]
    cy = (y0 + y1) / 2
    h = w.get_size()[1]
    before = sim.scene
    send(w, "on_mouse_motion", x0 + 3, h - cy, 0, 0)
    frames(w, 2)
    send(w, "on_mouse_press", x0 + 3, h - cy, 1, 0)
    frames(w, 2)
    send(w, "on_mouse_drag", x1 - 2, h - cy, x1 - x0 - 5, 0, 1, 0)
    frames(w, 2)
    assert sim.params.count == 3 and sim.scene is before        # rebuilds on release only
    send(w, "on_mouse_release", x1 - 2, h - cy, 1, 0)
    frames(w, 3)
    assert sim.params.count == 20
    assert sim.scene is not before and sim.scene.world.particles.count == 20
    assert w.viewer.camera.yaw == pytest.approx(sim.scene.camera.yaw)   # the panel ate it


def test_live_slider_applies_at_once(open_viewer, sim):
    w = open_viewer(sim)
    frames(w, 3)
    x0, y0, _x1, y1 = w.viewer.panel.rects["bounce"]
    cy, h = (y0 + y1) / 2, w.get_size()[1]
    send(w, "on_mouse_motion", x0 + 3, h - cy, 0, 0)
    frames(w, 2)
    send(w, "on_mouse_press", x0 + 3, h - cy, 1, 0)
    frames(w, 2)
    assert sim.params.bounce == pytest.approx(0.0, abs=0.02)
    assert sim.scene.handles["ground"].restitution == sim.params.bounce
    send(w, "on_mouse_release", x0 + 3, h - cy, 1, 0)
    frames(w, 2)


def test_ctrl_drag_pulls_a_particle(open_viewer, sim):
    from pyglet.window import key, mouse

    w = open_viewer(sim, paused=False)
    press_key(w, "TAB")                         # panel away: the particle is in the clear
    frames(w, 30)                               # let the balls settle on the ground
    v = w.viewer
    pos = sim.scene.world.particles.position[2].copy()
    px, py = v.camera.project(pos[None], v.renderer.size)[0]
    x, y = to_window(w, px, py)
    send(w, "on_mouse_motion", x, y, 0, 0)
    send(w, "on_mouse_press", x, y, mouse.LEFT, key.MOD_CTRL)
    assert v.mouse.grab is not None and v.mouse.grab.index == 2
    yaw = v.camera.yaw
    for k in range(1, 11):                       # drag 120 px up, in steps, as a hand would
        send(w, "on_mouse_drag", x, y + 12 * k, 0, 12, mouse.LEFT, key.MOD_CTRL)
        frames(w)
    frames(w, 60)
    assert len(v.mouse.extra_lines()) == 1
    lifted = sim.scene.world.particles.position[2]
    assert lifted[1] > pos[1] + 0.5, lifted
    assert v.camera.yaw == yaw                   # a grab does not orbit
    send(w, "on_mouse_release", x, y + 120, mouse.LEFT, key.MOD_CTRL)
    assert v.mouse.grab is None and v.mouse.extra_lines() == []


def test_drag_on_the_scene_orbits_and_wheel_zooms(open_viewer, sim):
    w = open_viewer(sim)
    frames(w, 2)
    v = w.viewer
    yaw, distance = v.camera.yaw, v.camera.distance
    send(w, "on_mouse_motion", 600, 250, 0, 0)
    frames(w, 2)
    send(w, "on_mouse_press", 600, 250, 1, 0)
    send(w, "on_mouse_drag", 650, 250, 50, 0, 1, 0)
    send(w, "on_mouse_release", 650, 250, 1, 0)
    send(w, "on_mouse_scroll", 600, 250, 0, 1)
    frames(w)
    assert v.camera.yaw != yaw and v.camera.distance < distance


def test_screenshot_matches_the_offscreen_render(open_viewer, sim, in_egl, tmp_path):
    from PIL import Image

    from pointmass.render import Renderer

    w = open_viewer(sim, paused=True)
    press_key(w, "RIGHT")
    frames(w, 3)
    press_key(w, "P", modifiers=2)              # Ctrl+P (MOD_CTRL == 2)
    shots = list(tmp_path.glob("*.png"))
    assert len(shots) == 1
    shot = np.asarray(Image.open(shots[0]).convert("RGB"))
    size = w.viewer.renderer.size
    assert shot.shape == (size[1], size[0], 3)
    camera = w.viewer.camera

    def offscreen(ctx):
        r = Renderer(ctx, size)
        r.render(sim.scene, camera, trails=sim.trails)
        rgb = r.read_rgb()
        r.release()
        return rgb

    want = in_egl(offscreen)
    diff = np.abs(shot.astype(np.int16) - want.astype(np.int16))
    assert diff.mean() < 1.0
    assert (diff.max(axis=2) > 24).mean() < 0.005


def test_v_records_an_mp4_of_the_view(open_viewer, sim, tmp_path):
    import av

    w = open_viewer(sim, paused=False)
    press_key(w, "V")
    assert w.viewer.recording
    frames(w, 20)                                # 1/3 s of simulated time at 30 fps: ~10
    press_key(w, "V")
    assert not w.viewer.recording
    videos = list(tmp_path.glob("*.mp4"))
    assert len(videos) == 1
    with av.open(str(videos[0])) as c:
        count = sum(1 for _ in c.decode(video=0))
    assert 9 <= count <= 12


def test_escape_closes_without_gl_errors(open_viewer, sim):
    from imgui_bundle import imgui

    w = open_viewer(sim)
    frames(w, 2)
    assert w.ctx.error == "GL_NO_ERROR"
    press_key(w, "ESCAPE")
    assert w.viewer is None
    assert imgui.get_current_context() is None


def test_show_wraps_a_bare_scene_and_reset_restores_it(open_viewer):
    from pointmass import Ground, Scene, Simulation, World

    world = World()
    world.add_particle((0, 2, 0), mass=1.0, radius=0.2)
    world.add(Ground())
    sim = Simulation(Scene(world))
    w = open_viewer(sim, paused=False)
    frames(w, 20)
    assert world.particles.position[0, 1] < 2.0
    press_key(w, "R")
    assert world.particles.position[0, 1] == 2.0 and sim.time == 0.0
    frames(w, 2)


def _view_width(w) -> int:
    return w.get_framebuffer_size()[0] - w.viewer.view_x


def test_resize_follows_the_framebuffer(open_viewer, sim):
    """The 3D view is the framebuffer less the panel's span, and follows a resize."""
    w = open_viewer(sim)
    frames(w, 2)
    w.set_size(800, 400)
    for _ in range(20):                          # the X server answers asynchronously
        frames(w)
        if tuple(w.get_framebuffer_size()) == (800, 400):
            break
    frames(w)
    assert w.viewer.renderer.size == (_view_width(w), w.get_framebuffer_size()[1])


def test_the_scene_is_never_under_the_panel(open_viewer, sim):
    """With the panel open the 3D view is drawn right of it (its own viewport), and takes the
    whole window when Tab hides the panel; clicks land in the view's own pixels."""
    from pointmass.app.panel import PANEL_SPAN

    w = open_viewer(sim)
    frames(w, 2)
    v = w.viewer
    fw, fh = w.get_framebuffer_size()
    assert v.view_x == round(PANEL_SPAN * fw / w.get_size()[0]) > 0
    assert v.renderer.size == (fw - v.view_x, fh)
    assert v.to_view(v.view_x + 10, 20) == (10, 20)
    press_key(w, "TAB")
    frames(w)
    assert v.view_x == 0 and v.renderer.size == (fw, fh)


def test_opens_after_an_offscreen_render_on_this_thread(open_viewer, sim):
    """A notebook renders a clip (EGL, current on the main thread), then calls show()."""
    from pointmass.render import create_headless_context

    try:
        egl = create_headless_context()
    except Exception as exc:
        pytest.skip(f"no EGL: {exc}")
    try:
        w = open_viewer(sim)
        frames(w, 2)
        assert w.ctx.error == "GL_NO_ERROR"
    finally:
        w.close()
        egl.release()


def test_f_frames_every_particle(open_viewer, sim):
    """F points the camera at the centre of all the particles, keeping its direction, so a
    view that has wandered off brings the scene back."""
    import numpy as np

    w = open_viewer(sim, paused=True)
    frames(w, 2)
    camera = w.viewer.camera
    yaw, pitch = camera.yaw, camera.pitch
    camera.target = np.array([500.0, 0.0, 500.0])
    press_key(w, "F")
    p = sim.scene.world.particles
    low = (p.position - p.radius[:, None]).min(axis=0)
    high = (p.position + p.radius[:, None]).max(axis=0)
    assert np.allclose(camera.target, (low + high) / 2)
    assert (camera.yaw, camera.pitch) == (yaw, pitch)
    size = w.viewer.renderer.size
    pts = camera.project(p.position, size)
    assert ((pts >= 0) & (pts <= np.array(size))).all()
