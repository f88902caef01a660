"""Fixtures for the viewer tests: a real pyglet window under Xvfb, an EGL context for the
headless panel, and the test demo.

Window tests skip without a display, and GL tests without EGL, unless POINTMASS_REQUIRE_GL=1
(CI), which makes either a failure. Every window is closed at the end of its test, after
checking that GL holds no error, and must leave no ImGui context behind.
"""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest

DEMO = Path(__file__).with_name("demo_balls.py")


def _require_gl() -> bool:
    return os.environ.get("POINTMASS_REQUIRE_GL", "") not in ("", "0")


def _unavailable(reason: str):
    if _require_gl():
        pytest.fail(f"POINTMASS_REQUIRE_GL=1 but {reason}")
    pytest.skip(reason)


@pytest.fixture
def sim():
    """A fresh Simulation of the test demo."""
    from pointmass.demo import Simulation, load_demo

    return Simulation(load_demo(DEMO))


@pytest.fixture
def open_viewer(tmp_path):
    """``open_viewer(sim, paused=True, size=(800, 500))`` -> a ViewerWindow (closed after the
    test, which fails if GL reports an error or an ImGui context is left)."""
    from pointmass.app.errors import has_display

    if not has_display():
        _unavailable("no display (run the window tests under xvfb-run -a)")
    from imgui_bundle import imgui

    from pointmass.app import open_window

    windows = []

    def make(simulation, *, paused: bool = True, size=(800, 500)):
        w = open_window(simulation, paused=paused, size=size, output_dir=tmp_path)
        windows.append(w)
        w.dispatch_events()
        return w

    yield make
    for w in windows:
        if w.viewer is not None:
            w.switch_to()
            error = w.ctx.error
            w.close()
            assert error == "GL_NO_ERROR"
    assert imgui.get_current_context() is None, "a window left its ImGui context behind"


@pytest.fixture
def in_egl():
    """``in_egl(fn)`` runs ``fn(ctx)`` with a fresh EGL context *in its own thread* and returns
    its result. A thread, because a context current on the main thread would stop the next
    pyglet window's GLX context from becoming current there (one API per thread in libglvnd)."""
    def run(fn):
        result, error = [], []

        def work():
            try:
                from pointmass.render import create_headless_context

                ctx = create_headless_context()
            except Exception as exc:      # no moderngl, or RenderUnavailable
                error.append(("unavailable", exc))
                return
            try:
                result.append(fn(ctx))
                result.append(ctx.error)
            except BaseException as exc:
                error.append(("raised", exc))
            finally:
                ctx.release()

        thread = threading.Thread(target=work)
        thread.start()
        thread.join()
        if error:
            kind, exc = error[0]
            if kind == "unavailable":
                _unavailable(f"no EGL OpenGL context: {exc}")
            raise exc
        value, gl_error = result
        assert gl_error == "GL_NO_ERROR"
        return value

    return run
