"""An OpenGL context with no window: EGL standalone (works with no display and no GPU)."""

from __future__ import annotations

import moderngl

#: Debian/Ubuntu packages that provide EGL and Mesa's software rasterizer (llvmpipe).
EGL_PACKAGES = "libegl1 libgl1-mesa-dri"


class RenderUnavailable(RuntimeError):
    """No OpenGL context could be made (EGL or Mesa missing, or GL older than 3.3)."""


def create_headless_context(*, require: int = 330) -> moderngl.Context:
    """An offscreen moderngl context through EGL (GL ≥ 3.3 core).

    Raises:
        RenderUnavailable: when EGL or a GL driver is missing; the message names the system
            packages that provide them.
    """
    try:
        # moderngl's stub types ``backend`` as a dict; the documented value is the string
        return moderngl.create_standalone_context(backend="egl",  # type: ignore[arg-type]
                                                  require=require)
    except Exception as exc:  # moderngl raises plain Exception subclasses from glcontext
        raise RenderUnavailable(
            f"could not create an offscreen OpenGL {require // 100}.{require % 100 // 10} "
            f"context through EGL ({exc}). Install EGL and Mesa, e.g. on Debian/Ubuntu: "
            f"sudo apt-get install {EGL_PACKAGES}"
        ) from exc
