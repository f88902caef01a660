"""The viewer's state and per-frame work, without pyglet: time stepping, drawing the scene into
the renderer's framebuffer, the panel, keys and captures. ``window.py`` feeds it events.

One frame is ``update(real_dt)`` (the playback clock turns real time into simulated seconds and
``Simulation.advance`` into fixed steps) and then ``draw(screen)`` (scene into the offscreen
FBO, blitted to ``screen``, panel on top). Drawing never steps physics. The live plots read a
``Probe`` the viewer adds to the Simulation: the same object a notebook would plot.

Overlap (on by default; ``Viewer(overlap=False)`` or ``POINTMASS_OVERLAP=0`` turns it off):
``update`` only works out the steps the frame owes, and ``draw`` builds the panel (which reads
and may change the simulation), captures what the renderer reads (``FrameState``), and then
runs those steps in one worker thread while it draws the capture: the picture is the state
before the frame's steps, one frame behind the physics. The step's numba kernels release the
GIL, so the two share the cores. Everything that touches the simulation — the next ``update``,
keys, mouse, panel changes, reset, close — first waits for the worker (``join_physics``); no
lock is held while drawing. The steps and their order are those of stepping in line, so the
trajectory is bit for bit the same (tests/app/test_overlap.py).
"""

from __future__ import annotations

import os
import sys
import time
from concurrent.futures import Future
from concurrent.futures import wait as wait_futures
from pathlib import Path

import numpy as np
from imgui_bundle import imgui, implot

