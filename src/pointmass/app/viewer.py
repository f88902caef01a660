"""The viewer's state and per-frame work, without pyglet: time stepping, drawing the scene into
the renderer's framebuffer, the panel, keys and captures. ``window.py`` feeds it events.

One frame is ``update(real_dt)`` (the playback clock turns real time into simulated seconds and
``Simulation.advance`` into fixed steps) and then ``draw(screen)`` (scene into the offscreen
FBO, blitted to ``screen``, panel on top). Drawing never steps physics. The live plots read a
``Probe`` the viewer adds to the Simulation: the same object a notebook would plot.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
from imgui_bundle import imgui, implot

from ..probes import Probe
from ..render import OrbitCamera, Renderer
from .blit import Blitter
from .capture import ViewRecorder, save_png, timestamped
from .clock import PlaybackClock
from .imgui_renderer import ImguiRenderer
from .keymap import KeyMap
from .mouse import MouseControls
from .panel import PANEL_SPAN, Panel
from .stats import FrameStats

#: The window's colour where the panel stands (RGBA in [0, 1]).
_BEHIND_PANEL = (0.09, 0.10, 0.12, 1.0)
#: Simulated seconds the live plots show.
PLOT_SECONDS = 10.0


class Viewer:
    """A simulation on screen.

    Args:
        ctx: The moderngl context to draw with (the window's).
        sim: A ``pointmass.Simulation``.
        size: Framebuffer size (width, height) [px].
        paused: Start paused.
        output_dir: Where screenshots and videos go.
        stem: File name start for captures.
    """

    def __init__(self, ctx, sim, size: tuple[int, int], *, paused: bool = False,
                 output_dir: Path | str = ".", stem: str = "pointmass") -> None:
        self.ctx, self.sim = ctx, sim
        self.clock = PlaybackClock(paused=paused)
        self.camera = OrbitCamera.from_hint(sim.scene.camera)
        self.show_panel, self.show_help, self.show_contacts = True, False, False
        #: The window's framebuffer size [px] and its pixels per window point.
        self.window_size, self.pixel_ratio = tuple(size), 1.0
        self.renderer = Renderer(ctx, self._view_size())
        self.mouse = MouseControls(self.camera, sim, lambda: self.renderer.size,
                                   say=self._say)
        demo = getattr(sim, "demo", None)
        self.keymap = KeyMap(demo.keys if demo is not None else {})
        self.stats = FrameStats()
        self.panel = Panel()
        self.output_dir, self.stem = Path(output_dir), stem
        self.recorder: ViewRecorder | None = None
        self.messages: list[str] = []        # what happened (screenshot paths...), newest last
        self.closed = False
        #: Seconds of physics one frame may spend before it drops the steps it still owes.
        self.physics_budget = 0.05
        #: World settings changed in the panel, re-applied after every reset or rebuild.
        self.world_overrides: dict = {}
        self.probe: Probe | None = None
        self._watch()
        # ImGui contexts are global: one per viewer, destroyed in close() so tests do not leak.
        self.imgui_ctx = imgui.create_context()
        self.implot_ctx = implot.create_context()
        imgui.get_io().set_ini_filename(None)
        self.gui = ImguiRenderer(ctx)
        self.blitter = Blitter(ctx)

    # -- layout: the 3D view beside the panel, never under it ------------------------------------
    @property
    def view_x(self) -> int:
        """Left edge of the 3D view in the window [px]: right of the panel when it is shown."""
        return round(PANEL_SPAN * self.pixel_ratio) if self.show_panel else 0

    def _view_size(self) -> tuple[int, int]:
        w, h = self.window_size
        return max(16, w - self.view_x), h

    def to_view(self, x: float, y: float) -> tuple[float, float]:
        """Window pixels (origin top-left) to 3D-view pixels."""
        return x - self.view_x, y

    def _layout(self) -> None:
        if self.recorder is None:  # a recording keeps its frame size until it stops
            self.renderer.resize(self._view_size())

    @property
    def recording(self) -> bool:
        return self.recorder is not None

    # -- time -----------------------------------------------------------------------------------
    def update(self, real_dt: float) -> int:
        """Run the physics steps this frame owes; returns how many ran."""
        clock, sim = self.clock, self.sim
        t0 = time.perf_counter()
        if clock.paused:
            steps = clock.take_single_steps()
            for _ in range(steps):
                sim.step()
        else:
            # Capped in steps and in time: big scenes stay interactive (slow motion instead).
            steps = sim.advance(clock.seconds(real_dt), max_steps=clock.max_steps,
                                max_wall_seconds=self.physics_budget)
        physics = time.perf_counter() - t0
        self.stats.frame(real_dt, steps * sim.dt, steps, physics)
        return steps

    def _watch(self) -> None:
        """(Re)attach the live plots' probe: energies and the scene's own plot quantities."""
        sim = self.sim
        if self.probe is not None and self.probe in sim.probes:
            sim.remove_probe(self.probe)
        quantities = {"kinetic": lambda w: w.kinetic_energy(),
                      "potential": lambda w: w.potential_energy()}
        for name, fn in sim.scene.plots.items():
            quantities["plot:" + name] = lambda w, fn=fn: fn(sim.scene)
        samples = max(2, round(PLOT_SECONDS / sim.dt))
        self.probe = sim.add_probe(Probe(max_samples=samples, **quantities))

    # -- drawing --------------------------------------------------------------------------------
    def draw(self, screen) -> None:
        """Scene into the FBO, copied to ``screen``, the panel over it."""
        r = self.renderer
        self.camera.track(self.sim.scene)
        r.render(self.sim.scene, self.camera, trails=self.sim.trails,
                 show_contacts=self.show_contacts, extra_lines=self.mouse.extra_lines())
        if self.recorder is not None:
            self.recorder.offer(r.read_rgb, self.sim.time)
            if self.recorder.error is not None:
                self.stop_recording()
        screen.use()
        screen.clear(*_BEHIND_PANEL)
        self.blitter.draw(r.color_texture, screen, x=self.view_x)
        t0 = time.perf_counter()
        imgui.new_frame()
        self.panel.draw(self, show_panel=self.show_panel)
        imgui.render()
        self.gui.render(imgui.get_draw_data())
        self.stats.gui_ms = 1e3 * (time.perf_counter() - t0)

    def resize(self, size: tuple[int, int], pixel_ratio: float | None = None) -> None:
        if size[0] > 0 and size[1] > 0:
            self.window_size = tuple(size)
            if pixel_ratio is not None:
                self.pixel_ratio = pixel_ratio
            self._layout()

    # -- actions (keys, panel buttons) ----------------------------------------------------------
    def key(self, name: str, *, ctrl: bool = False) -> str | None:
        """A key press by name; returns the action or demo key it triggered."""
        action = self.keymap.resolve(name, ctrl=ctrl)
        if action.kind == "demo":
            self.sim.press(action.name)
            return action.name
        if action.kind == "action":
            self.act(action.name)
            return action.name
        return None

    def act(self, action: str) -> None:
        clock = self.clock
        if action == "pause":
            clock.toggle_pause()
        elif action == "step":
            clock.single_step()
        elif action == "reset":
            self.mouse.end_grab()
            self.sim.rebuild()
            self._after_rebuild()
        elif action == "slower":
            clock.slower()
        elif action == "faster":
            clock.faster()
        elif action == "screenshot":
            self.screenshot()
        elif action == "record":
            self.stop_recording() if self.recording else self.start_recording()
        elif action == "panel":
            self.show_panel = not self.show_panel
            self._layout()
        elif action == "contacts":
            self.show_contacts = not self.show_contacts
        elif action == "frame":
            self.frame_all()
        elif action == "help":
            self.show_help = not self.show_help
        elif action == "close":
            self.closed = True

    def frame_all(self) -> None:
        """Point the camera at every visible particle, keeping its direction (F, as in Blender
        and MuJoCo's viewer)."""
        from ..scene import CameraHint

        scene = self.sim.scene
        p = scene.world.particles
        shown = np.ones(p.count, bool) if scene.hidden is None else \
            ~np.asarray(scene.hidden, bool)[: p.count]
        cam = self.camera
        hint = CameraHint.framing(p.position[shown], p.radius[shown], fov=cam.fov)
        cam.target = np.array(hint.target, float)
        cam.distance = hint.distance

    def set_param(self, name: str, value) -> None:
        """From the panel: live parameters apply at once, rebuild ones rebuild the scene."""
        before = self.sim.scene
        self.sim.set_param(name, value)
        if self.sim.scene is not before:
            self.mouse.end_grab()
            self._after_rebuild()

    def set_world(self, name, value) -> None:
        """From the panel: change a world setting (a name, or ("restitution", generator index))
        and remember it, so a reset or a rebuild keeps what the user chose."""
        self.world_overrides[name] = value
        self._apply_world(name, value)

    def _apply_world(self, name, value) -> None:
        world = self.sim.scene.world
        if isinstance(name, tuple):  # ("restitution", i): one contact generator's
            generators = world.contact_generators
            if name[1] < len(generators) and hasattr(generators[name[1]], "restitution"):
                generators[name[1]].restitution = value
        else:
            setattr(world, name, value)

    def _after_rebuild(self) -> None:
        for name, value in self.world_overrides.items():
            self._apply_world(name, value)
        self.clock.reset()
        self._watch()

    # -- captures -------------------------------------------------------------------------------
    def screenshot(self, path: Path | None = None) -> Path:
        """Save the 3D view as it was last drawn (PNG)."""
        path = path or timestamped(self.output_dir, self.stem, ".png")
        save_png(self.renderer.read_rgb(), path)
        self._say(f"screenshot {path}")
        return path

    def start_recording(self, path: Path | None = None) -> None:
        path = path or timestamped(self.output_dir, self.stem, ".mp4")
        self.recorder = ViewRecorder(path, self.renderer.size)
        self._say(f"recording {path}")

    def stop_recording(self) -> Path | None:
        recorder, self.recorder = self.recorder, None
        if recorder is None:
            return None
        path = recorder.close()
        self._say(f"saved {path}" if recorder.error is None
                  else f"recording failed: {recorder.error}")
        return path

    def _say(self, text: str) -> None:
        """Tell the user (the panel shows the last message; the terminal gets them all)."""
        self.messages.append(text)
        print(f"pointmass: {text}", file=sys.stderr)

    def close(self) -> None:
        """Finish a recording, free GL objects, destroy the ImGui contexts."""
        self.stop_recording()
        self.mouse.end_grab()
        self.gui.release()
        self.blitter.release()
        self.renderer.release()
        implot.destroy_context(self.implot_ctx)
        imgui.destroy_context(self.imgui_ctx)
