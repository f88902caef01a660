"""What the renderer draws for rigid bodies (``world.bodies``): boxes as lit, outlined box
meshes at their pose; spheres as impostors with three small markers on their surface along the
body's axes, so a sphere's spin can be seen (a plain shaded ball looks the same at any angle).

Pure numpy over the bodies' arrays, copied at capture time like everything in a FrameState.
"""

from __future__ import annotations

import numpy as np

from ..rigid.bodies import world_rotation
from ..rigid.shapes import BOX, SPHERE
from ..scene import BoxVisual

#: Colors of movable bodies, by index (warm wood and paint); static ones are grey.
BODY_PALETTE = np.array([(0.86, 0.56, 0.28), (0.80, 0.42, 0.30), (0.90, 0.70, 0.36),
                         (0.62, 0.48, 0.34), (0.78, 0.60, 0.42)])
STATIC_COLOR = (0.55, 0.57, 0.60)
#: Sphere bodies stand out from the boxes they hit.
SPHERE_COLOR = (0.30, 0.50, 0.85)
#: Sleeping bodies (``World(sleep=True)``) are drawn this much of the way to ``ASLEEP_COLOR``
#: (Cyclone's explosion demo colours awake and asleep bodies apart; Box2D greys sleepers).
ASLEEP_TINT = 0.45
ASLEEP_COLOR = np.array((0.42, 0.48, 0.60))
#: The spin markers: radius as a fraction of the sphere's, and their colors (x, y, z axes).
MARKER_SCALE = 0.16
MARKER_COLORS = np.array([(0.95, 0.30, 0.20), (0.30, 0.85, 0.35), (0.95, 0.95, 0.95)])


def body_colors(bodies) -> np.ndarray:
    """(N, 3) colors: the palette for movable bodies (spheres ``SPHERE_COLOR``), grey for
    static ones, tinted toward ``ASLEEP_COLOR`` while asleep."""
    n = bodies.count
    out = BODY_PALETTE[np.arange(n) % len(BODY_PALETTE)].copy()
    out[bodies.shape[:n] == SPHERE] = SPHERE_COLOR
    out[bodies.inv_mass[:n] == 0.0] = STATIC_COLOR
    asleep = ~bodies.awake[:n]
    out[asleep] += ASLEEP_TINT * (ASLEEP_COLOR - out[asleep])
    return out


def box_visuals(bodies) -> list[BoxVisual]:
    """A BoxVisual at each box body's pose."""
    colors = body_colors(bodies)
    out = []
    for i in np.flatnonzero(bodies.shape == BOX):
        out.append(BoxVisual(center=bodies.position[i].copy(), half_size=bodies.size[i].copy(),
                             rotation=world_rotation(bodies.orientation[i]),
                             color=tuple(float(c) for c in colors[i])))
    return out


def sphere_rows(bodies, floats: int) -> tuple[np.ndarray, np.ndarray]:
    """(balls, markers): sphere rows (``floats`` wide: centre, radius, rgb, glow) for the
    sphere bodies, and for the three axis markers half sunk into each one's surface."""
    idx = np.flatnonzero(bodies.shape == SPHERE)
    balls = np.zeros((len(idx), floats), np.float32)
    markers = np.zeros((3 * len(idx), floats), np.float32)
    if not len(idx):
        return balls, markers
    pos, r = bodies.position[idx], bodies.size[idx, 0]
    balls[:, 0:3] = pos
    balls[:, 3] = r
    balls[:, 4:7] = body_colors(bodies)[idx]
    for k, i in enumerate(idx):
        axes = world_rotation(bodies.orientation[i])       # columns: the body's axes
        rows = markers[3 * k: 3 * k + 3]
        rows[:, 0:3] = pos[k] + r[k] * axes.T
        rows[:, 3] = MARKER_SCALE * r[k]
        rows[:, 4:7] = MARKER_COLORS
    return balls, markers


