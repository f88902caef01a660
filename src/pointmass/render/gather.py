"""Pulling what to draw out of a Scene into flat float32 arrays (no GL, no Python loop over
particles: only over generators, trails and boxes)."""

from __future__ import annotations

import numpy as np

from ..scene import Scene
from . import style

#: Floats per line instance: start (3), end (3), rgba (4), width [px], dash period [m].
LINE_FLOATS = 12
#: Floats per sphere instance: centre (3), radius, rgb, glow (1: an unlit glowing sprite).
SPHERE_FLOATS = 8

LINK_KINDS = ("spring", "bungee", "cable", "rod", "joint")


def generators(scene: Scene):
    """Every force and contact generator of the scene's world, and its joints."""
    return [*scene.world.forces, *scene.world.contact_generators, *scene.world.joints]


def anchor_points(scene: Scene) -> np.ndarray:
    """Distinct anchor points of anchored generators [m], shape (A, 3)."""
    found = []
    for gen in generators(scene):
        anchor = getattr(gen, "anchor", None)
        if anchor is not None and getattr(gen, "kind", None) in LINK_KINDS:
            found.append(np.asarray(anchor, dtype=np.float64).reshape(-1, 3))
    if not found:
        return np.zeros((0, 3))
    return np.unique(np.concatenate(found), axis=0)


def glow_mask(scene: Scene) -> np.ndarray:
    """Which particles glow, shape (N,) bool: ``scene.glow`` as a flag for all or a mask (a
    short mask leaves the rest unlit, so a demo may grow its world without growing it)."""
    n = scene.world.particles.count
    glow = scene.glow
    if glow is None or np.ndim(glow) == 0:
        return np.full(n, bool(glow))
    mask = np.zeros(n, bool)
    g = np.asarray(glow, bool).reshape(-1)[:n]
    mask[: len(g)] = g
    return mask


def fill_spheres(scene: Scene, out: np.ndarray, anchors: np.ndarray) -> int:
    """Write particles then anchor markers into ``out`` (rows of SPHERE_FLOATS); returns the
    row count. ``out`` must have room for N + A rows."""
    p = scene.world.particles
    n = p.count
    r = p.radius
    out[:n, 0:3] = p.position
    out[:n, 3] = np.where(r > 0, r, scene.point_radius)
    if scene.hidden is not None:
        hidden = np.asarray(scene.hidden, bool)[:n]
        out[: len(hidden), 3][hidden] = 0.0   # radius 0: the vertex shader drops the quad
    out[:n, 4:7] = scene.particle_colors()
    out[:n, 7] = glow_mask(scene)
    a = len(anchors)
    if a:
        out[n:n + a] = anchor_rows(scene, anchors)
    return n + a


def anchor_rows(scene: Scene, anchors: np.ndarray) -> np.ndarray:
    """Sphere rows for the anchor markers (small dark balls at each link's fixed end)."""
    rows = np.zeros((len(anchors), SPHERE_FLOATS), np.float32)
    rows[:, 0:3] = anchors
    rows[:, 3] = scene.point_radius * style.ANCHOR_SCALE
    rows[:, 4:7] = style.ANCHOR_COLOR
    return rows


def _rows(start, end, rgb, alpha, width, dash) -> np.ndarray:
    k = len(start)
    rows = np.empty((k, LINE_FLOATS), np.float32)
    rows[:, 0:3] = start
    rows[:, 3:6] = end
    rows[:, 6:9] = rgb
    rows[:, 9] = alpha
    rows[:, 10] = width
    rows[:, 11] = dash
    return rows


