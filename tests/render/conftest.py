"""GL fixtures: one EGL context per session, and a GL error check around every test that uses
it (golden-image comparison lives in tests/conftest.py, shared with the panel test).

Without EGL the GL tests skip, unless POINTMASS_REQUIRE_GL=1 (CI), which makes that a failure.
Goldens are rewritten only with POINTMASS_UPDATE_GOLDENS=1.
"""

from __future__ import annotations

import os

import pytest


def _require_gl() -> bool:
    return os.environ.get("POINTMASS_REQUIRE_GL", "") not in ("", "0")


@pytest.fixture(scope="session")
def gl_session():
    """The session's EGL context (skips, or fails under POINTMASS_REQUIRE_GL=1, without EGL)."""
    try:
        from pointmass.render import create_headless_context

        context = create_headless_context()
    except Exception as exc:  # ImportError (no moderngl) or RenderUnavailable
        if _require_gl():
            pytest.fail(f"POINTMASS_REQUIRE_GL=1 but no EGL context: {exc}")
        pytest.skip(f"no EGL OpenGL context: {exc}")
    yield context
    context.release()


@pytest.fixture
def ctx(gl_session):
    """The EGL context, with ctx.error asserted clean before and after the test."""
    assert gl_session.error == "GL_NO_ERROR", "a GL error was left by an earlier test"
    yield gl_session
    assert gl_session.error == "GL_NO_ERROR"