def rotations(quaternions: np.ndarray) -> np.ndarray:
    """Rotation matrices (N, 3, 3) of unit quaternions (N, 4) (w, x, y, z): ``world_rotation``
    for all at once."""
    w, x, y, z = (quaternions[:, k] for k in range(4))
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
    ], 1)


def body_arrays(bodies, floats: int) -> dict[str, np.ndarray]:
    """The hardware path's rigid bodies, straight from the bodies' arrays in a few numpy passes
    (no Python loop over bodies, no BoxVisual per box): "boxes" (K, BOX_FLOATS) box instance
    rows (``geometry.box_instances``' layout), "edges" (12 K, 3) × 2 starts and ends with
    "edge_rgb" (12 K, 3), "casters" (K, floats) the balls whose blobs the boxes cast
    (``ShadowMap.box_rows``), and "balls" / "markers" (``sphere_rows``)."""
    from .geometry import _CUBE_CORNERS, _CUBE_EDGES, BOX_FLOATS

    n = bodies.count
    if n == 0:
        return _no_bodies(floats)
    colors = body_colors(bodies)
    box = np.flatnonzero(bodies.shape[:n] == BOX)
    out: dict[str, np.ndarray] = {}
    center = bodies.position[box]
    half = bodies.size[box]
    model = np.concatenate([rotations(bodies.orientation[box]) * half[:, None, :],
                            center[:, :, None]], axis=2)                 # (K, 3, 4)
    rows = np.empty((len(box), BOX_FLOATS), np.float32)
    rows[:, :12] = model.reshape(-1, 12)
    rows[:, 12:15] = colors[box]
    rows[:, 15] = 1.0
    out["boxes"] = rows
    m = rows[:, :12].astype(float).reshape(-1, 3, 4)                     # as box_edge_lines
    corners = np.einsum("nij,kj->nki", m[:, :, :3], _CUBE_CORNERS) + m[:, None, :, 3]
    out["edge_start"] = corners[:, _CUBE_EDGES[:, 0]].reshape(-1, 3)
    out["edge_end"] = corners[:, _CUBE_EDGES[:, 1]].reshape(-1, 3)
    out["edge_rgb"] = np.repeat(colors[box], 12, axis=0)
    casters = np.zeros((len(box), floats), np.float32)
    casters[:, 0:3] = center
    casters[:, 3] = 0.75 * np.linalg.norm(half, axis=1)
    out["casters"] = casters

    idx = np.flatnonzero(bodies.shape[:n] == SPHERE)
    pos, r = bodies.position[idx], bodies.size[idx, 0]
    balls = np.zeros((len(idx), floats), np.float32)
    balls[:, 0:3] = pos
    balls[:, 3] = r
    balls[:, 4:7] = colors[idx]
    markers = np.zeros((len(idx), 3, floats), np.float32)
    axes = rotations(bodies.orientation[idx])                  # columns: each body's axes
    markers[:, :, 0:3] = pos[:, None, :] + r[:, None, None] * axes.transpose(0, 2, 1)
    markers[:, :, 3] = MARKER_SCALE * r[:, None]
    markers[:, :, 4:7] = MARKER_COLORS
    out["balls"] = balls
    out["markers"] = markers.reshape(-1, floats)
    return out


def _no_bodies(floats: int) -> dict[str, np.ndarray]:
    """``body_arrays`` of a world without bodies, without its ~30 numpy calls on empty arrays
    (a tenth of a millisecond a frame, most of a particle scene's capture at 10 000)."""
    from .geometry import BOX_FLOATS

    return {"boxes": np.zeros((0, BOX_FLOATS), np.float32), "edge_start": np.zeros((0, 3)),
            "edge_end": np.zeros((0, 3)), "edge_rgb": np.zeros((0, 3)),
            "casters": np.zeros((0, floats), np.float32),
            "balls": np.zeros((0, floats), np.float32),
            "markers": np.zeros((0, floats), np.float32)}
