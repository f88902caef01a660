"""Letting go of an EGL context that is current on this thread, so the window's GLX context can
become current (libglvnd allows one API's context per thread). An offscreen render or recording
made earlier in the same process (a notebook, a test) leaves its EGL context current."""

from __future__ import annotations

import ctypes


def release_current_egl() -> bool:
    """Make no EGL context current on this thread; True when one was. The EGL context stays
    alive: ``with ctx:`` (moderngl) makes it current again."""
    try:
        egl = ctypes.CDLL("libEGL.so.1")
    except OSError:
        return False
    egl.eglGetCurrentContext.restype = ctypes.c_void_p
    egl.eglGetCurrentDisplay.restype = ctypes.c_void_p
    egl.eglMakeCurrent.argtypes = [ctypes.c_void_p] * 4
    egl.eglMakeCurrent.restype = ctypes.c_uint
    if not egl.eglGetCurrentContext():
        return False
    egl.eglMakeCurrent(egl.eglGetCurrentDisplay(), None, None, None)
    return True
