"""The ImGui panel: the demo's parameters, world settings, statistics and a live plot, plus the
help overlay. It only *draws and reports*: changes go through its host (the window), which owns
the simulation, so a rebuild also cancels a grab and clears the plot.

The host provides: ``sim``, ``clock`` (PlaybackClock), ``stats`` (FrameStats), ``probe`` (the
live plots' Probe), ``keymap``, ``show_help``, ``recording``, ``set_param(name, value)`` and
``act(action)``.
"""

from __future__ import annotations

import numpy as np
from imgui_bundle import imgui, implot

from ..params import param_specs
from .keymap import MOUSE_HELP
from .stats import particle_count

PANEL_WIDTH = 360
#: Window points the panel takes from the left edge (its width and margins): the 3D view is
#: drawn to the right of it, so no part of the scene is ever under the panel.
PANEL_SPAN = PANEL_WIDTH + 16
RESOLVERS = ("sequential", "worst-first")
#: The live plots' heights [points] when the window has room, and the least they shrink to.
PLOT_HEIGHT, QUANTITY_PLOT_HEIGHT, MIN_PLOT_HEIGHT = 130.0, 140.0, 60.0
_OPEN = imgui.TreeNodeFlags_.default_open


class Panel:
    """Draws the panel each frame; keeps the values of rebuild sliders being dragged."""

    def __init__(self) -> None:
        self._pending: dict[str, object] = {}   # rebuild parameters applied on release
        self.world_open = False                 # open the World section at first
        self.rects: dict[str, tuple[float, float, float, float]] = {}
        """Where each parameter's widget was drawn last frame: (x0, y0, x1, y1) in window
        points, origin top-left (for tests that drag sliders)."""

    def draw(self, host, *, show_panel: bool = True) -> None:
        """Build this frame's ImGui windows (between ``new_frame`` and ``render``)."""
        if show_panel:
            io = imgui.get_io()
            imgui.set_next_window_pos(imgui.ImVec2(8, 8), imgui.Cond_.always)
            imgui.set_next_window_size(imgui.ImVec2(PANEL_WIDTH, io.display_size.y - 16),
                                       imgui.Cond_.always)
            imgui.begin("pointmass", None,
                        imgui.WindowFlags_.no_move | imgui.WindowFlags_.no_resize)
            imgui.push_item_width(-150)       # leave room for the labels on the right
            # Thin, translucent slider handles: ImGui's default 12 px block sits on the
            # centred value text and hides it whenever the value is mid-range.
            imgui.push_style_var(imgui.StyleVar_.grab_min_size, 4.0)
            imgui.push_style_color(imgui.Col_.slider_grab, imgui.ImVec4(0.45, 0.70, 1.0, 0.45))
            self._controls(host)
            if imgui.collapsing_header("Parameters", _OPEN):
                self._parameters(host)
            if imgui.collapsing_header("Statistics", _OPEN):
                self._statistics(host)
            if imgui.collapsing_header("Plots", _OPEN):
                self._plots(host)
            if self.world_open:
                imgui.set_next_item_open(True, imgui.Cond_.once)
            opened = imgui.collapsing_header("World")  # closed at first: less used
            lo, hi = imgui.get_item_rect_min(), imgui.get_item_rect_max()
            self.rects["header:World"] = (lo.x, lo.y, hi.x, hi.y)
            if opened:
                self._world(host)
            imgui.pop_style_color()
            imgui.pop_style_var()
            imgui.pop_item_width()
            imgui.end()
        if host.show_help:
            self._help(host)

    # -- sections -------------------------------------------------------------------------------
    def _controls(self, host) -> None:
        clock = host.clock
        if imgui.button("Resume" if clock.paused else "Pause"):
            host.act("pause")
        imgui.same_line()
        if imgui.button("Step"):
            host.act("step")
        imgui.same_line()
        if imgui.button("Reset"):
            host.act("reset")
        imgui.same_line()
        if imgui.button("Help"):
            host.act("help")
        if host.recording:
            imgui.same_line()
            imgui.text_colored(imgui.ImVec4(1, 0.3, 0.3, 1), "REC")
        messages = getattr(host, "messages", None)
        if messages:                       # the last screenshot or video path
            imgui.text_wrapped(messages[-1])

    def _parameters(self, host) -> None:
        params = host.sim.params
        specs = param_specs(params)
        if not specs:
            imgui.text_disabled("(no parameters)")
            return
        for spec in specs:
            value = self._pending.get(spec.name, getattr(params, spec.name))
            label = spec.name + (" *" if spec.rebuild else "")
            if spec.kind is bool:
                changed, value = imgui.checkbox(label, bool(value))
            elif spec.kind is str:
                changed, index = imgui.combo(label, spec.choices.index(value), list(spec.choices))
                value = spec.choices[index]
            elif spec.kind is int:
                changed, value = imgui.slider_int(label, int(value), int(spec.low),
                                                  int(spec.high))
            else:
                changed, value = imgui.slider_float(label, float(value), float(spec.low),
                                                    float(spec.high), "%.4g")
            lo, hi = imgui.get_item_rect_min(), imgui.get_item_rect_max()
            self.rects[spec.name] = (lo.x, lo.y, hi.x, hi.y)
            if spec.description:
                imgui.set_item_tooltip(spec.description + (" (rebuilds)" if spec.rebuild else ""))
            dragging = spec.kind in (int, float) and imgui.is_item_active()
            if spec.rebuild and dragging:
                if changed:
                    self._pending[spec.name] = value      # rebuild once, on release
            elif spec.name in self._pending and not dragging:
                host.set_param(spec.name, self._pending.pop(spec.name))
            elif changed:
                host.set_param(spec.name, value)
        if any(s.rebuild for s in specs):
            imgui.text_disabled("* rebuilds the scene (on release)")

    def _world(self, host) -> None:
        world = host.sim.scene.world
        changed, g = imgui.slider_float3("gravity", [float(x) for x in world.gravity],
                                         -30.0, 30.0, "%.2f")
        if changed:
            host.set_world("gravity", g)
        for i, gen in enumerate(world.contact_generators):
            if hasattr(gen, "restitution"):
                changed, e = imgui.slider_float(f"e {type(gen).__name__}##{i}",
                                                float(gen.restitution), 0.0, 1.0, "%.2f")
                imgui.set_item_tooltip(f"restitution of {type(gen).__name__} contacts")
                if changed:
                    host.set_world(("restitution", i), e)
        changed, index = imgui.combo("resolver", RESOLVERS.index(world.resolver),
                                     list(RESOLVERS))
        if changed:
            host.set_world("resolver", RESOLVERS[index])
        auto = world.iterations is None
        changed, auto = imgui.checkbox("auto iterations", auto)
        if changed:
            host.set_world("iterations", None if auto else 100)
        if world.iterations is not None:
            changed, n = imgui.slider_int("iterations", world.iterations, 1, 2000)
            if changed:
                host.set_world("iterations", max(1, n))
        changed, n = imgui.slider_int("substeps", world.substeps, 1, 20)
        if changed:
            host.set_world("substeps", n)
        if world.bodies.count:
            changed, on = imgui.checkbox("sleep", world.sleep)
            imgui.set_item_tooltip("still islands of rigid bodies stop until touched or pushed")
            if changed:
                host.set_world("sleep", on)
        changed, scale = imgui.slider_float("time scale", host.clock.time_scale, 0.05, 8.0,
                                            "%.2fx", imgui.SliderFlags_.logarithmic)
        if changed:
            host.clock.time_scale = max(0.05, scale)

    def _statistics(self, host) -> None:
        s, scene = host.stats, host.sim.scene
        world = scene.world
        last = host.sim.last_stats
        contacts = last.contacts + last.body_contacts if last is not None else 0
        bodies = world.bodies.count
        rows = (
            ("sim time", f"{scene.time:.3f} s"),
            ("real-time factor", f"{s.realtime:.2f}x" + ("  (paused)" if host.clock.paused
                                                         else "")),
            ("frames/s", f"{s.fps:.1f}"),
            ("physics per step", f"{s.step_ms:.2f} ms  (dt {1e3 * host.sim.dt:.2f} ms)"),
            ("panel per frame", f"{s.gui_ms:.2f} ms"),
            ("particles", particle_count(scene)
             + (f"  (+ {bodies} rigid bodies)" if bodies else "")),
            *((("bodies awake", f"{last.awake_bodies}"),) if bodies and last is not None
              else ()),
            ("contacts", f"{contacts}" + (f"  ({last.mode})" if last is not None else "")),
            ("kinetic energy", f"{world.kinetic_energy():.4g} J"),
            ("potential energy", f"{world.potential_energy():.4g} J"),
        )
        for name, value in rows:
            imgui.text(f"{name:<18}{value}")

    def _plots(self, host) -> None:
        probe = host.probe
        t = probe.t if probe is not None else ()
        if len(t) < 2:
            imgui.text_disabled("(runs when the simulation does)")
            return
        kinetic, potential = probe["kinetic"], probe["potential"]
        energies = {"kinetic": kinetic, "potential": potential, "total": kinetic + potential}
        world = host.sim.world
        movable = bool((world.particles.inv_mass > 0).any() or (world.bodies.inv_mass > 0).any())
        # A scene of only kinematic (infinite-mass) bodies has no energy: no flat-zero plot.
        names = [n[5:] for n in probe.names() if n.startswith("plot:")]
        energy_h, quantity_h = self._plot_heights(movable, len(names))
        if movable and implot.begin_plot("##energy", imgui.ImVec2(-1, energy_h)):
            _setup_axes("t [s]", "energy [J]", t, energies.values())
            implot.setup_legend(implot.Location_.north_west)
            for name, ys in energies.items():
                implot.plot_line(name, t, ys)
            implot.end_plot()
        if not names:
            return
        series = {name: probe["plot:" + name] for name in names}
        for name, ys in series.items():      # the values now, labelled
            imgui.text(f"{name} = {ys[-1]:.4g}")
        # One plot for all of them: a quantity approaching its limit shows against it.
        if implot.begin_plot("##quantities", imgui.ImVec2(-1, quantity_h)):
            _setup_axes("t [s]", "", t, series.values())
            implot.setup_legend(implot.Location_.south_east)
            for name, ys in series.items():
                implot.plot_line(name, t, ys)
            implot.end_plot()

    @staticmethod
    def _plot_heights(energy: bool, quantities: int) -> tuple[float, float]:
        """Heights of the energy plot and the quantities plot: their usual 130 and 140 points,
        shrunk (to 60 at least) so the World header below them stays in the window: with the
        extra statistics rows of a rigid-body demo and a plot of its own, it was cut off at the
        bottom of a 720-pixel window (box_tower, flightsim, spinning_top)."""
        style = imgui.get_style()
        spacing = style.item_spacing.y
        room = imgui.get_content_region_avail().y
        room -= imgui.get_frame_height_with_spacing() + spacing       # the World header
        room -= quantities * imgui.get_text_line_height_with_spacing()  # "name = value" rows
        wanted = (PLOT_HEIGHT if energy else 0.0) + (QUANTITY_PLOT_HEIGHT if quantities else 0.0)
        plots = int(energy) + int(quantities > 0)
        room -= plots * spacing
        scale = 1.0 if wanted <= 0 or room >= wanted else max(room, 0.0) / wanted
        return (max(MIN_PLOT_HEIGHT, PLOT_HEIGHT * scale),
                max(MIN_PLOT_HEIGHT, QUANTITY_PLOT_HEIGHT * scale))

    def _help(self, host) -> None:
        io = imgui.get_io()
        imgui.set_next_window_pos(imgui.ImVec2(io.display_size.x / 2, io.display_size.y / 2),
                                  imgui.Cond_.always, imgui.ImVec2(0.5, 0.5))
        flags = imgui.WindowFlags_.always_auto_resize | imgui.WindowFlags_.no_collapse
        _, still_open = imgui.begin("Keys and mouse (F1 / H)", True, flags)
        if imgui.begin_table("keys", 2):
            for keys, text in (*host.keymap.help_rows(), *MOUSE_HELP):
                imgui.table_next_row()
                imgui.table_next_column()
                imgui.text(keys)
                imgui.table_next_column()
                imgui.text(text)
            imgui.end_table()
        imgui.end()
        if still_open is False:
            host.act("help")


