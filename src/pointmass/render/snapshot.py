"""One picture of a running simulation: render offscreen, save as PNG/JPEG."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from .. import worker
from . import shadow_splat
from .camera import OrbitCamera
from .context import create_headless_context
from .renderer import Renderer


def check_writable(path: str | Path) -> Path:
    """``path`` as a Path, or a PermissionError/FileNotFoundError if its folder cannot take it
    (checked before any simulation runs)."""
    path = Path(path)
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise FileNotFoundError(f"cannot write {path}: folder {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise PermissionError(f"cannot write {path}: folder {parent} is not writable")
    if path.exists() and not os.access(path, os.W_OK):
        raise PermissionError(f"cannot write {path}: the file is not writable")
    # Permission bits do not tell the whole story (root, read-only mounts, /proc): try it.
    existed = path.exists()
    try:
        with open(path, "ab"):
            pass
    except OSError as exc:
        raise PermissionError(f"cannot write {path}: {exc.strerror or exc}") from None
    if not existed:
        path.unlink()
    return path


def save_image(rgb: np.ndarray, path: str | Path) -> None:
    """Write an (H, W, 3) uint8 image; the format follows the suffix (.png, .jpg, ...)."""
    from PIL import Image

    Image.fromarray(rgb).save(path)


def render_frame(simulation, size: tuple[int, int] = (1280, 720), *, time: float = 0.0,
                 show_contacts: bool = False) -> np.ndarray:
    """Advance ``simulation`` (a ``Simulation``) by ``time`` seconds and render it offscreen
    from its camera hint; returns (H, W, 3) uint8, top row first."""
    if time > 0:
        # In the physics worker: a first step's compile leaves Ctrl-C prompt (see worker).
        worker.call(simulation.advance, time)
    worker.call(shadow_splat.warm)          # the renderer's kernels too, not in this thread
    ctx = create_headless_context()
    try:
        renderer = Renderer(ctx, size)
        scene = simulation.scene
        camera = OrbitCamera.from_hint(scene.camera)
        camera.track(scene)
        renderer.render(scene, camera, trails=simulation.trails, show_contacts=show_contacts)
        rgb = renderer.read_rgb()
        renderer.release()
        return rgb
    finally:
        ctx.release()


def render_png(source, path: str | Path, *, time: float = 0.0,
               size: tuple[int, int] = (1280, 720), overrides=(),
               overwrite: bool = True) -> Path:
    """``pointmass.render``: write one picture of ``source`` (a Scene, a Simulation, a demo
    name or ``.py`` path) after ``time`` more simulated seconds [s] to ``path``; returns it.

    A Scene or a Simulation goes on from where it is (and is left there); a demo starts at 0.
    An existing file is replaced (as ``savefig`` does) unless ``overwrite=False``. The format
    follows the suffix (.png, .jpg)."""
    from .. import _validate as check
    from ..simulation import Simulation

    time = check.scalar(time, "time", low=0.0, high=3600.0)
    given = tuple(size)
    if len(given) != 2 or not all(isinstance(v, int) and not isinstance(v, bool)
                                  and 0 < v <= 8192 for v in given):
        raise ValueError(f"size must be (width, height) in pixels, each 1 to 8192, got {size!r}")
    size = (given[0], given[1])
    path = Path(path)
    if path.suffix.lower() not in (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".webp"):
        raise ValueError(f"path must name an image file (.png, .jpg), got {str(path)!r}")
    if path.exists() and not overwrite:
        raise FileExistsError(f"{path} exists (overwrite=False)")
    path = check_writable(path)
    sim = source if isinstance(source, Simulation) else Simulation(source,
                                                                    overrides=list(overrides))
    save_image(render_frame(sim, size, time=time), path)
    return path