def link_lines(scene: Scene, width_scale: float, skip=()) -> list[np.ndarray]:
    """Line rows for every spring, bungee, cable and rod, each kind with its own look (but the
    generators in ``skip``: the hardware path draws those from the GPU)."""
    out = []
    particles = scene.world.particles
    for gen in generators(scene):
        if any(gen is g for g in skip):
            continue
        kind = getattr(gen, "kind", None)
        seg = getattr(gen, "segments", None)
        if kind not in LINK_KINDS or seg is None:
            continue
        got = seg(particles)
        if got is None:
            continue
        start, end, strain = got
        start = np.asarray(start, np.float64).reshape(-1, 3)
        if len(start) == 0:
            continue
        end = np.broadcast_to(np.asarray(end, np.float64).reshape(-1, 3), start.shape)
        strain = np.broadcast_to(np.asarray(strain, np.float64).reshape(-1), (len(start),))
        dash_period = style.LINK_SLACK_DASH[kind]
        dash = np.where(strain < -1e-3, dash_period, 0.0) if dash_period else 0.0
        out.append(_rows(start, end, style.link_colors(kind, strain), 1.0,
                         style.LINK_WIDTH[kind] * width_scale, dash))
    return out


def trail_lines(scene: Scene, trails, colors: np.ndarray, width_scale: float, *,
                glowing: bool = False) -> list[np.ndarray]:
    """Line rows for each recorded path (``pointmass.trails.Trails``), from the trail's oldest
    point, nearly transparent, to the particle's current position.

    With ``glowing`` only the trails of glowing particles (``scene.glow``), drawn as light
    streaks for additive blending: brightest and widest at the head, fading faster and
    tapering toward the tail, so a short trail reads as motion rather than as a line. Without
    it, only the others, with the plain fade.
    """
    out = []
    hidden = scene.hidden
    pos = scene.world.particles.position
    glow = glow_mask(scene)
    for i in trails:
        if i >= len(pos) or (hidden is not None and i < len(hidden) and hidden[i]):
            continue  # a dead round or spark: its old path is not its own any more
        if bool(glow[i]) != glowing:
            continue
        pts = np.vstack([trails.points(i), pos[i]])
        if len(pts) < 2:
            continue
        rgb = colors[i] if i < len(colors) else (1.0, 1.0, 1.0)
        if glowing:
            t = np.linspace(0.0, 1.0, len(pts))[1:]
            width = style.GLOW_TRAIL_WIDTH * width_scale * (
                style.GLOW_TRAIL_TAIL + (1.0 - style.GLOW_TRAIL_TAIL) * t)
            out.append(_rows(pts[:-1], pts[1:], rgb, t * t, width, 0.0))
        else:
            alpha = np.linspace(0.05, 0.9, len(pts) - 1)
            out.append(_rows(pts[:-1], pts[1:], rgb, alpha, style.TRAIL_WIDTH * width_scale,
                             0.0))
    return out


def contact_lines(scene: Scene, radii: np.ndarray, width_scale: float) -> list[np.ndarray]:
    """A short line along each contact normal, from the contact point on particle ``a``."""
    c = scene.world.contacts
    touching = c.penetration >= 0.0  # speculative contacts (a gap inside the margin) are not shown
    if not touching.any():
        return []
    pos = scene.world.particles.position
    a = c.a[touching]
    normal = c.normal[touching]
    r = radii[a]
    start = pos[a] - normal * r[:, None]
    length = np.maximum(1.5 * r, 0.15)
    end = start + normal * length[:, None]
    return [_rows(start, end, style.CONTACT_COLOR, 1.0, 2.0 * width_scale, 0.0)]


def extra_line_rows(extra_lines, width_scale: float) -> list[np.ndarray]:
    """Line rows for caller-supplied (start, end, rgb) triples (the viewer's drag spring)."""
    if not extra_lines:
        return []
    start = np.array([s for s, _, _ in extra_lines], np.float64).reshape(-1, 3)
    end = np.array([e for _, e, _ in extra_lines], np.float64).reshape(-1, 3)
    rgb = np.array([c for _, _, c in extra_lines], np.float64).reshape(-1, 3)
    return [_rows(start, end, rgb, 1.0, style.EXTRA_WIDTH * width_scale, 0.0)]


def line_rows(start, end, rgb, alpha, width, dash=0.0) -> np.ndarray:
    """Line rows from starts and ends [m] (K, 3), rgb (3,) or (K, 3), alpha, width [px] and
    dash period [m] (scalars or (K,)): for overlays built in other modules."""
    return _rows(start, end, rgb, alpha, width, dash)
