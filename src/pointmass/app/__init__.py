"""The interactive viewer: a pyglet window with an ImGui panel (``pointmass run``,
``pointmass.show``).

Importing this package opens no display and loads no pyglet: ``run_demo`` and ``show`` import
the window when called, and raise ``NoDisplayError`` (naming ``pointmass record`` and
``xvfb-run``) when there is no display to open it on.
"""

from __future__ import annotations

from .errors import NoDisplayError, has_display, no_display_message

__all__ = ["NoDisplayError", "open_window", "run_demo", "show"]


def open_window(sim, *, title: str = "pointmass", paused: bool = False, size=(1280, 720),
                output_dir=".", visible: bool = True, demo_name: str | None = None,
                overlap: bool | None = None):
    """Open a ``ViewerWindow`` on a Simulation (not yet running its loop: call ``.run()``).
    ``overlap``: step physics in a worker thread while drawing (default: on, unless
    ``POINTMASS_OVERLAP=0``; see ``pointmass.app.viewer``).

    Raises:
        NoDisplayError: no display (or pyglet cannot connect to it).
        RenderUnavailable: the display has no OpenGL 3.3 core context.
    """
    if not has_display():
        raise NoDisplayError(no_display_message(demo_name, "neither DISPLAY nor "
                                                           "WAYLAND_DISPLAY is set"))
    try:
        import pyglet

        pyglet.options.shadow_window = False      # one context: the viewer's
        from .window import ViewerWindow
    except Exception as exc:
        if type(exc).__name__ == "NoSuchDisplayException":
            raise NoDisplayError(no_display_message(demo_name, str(exc))) from None
        raise
    try:
        return ViewerWindow(sim, title=title, size=size, paused=paused,
                            output_dir=output_dir, visible=visible, overlap=overlap)
    except Exception as exc:
        if type(exc).__name__ == "NoSuchDisplayException":
            raise NoDisplayError(no_display_message(demo_name, str(exc))) from None
        if type(exc).__name__ == "NoSuchConfigException":
            from ..render import RenderUnavailable

            raise RenderUnavailable(
                f"the display offers no OpenGL 3.3 core context ({exc}); record offscreen "
                f"instead: `pointmass record {demo_name or 'DEMO'} -o clip.mp4`") from None
        raise


def run_demo(name_or_sim, overrides: list[str] | None = None, paused: bool = False) -> None:
    """Open a window on a demo (a name, with ``--set`` style ``overrides``, or a Simulation
    already made, as ``pointmass run`` passes) and run it until the window is closed."""
    from ..simulation import Simulation

    sim = name_or_sim if isinstance(name_or_sim, Simulation) else \
        Simulation(name_or_sim, overrides=overrides)
    window = open_window(sim, title=sim.title, paused=paused,
                         demo_name=sim.demo.name if sim.demo is not None else None)
    window.run()


def show(scene_or_simulation, *, paused: bool = False, title: str | None = None) -> None:
    """Open a window on a Scene built in a script, a demo name or a Simulation, and run it
    until the window is closed. Reset (Backspace) puts a bare Scene's world back as it was
    when the window opened."""
    from ..scene import Scene
    from ..simulation import Simulation

    sim = scene_or_simulation
    if isinstance(sim, (Scene, str)):
        sim = Simulation(sim, title=title)
    elif not isinstance(sim, Simulation):
        raise TypeError(f"show() takes a Scene, a demo name or a Simulation, got "
                        f"{type(sim).__name__}")
    window = open_window(sim, title=title or sim.title, paused=paused)
    window.run()
    if window.left_running is not None:  # closed while compiling: the steps finish first
        window.left_running.result()