from .. import compiling
from ..probes import Probe
from ..render import OrbitCamera, Renderer
from ..worker import Worker
from . import glwait
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
        overlap: Step the frame's physics in a worker thread while drawing (default: on,
            unless the environment sets ``POINTMASS_OVERLAP=0``).
    """

    def __init__(self, ctx, sim, size: tuple[int, int], *, paused: bool = False,
                 output_dir: Path | str = ".", stem: str = "pointmass",
                 overlap: bool | None = None) -> None:
        self.ctx, self.sim = ctx, sim
        self.overlap = overlap_default() if overlap is None else bool(overlap)
        #: The one worker thread (a daemon: Ctrl-C during a compile in it ends the process at
        #: once), its running job, and the steps the next draw runs in it.
        self._worker: Worker | None = None
        self._running: Future | None = None
        self._due: tuple[float, int, float] | None = None
        self._running_due = self._due
        #: Seconds the last joined frame's steps took (in the worker with overlap), and how
        #: many steps they were.
        self.physics_seconds, self.physics_steps = 0.0, 0
        #: Main-thread seconds the last frame spent drawing (capture, render, blit, panel).
        self.draw_seconds = 0.0
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
        #: Seconds of physics one frame may spend before it drops the steps it still owes
        #: (None: no limit).
        self.physics_budget = 0.05
        #: World settings changed in the panel, re-applied after every reset or rebuild.
        self.world_overrides: dict = {}
        self.probe: Probe | None = None
        self._watch()
        #: While numba compiles in the worker, draw a notice and leave the worker be instead of
        #: waiting for it (the window's event loop turns this on; tests that drive frames
        #: themselves keep waiting, so each frame's steps are done when it returns).
        self.detach_compiles = False
        #: The job compiling the kernels the drawing calls (``start_warmup``), until done.
        self._warming: Future | None = None
        self._warming_since = 0.0
        #: What the worker is doing while the notice shows: "compiling" or "loading".
        self.notice_kind = "compiling"
        #: When the compile notice first showed (perf_counter seconds), while it shows.
        self._notice_since: float | None = None
        #: The compile notice as last drawn (tests read it).
        self.last_notice = ""
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
        """Work out the physics steps this frame owes. In line (``overlap`` off) they run here
        and the count is returned; with overlap the following ``draw`` runs them beside the
        drawing and this returns 0 (the stats count them when they are joined)."""
        if self.compiling() is not None:
            return 0                     # the worker compiles: no new steps owed meanwhile
        self.join_physics()
        if self._due is not None:        # an update with no draw since: run its steps now
            self._finish(*self._due, *self._physics(*self._due[:2]))
            self._due = None
        clock = self.clock
        if clock.paused:
            due = (0.0, clock.take_single_steps(), real_dt)
        else:
            due = (clock.seconds(real_dt), 0, real_dt)
        if self.overlap:
            self._due = due
            return 0
        if self.detach_compiles:         # in the worker, so a compile leaves the window live
            self._due = due
            self._start_physics()
            if self.compiling() is not None:
                return 0
            running = self._running
            self.join_physics()
            return self.physics_steps if running is not None else 0
        steps, physics = self._physics(*due[:2])
        self._finish(*due, steps, physics)
        return steps

    def _physics(self, seconds: float, single: int) -> tuple[int, float]:
        """Run a frame's steps (``seconds`` of playback, or ``single`` steps while paused);
        returns the steps and the seconds they took. In the worker thread with overlap."""
        sim = self.sim
        t0 = time.perf_counter()
        if single:
            for _ in range(single):
                sim.step()
            steps = single
        else:
            # Capped in steps and in time: big scenes stay interactive (slow motion instead).
            steps = sim.advance(seconds, max_steps=self.clock.max_steps,
                                max_wall_seconds=self.physics_budget)
        return steps, time.perf_counter() - t0

    def _finish(self, seconds: float, single: int, real_dt: float, steps: int,
                physics: float) -> None:
        self.physics_seconds, self.physics_steps = physics, steps
        self.stats.frame(real_dt, steps * self.sim.dt, steps, physics)

    def _start_physics(self) -> None:
        """Start the steps ``update`` left for this frame in the worker thread."""
        due, self._due = self._due, None
        if due is None:
            return
        if not (due[0] > 0 or due[1]):             # paused: nothing to run
            self._finish(*due, 0, 0.0)
            return
        if self._worker is None:
            self._worker = Worker("pointmass-physics")
        self._running, self._running_due = self._worker.submit(self._physics, *due[:2]), due

    def join_physics(self) -> None:
        """Wait for the worker's steps, if any run (before anything touches the simulation);
        an error raised in a step is raised here."""
        running, self._running = self._running, None
        if running is not None:
            steps, physics = running.result()
            self._finish(*self._running_due, steps, physics)

    @property
    def physics_running(self) -> bool:
        return self._running is not None

    def compiling(self) -> float | None:
        """Seconds numba has been compiling for the worker, when the window shows a notice
        instead of waiting for it (``detach_compiles``); else None. Waits for a frame's steps
        while no compile runs (the usual few milliseconds); never for the first job
        (``start_warmup``): numba's own start-up and its cache loads run outside its compile
        events, and waiting through them froze the window for seconds ("loading" then)."""
        self.notice_kind = "compiling"
        if not self.detach_compiles:
            return None
        warming = self._warming
        if warming is not None and not warming.done():
            seconds = compiling.elapsed()
            if seconds is None:
                self.notice_kind = "loading"
                return time.perf_counter() - self._warming_since
            return seconds
        running = self._running
        while running is not None and not running.done():
            seconds = compiling.elapsed()
            if seconds is not None:
                return seconds
            wait_futures([running], timeout=0.02)
        if warming is not None:
            self._warming = None
            warming.result()                # an error in it is raised here
        return None

    def start_warmup(self) -> None:
        """Compile, in the worker, the kernels the main thread calls while drawing (the
        panel's energies, the blob shadows), so the first frames show a notice instead of
        freezing, and a signal is handled at once (it waits while the main thread compiles)."""
        if self._worker is None:
            self._worker = Worker("pointmass-physics")
        self._warming_since = time.perf_counter()
        self._warming = self._worker.submit(warm_drawing, self.sim)

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
        """The panel, then the scene into the FBO, copied to ``screen``, the panel over it.

        With overlap the frame's steps run in the worker from the capture of the scene to the
        next ``join_physics``; the panel is built before, as it reads the simulation (and a
        slider or Reset changes it)."""
        seconds = self.compiling()
        if seconds is not None:
            # The steps this frame's update owed are dropped, not left for the next update,
            # which would run them in line, here in the main thread: a compile there froze
            # the window (and held off signals) until it ended.
            self._due = None
            self._draw_compiling(screen, seconds)
            return
        self._notice_since = None
        self.join_physics()
        t0 = time.perf_counter()
        imgui.new_frame()
        self.panel.draw(self, show_panel=self.show_panel)
        self._draw_overlay()
        imgui.render()
        gui = time.perf_counter() - t0
        r, sim = self.renderer, self.sim
        self.camera.track(sim.scene)
        frame = r.capture(sim.scene, trails=sim.trails, show_contacts=self.show_contacts,
                          extra_lines=self.mouse.extra_lines())
        self._start_physics()               # the simulation is not touched from here on
        r.draw(frame, self.camera)
        if self._running is not None:
            glwait.finish()                 # rasterize with the GIL free for the worker
        if self.recorder is not None:
            self.recorder.offer(r, frame.time)
            if self.recorder.error is not None:
                self.stop_recording()
        screen.use()
        screen.clear(*_BEHIND_PANEL)
        self.blitter.draw(r.color_texture, screen, x=self.view_x)
        t1 = time.perf_counter()
        self.gui.render(imgui.get_draw_data())
        t2 = time.perf_counter()
        self.stats.gui_ms = 1e3 * (gui + t2 - t1)
        self.draw_seconds = t2 - t0

    def overlay_text(self) -> list[str]:
        """The lines drawn over the scene now: the demo's hint until the first demo key or
        click (what to do, e.g. "Click or press SPACE to fire")."""
        hint = self.sim.hint
        return [hint] if hint and self.sim.presses == 0 else []

    def _draw_overlay(self) -> None:
        """The overlay lines in a small box at the bottom centre of the 3D view."""
        lines = self.overlay_text()
        if not lines:
            return
        io = imgui.get_io()
        left = self.view_x / max(self.pixel_ratio, 1e-9)     # the 3D view's left edge [points]
        x = (left + io.display_size.x) / 2
        imgui.set_next_window_pos(imgui.ImVec2(x, io.display_size.y - 24), imgui.Cond_.always,
                                  imgui.ImVec2(0.5, 1.0))
        imgui.set_next_window_bg_alpha(0.6)
        flags = (imgui.WindowFlags_.no_decoration | imgui.WindowFlags_.always_auto_resize
                 | imgui.WindowFlags_.no_inputs | imgui.WindowFlags_.no_saved_settings
                 | imgui.WindowFlags_.no_focus_on_appearing | imgui.WindowFlags_.no_nav)
        imgui.begin("##hint", None, flags)
        for line in lines:
            imgui.text(line)
        imgui.end()

    def _draw_compiling(self, screen, seconds: float) -> None:
        """While the worker compiles: the last picture of the scene, the notice over it. The
        panel is left out: it reads the simulation, which the worker is stepping."""
        imgui.new_frame()
        io = imgui.get_io()
        left = self.view_x / max(self.pixel_ratio, 1e-9)     # the 3D view's left edge [points]
        imgui.set_next_window_pos(imgui.ImVec2((left + io.display_size.x) / 2,
                                               io.display_size.y / 2),
                                  imgui.Cond_.always, imgui.ImVec2(0.5, 0.5))
        flags = (imgui.WindowFlags_.no_decoration | imgui.WindowFlags_.always_auto_resize
                 | imgui.WindowFlags_.no_inputs | imgui.WindowFlags_.no_saved_settings)
        imgui.begin("##compiling", None, flags)
        # Seconds since the notice first showed (numba's bursts restart between kernels).
        if self._notice_since is None:
            self._notice_since = time.perf_counter() - seconds
        shown = time.perf_counter() - self._notice_since
        self.last_notice = compiling.notice(shown, ellipsis="...").capitalize() \
            if self.notice_kind == "compiling" else "Loading physics kernels ..."
        imgui.text(self.last_notice)
        imgui.text_disabled("numba turns the physics into machine code once; later runs load "
                            "it from the cache.")
        imgui.end()
        imgui.render()
        screen.use()
        screen.clear(*_BEHIND_PANEL)
        self.blitter.draw(self.renderer.color_texture, screen, x=self.view_x)
        self.gui.render(imgui.get_draw_data())

    def resize(self, size: tuple[int, int], pixel_ratio: float | None = None) -> None:
        if size[0] > 0 and size[1] > 0:
            self.window_size = tuple(size)
            if pixel_ratio is not None:
                self.pixel_ratio = pixel_ratio
            self._layout()

    # -- actions (keys, panel buttons) ----------------------------------------------------------
    def key(self, name: str, *, ctrl: bool = False) -> str | None:
        """A key press by name; returns the action or demo key it triggered."""
        self.join_physics()
        action = self.keymap.resolve(name, ctrl=ctrl)
        if action.kind == "demo":
            self.sim.press(action.name)
            return action.name
        if action.kind == "action":
            self.act(action.name)
            return action.name
        return None

    def act(self, action: str) -> None:
        self.join_physics()
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
        self.join_physics()
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
        self.join_physics()
        before = self.sim.scene
        self.sim.set_param(name, value)
        if self.sim.scene is not before:
            self.mouse.end_grab()
            self._after_rebuild()

    def set_world(self, name, value) -> None:
        """From the panel: change a world setting (a name, or ("restitution", generator index))
        and remember it, so a reset or a rebuild keeps what the user chose."""
        self.join_physics()
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
        path = recorder.close(self.renderer)
        self._say(f"saved {path}" if recorder.error is None
                  else f"recording failed: {recorder.error}")
        return path

    def _say(self, text: str) -> None:
        """Tell the user (the panel shows the last message; the terminal gets them all)."""
        self.messages.append(text)
        print(f"pointmass: {text}", file=sys.stderr)

    def close(self, *, wait: bool = True) -> None:
        """Wait for the worker (unless ``wait`` is False: the process is ending, and a compile
        there may take a minute), finish a recording, free GL objects, destroy the ImGui
        contexts."""
        try:
            if wait:
                self.join_physics()
            else:
                self._running = None
        finally:
            if self._worker is not None:
                self._worker.shutdown()
                self._worker = None
            self._release()

    def _release(self) -> None:
        self.stop_recording()
        self.mouse.end_grab()
        self.gui.release()
        self.blitter.release()
        self.renderer.release()
        implot.destroy_context(self.implot_ctx)
        imgui.destroy_context(self.imgui_ctx)


def warm_drawing(sim) -> None:
    """Call, once, the numba kernels drawing a frame calls (compiled or loaded from the cache
    here, in the worker, not in the main thread)."""
    world = sim.scene.world
    world.kinetic_energy()
    world.potential_energy()
    from ..render import shadow_splat

    shadow_splat.warm()


def overlap_default() -> bool:
    """Overlap physics with drawing unless ``POINTMASS_OVERLAP`` is 0 (or off, false, no)."""
    return os.environ.get("POINTMASS_OVERLAP", "1").strip().lower() not in ("0", "off",
                                                                          "false", "no")