#: Fraction of the data's range left empty above and below it in a plot.
PLOT_MARGIN = 0.08


def plot_limits(values) -> tuple[float, float]:
    """The y range of a plot of ``values`` (arrays): their range plus a margin on each side, so
    a line at the data's edge (a constant reference such as a terminal velocity) stays inside
    the frame instead of on its border; a flat series gets a band around it."""
    finite = [np.asarray(v, np.float64) for v in values]
    finite = [v[np.isfinite(v)] for v in finite]
    finite = [v for v in finite if v.size]
    if not finite:
        return -1.0, 1.0
    low = min(float(v.min()) for v in finite)
    high = max(float(v.max()) for v in finite)
    span = high - low
    # Below a millionth of its size a change is rounding (a tower settling by 1e-11 m), not a
    # curve worth magnifying: such a series gets a band around it, as a flat one does.
    pad = PLOT_MARGIN * span if span > 1e-6 * max(1.0, abs(high)) else \
        max(0.5, 0.1 * abs(high))
    return low - pad, high + pad


def _setup_axes(x_label: str, y_label: str, t, values) -> None:
    implot.setup_axes(x_label, y_label)
    implot.setup_axis_limits(implot.ImAxis_.x1, float(t[0]), float(t[-1]), imgui.Cond_.always)
    low, high = plot_limits(values)
    implot.setup_axis_limits(implot.ImAxis_.y1, low, high, imgui.Cond_.always)
