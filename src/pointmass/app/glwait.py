"""Waiting for the GL without holding the GIL.

moderngl never releases the GIL, so a moderngl call that has to wait for the rasterizer (the
blit that samples the frame just rendered: Mesa's llvmpipe finishes the whole scene first)
holds it for most of the drawing, and the physics worker (``pointmass.app.viewer``) stalls at
its next Python line. ``finish()`` waits in ``glFinish`` called through ctypes, which lets the
GIL go while it waits: the worker steps on meanwhile.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import functools


@functools.cache
def _gl_finish():
    """libGL's glFinish through ctypes (CDLL: the GIL is released for each call), or None."""
    name = ctypes.util.find_library("GL") or "libGL.so.1"
    try:
        fn = ctypes.CDLL(name).glFinish
    except (OSError, AttributeError):
        return None
    fn.restype, fn.argtypes = None, []
    return fn


def finish() -> bool:
    """``glFinish`` on this thread's current context, without the GIL; False when libGL is
    not found (then nothing waited)."""
    fn = _gl_finish()
    if fn is None:
        return False
    fn()
    return True
