"""Which of the renderer's two paths a GL context gets.

"software" (llvmpipe, CI): everything gathered into sphere rows and shadows splatted on the CPU
(``shadow_splat``), which is what a software rasterizer wants. "hardware" (a real GPU): the
particles live in GPU buffers (positions sent once a frame, their look when it changes), shadows
are drawn by the GPU (``shadow_blobs.glsl``), so the CPU's work per frame does not grow with the
particle count beyond one float32 copy of the positions.

The context's GL_RENDERER decides, unless the caller (``Renderer(path=...)``) or the environment
(``POINTMASS_RENDER_PATH=hardware|software|auto``) forces one: a test runs the hardware path's
shaders under llvmpipe that way.
"""

from __future__ import annotations

import os

#: GL_RENDERER substrings of software rasterizers (Mesa's llvmpipe, softpipe, swrast).
SOFTWARE_RENDERERS = ("llvmpipe", "softpipe", "swrast")
#: The environment variable that forces a path.
ENV = "POINTMASS_RENDER_PATH"
PATHS = ("hardware", "software")


def is_software(gl_renderer: str) -> bool:
    """Whether a GL_RENDERER string names a software rasterizer."""
    name = gl_renderer.lower()
    return any(s in name for s in SOFTWARE_RENDERERS)


def choose_path(ctx, path: str | None = None) -> str:
    """"hardware" or "software" for ``ctx``: ``path`` if given ("auto": decide), else
    ``$POINTMASS_RENDER_PATH``, else by the GL renderer's name."""
    source = "path"
    if path is None:
        path, source = os.environ.get(ENV, "auto").strip().lower() or "auto", ENV
    if path == "auto":
        return "software" if is_software(ctx.info["GL_RENDERER"]) else "hardware"
    if path not in PATHS:
        raise ValueError(f"{source} must be 'hardware', 'software' or 'auto', got {path!r}")
    return path
