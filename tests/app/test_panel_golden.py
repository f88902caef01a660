"""The panel drawn headless (EGL + our ImGui renderer) against a golden image.

Fixed display size, frame time and statistics, so the image depends only on the code. Regenerate
with POINTMASS_UPDATE_GOLDENS=1 (and look at tests/golden/panel.png before committing it).
"""

from __future__ import annotations

import numpy as np
import pytest

SIZE = (380, 760)


class Host:
    """What the panel needs from the window, with fixed numbers."""

    def __init__(self, sim):
        from types import SimpleNamespace

        from pointmass import Probe
        from pointmass.app.clock import PlaybackClock
        from pointmass.app.keymap import KeyMap
        from pointmass.app.stats import FrameStats

        self.sim = sim
        self.clock = PlaybackClock()
        self.keymap = KeyMap(sim.demo.keys)
        self.stats = FrameStats()
        s = self.stats
        s.fps, s.realtime, s.step_ms, s.gui_ms = 60.0, 1.0, 0.25, 0.6
        # The live plots' probe, fed known curves (a fake world that only has a time).
        self.probe = Probe(kinetic=lambda w: 10 * np.exp(-w.time),
                           potential=lambda w: 10 - 10 * np.exp(-w.time),
                           **{"plot:v_y": lambda w: -5 * (1 - np.exp(-2 * w.time))})
        for k in range(120):
            self.probe.record(SimpleNamespace(time=k / 60))
        self.show_help = False
        self.recording = False
        self.calls = []

    def set_param(self, name, value):
        self.calls.append(("set", name, value))

    def act(self, action):
        self.calls.append(("act", action))


def draw_panel(ctx, host, frames: int = 3, *, help_too: bool = False,
               world_open: bool = False) -> np.ndarray:
    from imgui_bundle import imgui, implot

    from pointmass.app.imgui_renderer import ImguiRenderer
    from pointmass.app.panel import Panel

    imgui_ctx, implot_ctx = imgui.create_context(), implot.create_context()
    try:
        io = imgui.get_io()
        io.set_ini_filename(None)
        io.display_size = imgui.ImVec2(*SIZE)
        io.display_framebuffer_scale = imgui.ImVec2(1, 1)
        gui, panel = ImguiRenderer(ctx), Panel()
        panel.world_open = world_open
        fbo = ctx.simple_framebuffer(SIZE)
        host.show_help = help_too
        for _ in range(frames):             # windows settle their size over the first frames
            io.delta_time = 1 / 60
            fbo.use()
            fbo.clear(0.15, 0.16, 0.18, 1.0)
            imgui.new_frame()
            panel.draw(host)
            imgui.render()
            gui.render(imgui.get_draw_data())
        rgb = np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)
        gui.release()
        (ctx.screen or ctx.detect_framebuffer(0)).use()   # never release a bound framebuffer
        fbo.release()
        return rgb[::-1].copy()
    finally:
        implot.destroy_context(implot_ctx)
        imgui.destroy_context(imgui_ctx)


@pytest.mark.gl
def test_panel_matches_golden(in_egl, sim, golden):
    """The panel after 30 steps looks like tests/golden/panel.png."""
    for _ in range(30):
        sim.step()
    golden("panel", in_egl(lambda ctx: draw_panel(ctx, Host(sim))))


@pytest.mark.gl
def test_help_overlay_lists_demo_keys(in_egl, sim, golden):
    """The help overlay, with the demo's keys, over the panel with its World section open."""
    golden("panel_help", in_egl(lambda ctx: draw_panel(ctx, Host(sim), help_too=True,
                                                       world_open=True)))


@pytest.mark.gl
def test_imgui_context_is_gone_after_drawing(in_egl, sim):
    from imgui_bundle import imgui

    in_egl(lambda ctx: draw_panel(ctx, Host(sim), frames=1))
    assert imgui.get_current_context() is None
