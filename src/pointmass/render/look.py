"""The particles' look for the hardware path: drawn radius and color, sent to the GPU only when
they change (positions go every frame; see ``particle_buffers``).

A ``ParticleLook`` is one (N,) record array of (radius float32, rgba uint8), the alpha byte 255
for a glowing particle, a radius of 0 for a hidden one. With no ``scene.colors`` the color bytes
are left 0 and the shader takes the default palette by index (``palette`` True).

Whether the look changed is decided without a pass over the particles where that is possible:
the particle count, the identity of ``scene.colors`` / ``hidden`` / ``glow``, the radius
storage, ``scene.point_radius`` and ``scene.look_version`` (``Scene.look_changed()``) form a key.
Demos also edit those arrays in place (fireworks recolor and hide sparks), which no key sees:
up to ``COMPARE_MAX`` particles the sources are compared with the last copy as well (a fraction
of a millisecond); above it a scene that edits its arrays in place calls
``scene.look_changed()``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..scene import Scene
from .gather import glow_mask

#: Up to this many particles the look's sources are compared every frame (see above).
COMPARE_MAX = 131_072

LOOK_DTYPE = np.dtype([("radius", np.float32), ("rgba", np.uint8, 4)])


@dataclass(frozen=True)
class ParticleLook:
    """One upload's worth of look: ``rows`` (N,) LOOK_DTYPE, ``palette`` (colors by index in
    the shader), ``glowing`` (any particle glows), ``key`` and, for small scenes, the source
    copies it was made from (``sources``)."""

    rows: np.ndarray
    palette: bool
    glowing: bool
    key: tuple
    sources: tuple | None


def _key(scene: Scene) -> tuple:
    p = scene.world.particles
    glow = scene.glow
    return (p.count, id(p._radius), id(scene.colors), id(scene.hidden),
            glow if glow is None or np.ndim(glow) == 0 else id(glow),
            float(scene.point_radius), scene.look_version)


def _sources(scene: Scene) -> tuple:
    """Copies of what the look is made from (small scenes: compared frame to frame)."""
    p = scene.world.particles
    n = p.count

    def copy(a):
        return None if a is None or np.ndim(a) == 0 else np.array(a, copy=True)

    return (p.radius.copy(), copy(scene.colors), copy(scene.hidden), copy(scene.glow), n)


def _same(a: tuple, b: tuple) -> bool:
    for x, y in zip(a, b):
        if x is None or y is None or np.ndim(x) == 0:
            if not (x is None and y is None) and not (np.ndim(x) == 0 and x == y):
                return False
        elif x.shape != y.shape or not np.array_equal(x, y):
            return False
    return True


def build_look(scene: Scene, key: tuple, sources: tuple | None) -> ParticleLook:
    """The look of every particle now (one numpy pass: only when it changed)."""
    p = scene.world.particles
    n = p.count
    rows = np.zeros(n, LOOK_DTYPE)
    r = p.radius
    radius = np.where(r > 0, r, scene.point_radius)
    if scene.hidden is not None:
        hidden = np.asarray(scene.hidden, bool)[:n]
        radius[: len(hidden)][hidden] = 0.0
    rows["radius"] = radius
    palette = scene.colors is None
    if not palette:
        rgb = scene.particle_colors()
        rows["rgba"][:, :3] = np.clip(np.rint(rgb * 255.0), 0, 255)
    glow = glow_mask(scene)
    rows["rgba"][:, 3] = np.where(glow, 255, 0)
    return ParticleLook(rows, palette, bool(glow.any()), key, sources)


class LookTracker:
    """Hands out a new ParticleLook only when the scene's look differs from the last one drawn.

    ``capture`` returns None when nothing changed; ``drawn(look)`` records what reached the GPU
    (a frame captured but never drawn leaves the old look current, so its change is sent with
    the next frame that is).
    """

    def __init__(self) -> None:
        self._drawn: ParticleLook | None = None

    def capture(self, scene: Scene) -> ParticleLook | None:
        key = _key(scene)
        last = self._drawn
        small = scene.world.particles.count <= COMPARE_MAX
        if last is not None and last.key == key:
            if not small or last.sources is None:
                return None
            sources = _sources(scene)
            if _same(sources, last.sources):
                return None
            return build_look(scene, key, sources)
        return build_look(scene, key, _sources(scene) if small else None)

    def drawn(self, look: ParticleLook) -> None:
        self._drawn = look

    def reset(self) -> None:
        """Forget what was drawn (the GL buffers were remade): the next capture sends all."""
        self._drawn = None
