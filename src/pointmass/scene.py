"""What a demo builds: the world plus what to draw and how to look at it (no GL here).

The renderer *pulls* from a Scene: particle arrays from ``scene.world.particles``, line segments
from every force or contact generator that has a ``segments`` method, planes and boxes from the
lists below. The physics never calls the renderer.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .rigid.bodies import world_rotation
from .world import World


@dataclass
class CameraHint:
    """Where an orbit camera starts: it looks at ``target`` from ``distance`` away.

    ``yaw`` turns around the vertical axis and ``pitch`` lifts the eye above the horizon
    (both in degrees); ``fov`` is the vertical field of view in degrees; ``follow`` names a
    particle to keep in view, ``follow_body`` a rigid body; ``keep_in_view`` keeps everything
    drawn in view (the default of a Scene made without a camera).
    """

    target: tuple[float, float, float] = (0.0, 1.0, 0.0)
    distance: float = 10.0
    yaw: float = 30.0
    pitch: float = 20.0
    fov: float = 45.0
    follow: int | None = None
    """A particle the camera keeps looking at as it moves (the target follows it; orbiting and
    zooming stay yours), or None for a fixed target."""
    follow_body: int | None = None
    """A rigid body to keep looking at, the same way (``follow`` wins when both are set)."""
    keep_in_view: bool = False
    """Keep every drawn particle and body in view: the target moves to the centre of their
    bounds and the camera backs away when they would leave the view (it never moves in by
    itself, so nothing pumps). Panning, zooming or focusing in a window hands the camera back
    to you. ``follow`` and ``follow_body`` win over it."""

    @classmethod
    def framing(cls, points, radii=None, *, yaw: float = 30.0, pitch: float = 20.0,
                fov: float = 45.0, minimum: float = 2.0,
                keep_in_view: bool = False) -> CameraHint:
        """A hint that frames ``points`` (N, 3) [m] with their ``radii`` (N,): the camera looks
        at the centre of their bounds from far enough that a sphere around them, at least
        ``minimum`` m across, fills about two thirds of the view's height; ``keep_in_view``
        as the attribute."""
        pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        if pts.shape[0] == 0:
            return cls(yaw=yaw, pitch=pitch, fov=fov, keep_in_view=keep_in_view)
        r = np.zeros(len(pts)) if radii is None else np.asarray(radii, np.float64).reshape(-1)
        low = (pts - r[:, None]).min(axis=0)
        high = (pts + r[:, None]).max(axis=0)
        center = (low + high) / 2
        size = max(float(np.linalg.norm(high - low)), minimum)
        distance = (size / 2) / math.tan(math.radians(fov) / 2) / 0.66 + size / 2
        return cls(target=tuple(center.tolist()), distance=distance, yaw=yaw, pitch=pitch,
                   fov=fov, keep_in_view=keep_in_view)


@dataclass
class BoxVisual:
    """A box to draw (walls, a platform, the cookbook's cube): centre [m], half extents [m],
    rotation as a 3×3 matrix (columns are the box's axes in world space), RGB color in [0, 1]."""

    center: tuple[float, float, float] = (0.0, 0.0, 0.0)
    half_size: tuple[float, float, float] = (0.5, 0.5, 0.5)
    rotation: np.ndarray = field(default_factory=lambda: np.eye(3))
    color: tuple[float, float, float] = (0.8, 0.5, 0.2)
    wireframe: bool = False

    def attach(self, body, local_center=(0.0, 0.0, 0.0), local_rotation=None) -> None:
        """Put this box where a rigid ``body`` (a ``Body`` handle) carries it now: its centre
        at the body point ``local_center`` [m] (body coordinates), its axes the body's turned
        by ``local_rotation`` (3, 3) if given (a part of a drawn vehicle, a sail)."""
        turn = world_rotation(body.orientation)
        self.center = tuple(body.position + turn @ np.asarray(local_center, dtype=np.float64))
        self.rotation = turn if local_rotation is None else turn @ local_rotation


@dataclass
class PlaneVisual:
    """A flat rectangle to draw (water surface, a tilted platform): centre, unit normal, half
    extents along its two in-plane axes [m], RGBA color (alpha < 1 blends)."""

    center: tuple[float, float, float] = (0.0, 0.0, 0.0)
    normal: tuple[float, float, float] = (0.0, 1.0, 0.0)
    half_size: tuple[float, float] = (5.0, 5.0)
    color: tuple[float, float, float, float] = (0.2, 0.4, 0.8, 0.5)


@dataclass
class Scene:
    """A world and how to show it.

    Attributes:
        world: The physics world.
        camera: Where the camera starts; by default it frames the particles and rigid bodies
            as they are when the scene is made (``CameraHint.framing``) and keeps them in view
            as they move (``CameraHint.keep_in_view``).
        colors: Per-particle RGB in [0, 1], shape (N, 3), or None for the default palette. May be
            reassigned (or grown) as particles are added.
        hidden: Optional boolean mask (N,) of particles not to draw (dead fireworks, rounds).
        show_links: Draw springs, bungees, cables and rods as lines.
        show_ground: Draw a ground grid at ``ground_height``.
        ground_height: Height of the ground grid [m].
        shadow_height: Height of the surface the blob shadows fall on [m]; None (the default):
            the ground. A scene whose things float on water above its ground (the sailboat)
            puts them on the water, so each shadow lies under what casts it in every view.
        point_radius: Drawn radius [m] of particles whose collision radius is 0.
        trails: Particle indices whose recent path is drawn.
        trail_length: How many past positions a trail keeps.
        boxes, planes: Extra geometry.
        plots: Named quantities for the viewer's live plot: name -> fn(scene) -> float.
        handles: Anything the demo wants to find again in ``apply``/``on_step``/``check``.
        dt: The fixed physics step [s] every driver uses for this scene.

    What a running scene does over time (held keys, recorded trails, probes) belongs to the
    ``Simulation`` that runs it, not to the Scene: one Scene, many ways to run it.
    """

    world: World
    camera: CameraHint | None = None
    colors: np.ndarray | None = None
    hidden: np.ndarray | None = None
    show_links: bool = True
    show_ground: bool = True
    ground_height: float = 0.0
    shadow_height: float | None = None
    point_radius: float = 0.1
    trails: list[int] = field(default_factory=list)
    trail_length: int = 240
    boxes: list[BoxVisual] = field(default_factory=list)
    planes: list[PlaneVisual] = field(default_factory=list)
    plots: dict[str, Callable[[Scene], float]] = field(default_factory=dict)
    handles: dict[str, Any] = field(default_factory=dict)
    dt: float = 1.0 / 120.0
    sky: str = "day"
    """The backdrop: "day" (grey sky, light ground grid) or "night" (a dark gradient and a
    dimmed grid, so glowing particles read)."""
    glow: bool | np.ndarray = False
    """Draw particles as unlit glowing sprites (a bright core and a soft halo, added to what is
    behind them, with additive tapering trails): True for all, or a boolean mask (N,)."""
    look_version: int = 0
    """Bumped by ``look_changed()``: tells a renderer that caches the particles' look on the
    GPU (the hardware path) that radii, ``colors``, ``hidden`` or ``glow`` were edited in place
    (needed above ``pointmass.render.look.COMPARE_MAX`` particles, where it stops comparing)."""

    def __post_init__(self) -> None:
        if self.camera is None:
            p, b = self.world.particles, self.world.bodies
            self.camera = CameraHint.framing(
                np.vstack([p.position, b.position]),
                np.concatenate([p.radius, np.linalg.norm(b.size, axis=1)]), keep_in_view=True)

    def look_changed(self) -> None:
        """Say that particle radii, ``colors``, ``hidden`` or ``glow`` were changed in place
        (assigning a new array is seen without this)."""
        self.look_version += 1

    @property
    def time(self) -> float:
        """Simulated seconds since the world was made: ``world.time``, the only clock."""
        return self.world.time

    def particle_colors(self) -> np.ndarray:
        """Colors for every particle, shape (N, 3): ``colors`` padded with the default palette."""
        n = self.world.particles.count
        out = default_colors(n)
        if self.colors is not None:
            c = np.asarray(self.colors, dtype=np.float64).reshape(-1, 3)[:n]
            out[: len(c)] = c
        return out


_PALETTE = np.array([
    (0.90, 0.30, 0.25), (0.25, 0.55, 0.90), (0.95, 0.75, 0.20), (0.35, 0.75, 0.40),
    (0.70, 0.40, 0.85), (0.95, 0.55, 0.20), (0.30, 0.80, 0.80), (0.85, 0.85, 0.85),
])


def default_colors(count: int) -> np.ndarray:
    """A repeating palette, shape (count, 3): a new array the caller may change."""
    reps = -(-count // len(_PALETTE))
    return np.tile(_PALETTE, (reps, 1))[:count]  # a tile, not fancy indexing: 10× cheaper
