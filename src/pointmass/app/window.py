"""The pyglet window: a GL 3.3 context for moderngl, events routed to ImGui and the viewer.

Event routing: every mouse and key event goes to ImGui first (it keeps its own input state);
the scene gets it only when ImGui does not want it (``io.want_capture_mouse`` /
``want_capture_keyboard``). A drag belongs to whoever got its press, so a slider drag that leaves
the panel does not orbit the camera, and an orbit that crosses the panel keeps orbiting.

Sizes: the renderer, viewport and blit use ``get_framebuffer_size()`` (pixels), mouse events come
in window points, scaled by framebuffer/window size (HiDPI).
"""

from __future__ import annotations

import sys
import time

import moderngl
import pyglet
from imgui_bundle import imgui
from pyglet.window import key, mouse

from .glcurrent import release_current_egl
from .imgui_input import PygletImguiInput
from .keymap import key_name
from .viewer import Viewer

_BUTTONS = {mouse.LEFT: "left", mouse.RIGHT: "right", mouse.MIDDLE: "middle"}
#: Seconds the event loop rests each frame while numba compiles in the physics worker.
COMPILING_FRAME_PAUSE = 0.1


class ViewerWindow(pyglet.window.Window):
    """A window on a simulation. Use ``run()`` for the event loop, or drive it yourself with
    ``tick(real_dt)`` (tests and benchmarks do, with dispatched events)."""

    viewer: Viewer | None = None        # None before the GL set-up and after close

    def __init__(self, sim, *, title: str = "pointmass", size=(1280, 720), paused=False,
                 output_dir=".", visible=True, overlap: bool | None = None) -> None:
        config = pyglet.gl.Config(major_version=3, minor_version=3, forward_compatible=True,
                                  double_buffer=True, depth_size=24)
        if sys.platform.startswith("linux"):
            # An earlier offscreen render's EGL context, if any, let go of *before* pyglet
            # makes its window: pyglet's own set-up calls (its shader programs, the window's
            # uniform buffer) otherwise land in the EGL context, and whether their names exist
            # in the window's context then depends on what that EGL context made (a render on
            # the hardware path before a window: GL_INVALID_OPERATION at the first resize).
            release_current_egl()
        super().__init__(size[0], size[1], caption=title, resizable=True, config=config,
                         visible=visible, vsync=False)
        self.switch_to()
        self.ctx = moderngl.create_context()
        self.gl_screen = self.ctx.detect_framebuffer(0)
        stem = "pointmass-" + getattr(getattr(sim, "demo", None), "name", "scene")
        self.viewer = Viewer(self.ctx, sim, self.get_framebuffer_size(), paused=paused,
                             output_dir=output_dir, stem=stem, overlap=overlap)
        self.imgui_input = PygletImguiInput(self)
        self._mouse_owner: str | None = None        # "gui" or "scene" while a button is down
        self._last = None
        #: Steps the worker was still compiling when the window closed (``show`` waits for
        #: them before handing the simulation back; ``pointmass run`` just exits).
        self.left_running = None

    # -- the frame ------------------------------------------------------------------------------
    def tick(self, real_dt: float) -> None:
        """One whole frame: physics for ``real_dt`` real seconds, draw, flip (with overlap the
        physics runs beside the drawing and the flip; the frame ends when both are done)."""
        self.viewer.update(real_dt)
        self.switch_to()
        self.on_draw()
        self.flip()
        if self.viewer is not None and self.viewer.compiling() is None:
            self.viewer.join_physics()

    def _quiet(self) -> bool:
        """Before an event touches the viewer: False when closed, else wait for the physics
        worker (no event ever races it)."""
        if self.viewer is None or self.viewer.compiling() is not None:
            return False              # closed, or the worker compiles: the event is dropped
        self.viewer.join_physics()
        return True

    def on_draw(self) -> None:
        if self.viewer is None:
            return
        self.imgui_input.new_frame_time()
        self.viewer.draw(self.gl_screen)
        self.imgui_input.update_cursor()
        if self.viewer.closed:
            self.close()

    def _scheduled(self, _dt: float) -> None:
        now = time.perf_counter()
        real_dt = now - self._last if self._last is not None else 0.0
        self._last = now
        if self.viewer is not None:
            if self.viewer.compiling() is not None:
                # ~10 notice frames a second, not 60: the compile in the worker is Python
                # holding the GIL, and every frame drawn here takes it away (a sleep frees it;
                # a signal still interrupts it at once).
                time.sleep(COMPILING_FRAME_PAUSE)
            self.viewer.update(real_dt)  # pyglet.app then calls on_draw and flips

    def run(self) -> None:
        """The event loop: physics and drawing at the display rate (~60 Hz)."""
        if self.viewer is not None:
            self.viewer.detach_compiles = True  # a first step's compile: notice, not freeze
            self.viewer.start_warmup()
        pyglet.clock.schedule_interval(self._scheduled, 1 / 60)
        try:
            pyglet.app.run(1 / 60)
        except BaseException:
            # Ctrl-C (or an error): close without waiting for a compile in the worker.
            if self.viewer is not None:
                self.close()
            raise
        finally:
            pyglet.clock.unschedule(self._scheduled)

    # -- sizes ----------------------------------------------------------------------------------
    def _to_pixels(self, x: float, y: float) -> tuple[float, float]:
        """Window points (origin bottom-left) to framebuffer pixels (origin top-left)."""
        w, h = self.get_size()
        fw, fh = self.get_framebuffer_size()
        return x * fw / w, (h - y) * fh / h

    def on_resize(self, width: int, height: int) -> None:
        if self.viewer is None:
            return pyglet.event.EVENT_HANDLED
        self.imgui_input.sync_size()
        self.viewer.resize(self.get_framebuffer_size(),
                           self.get_framebuffer_size()[0] / max(self.get_size()[0], 1))
        self.gl_screen = self.ctx.detect_framebuffer(0)
        return pyglet.event.EVENT_HANDLED

    # -- mouse ----------------------------------------------------------------------------------
    def on_mouse_motion(self, x, y, dx, dy) -> None:
        if self.viewer is None:       # closed (ImGui only: no need to wait for the physics)
            return
        self.imgui_input.mouse_move(x, y)

    def on_mouse_press(self, x, y, button, modifiers) -> None:
        if not self._quiet():         # closed
            return
        self.imgui_input.mouse_button(x, y, button, True)
        if imgui.get_io().want_capture_mouse:
            self._mouse_owner = "gui"
            return
        self._mouse_owner = "scene"
        self.viewer.mouse.press(*self.viewer.to_view(*self._to_pixels(x, y)),
                                _BUTTONS.get(button, "left"),
                                shift=bool(modifiers & key.MOD_SHIFT),
                                ctrl=bool(modifiers & key.MOD_CTRL))

    def on_mouse_drag(self, x, y, dx, dy, buttons, modifiers) -> None:
        if not self._quiet():         # closed
            return
        self.imgui_input.mouse_move(x, y)
        if self._mouse_owner == "scene":
            px, py = self.viewer.to_view(*self._to_pixels(x, y))
            scale = self.get_framebuffer_size()[0] / self.get_size()[0]
            self.viewer.mouse.drag(px, py, dx * scale, -dy * scale)

    def on_mouse_release(self, x, y, button, modifiers) -> None:
        if not self._quiet():         # closed
            return
        self.imgui_input.mouse_button(x, y, button, False)
        owner, self._mouse_owner = self._mouse_owner, None
        if owner == "scene":
            self.viewer.mouse.release(*self.viewer.to_view(*self._to_pixels(x, y)),
                                      _BUTTONS.get(button, "left"))

    def on_mouse_scroll(self, x, y, scroll_x, scroll_y) -> None:
        if not self._quiet():         # closed
            return
        self.imgui_input.scroll(scroll_x, scroll_y)
        if not imgui.get_io().want_capture_mouse:
            self.viewer.mouse.scroll(scroll_y)

    # -- keys -----------------------------------------------------------------------------------
    def on_key_press(self, symbol, modifiers):
        if symbol == key.ESCAPE and self.viewer is not None \
                and self.viewer.compiling() is not None:
            self.close()              # Escape closes even while the first step compiles
            return pyglet.event.EVENT_HANDLED
        if not self._quiet():
            return pyglet.event.EVENT_HANDLED
        self.imgui_input.key_event(symbol, True)
        if imgui.get_io().want_capture_keyboard and symbol != key.ESCAPE:
            return pyglet.event.EVENT_HANDLED
        name = key_name(key.symbol_string(symbol))
        self.viewer.sim.keys_down.add(name)     # demos poll held keys (a WASD load)
        self.viewer.key(name, ctrl=bool(modifiers & key.MOD_CTRL))
        if self.viewer.closed:
            self.close()
        return pyglet.event.EVENT_HANDLED     # Escape must not close behind our back

    def on_key_release(self, symbol, modifiers) -> None:
        if not self._quiet():         # closed
            return
        self.imgui_input.key_event(symbol, False)
        self.viewer.sim.keys_down.discard(key_name(key.symbol_string(symbol)))

    def on_deactivate(self) -> None:
        if self._quiet():                     # releases happen elsewhere: forget held keys
            self.viewer.sim.keys_down.clear()

    def on_text(self, text) -> None:
        if self.viewer is None:       # closed (ImGui only: no need to wait for the physics)
            return
        self.imgui_input.text(text)

    def on_close(self) -> None:
        self.close()

    def close(self) -> None:
        if self.viewer is not None:
            self.switch_to()
            viewer, self.viewer = self.viewer, None
            if viewer.compiling() is not None:   # do not hold the window for the compile
                self.left_running = viewer._running
                viewer.close(wait=False)
            else:
                viewer.close()
        super().close()
