"""Rendering (moderngl + pyrr; never pyglet): the renderer, the orbit camera, picking,
an offscreen EGL context and video recording.

    >>> from pointmass.render import create_headless_context, Renderer, OrbitCamera
    >>> ctx = create_headless_context()                       # doctest: +SKIP
    >>> r = Renderer(ctx, (640, 360))                         # doctest: +SKIP
    >>> r.render(scene, OrbitCamera.from_hint(scene.camera))  # doctest: +SKIP
    >>> rgb = r.read_rgb()                                    # (360, 640, 3) uint8

``record`` lives in ``pointmass.render.recording`` and ``VideoWriter`` in
``pointmass.render.video`` (they import PyAV / Pillow only when used).
"""

import sys as _sys
import types as _types

from .camera import OrbitCamera
from .context import RenderUnavailable, create_headless_context
from .picking import Hit, pick, pick_particle
from .renderer import Renderer

__all__ = ["Hit", "OrbitCamera", "RenderUnavailable", "Renderer", "create_headless_context",
           "pick", "pick_particle"]


class _CallablePackage(_types.ModuleType):
    """Importing this package sets the attribute ``pointmass.render`` to the package, over the
    function ``pointmass.render(scene, path, ...)`` of the same name: so the package is
    callable and calls that function, and ``pm.render(...)`` writes a picture whatever was
    imported before (``import pointmass.render`` included)."""

    def __call__(self, scene, path, **options):
        from .snapshot import render_png

        return render_png(scene, path, **options)


_sys.modules[__name__].__class__ = _CallablePackage
