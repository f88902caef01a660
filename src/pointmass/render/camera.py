"""An orbit camera: pure math (numpy + pyrr), no GL, so it is testable anywhere.

Matrices follow pyrr's convention: row vectors, ``clip = [x, y, z, 1] @ (view @ projection)``,
and their float32 bytes are what a GL ``mat4`` uniform expects (column-major).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from pyrr import matrix44

from ..scene import CameraHint

_UP = np.array([0.0, 1.0, 0.0])


@dataclass
class OrbitCamera:
    """Looks at ``target`` from ``distance`` away; angles in degrees.

    Attributes:
        target: The point looked at and orbited around [m], shape (3,).
        distance: Eye to target [m].
        yaw: Turn around the vertical axis [deg]; 0 puts the eye on +z.
        pitch: Lift of the eye above the target's horizon [deg], kept in (-89, 89).
        fov: Vertical field of view [deg].
        near, far: Clip distances [m].
        min_distance, max_distance: The range ``zoom`` keeps ``distance`` in [m].
        keep_in_view: ``track`` keeps every drawn particle and body in view
            (``CameraHint.keep_in_view``); a window turns it off when you pan, zoom or focus.
    """

    target: np.ndarray = field(default_factory=lambda: np.array([0.0, 1.0, 0.0]))
    distance: float = 10.0
    yaw: float = 30.0
    pitch: float = 20.0
    fov: float = 45.0
    near: float = 0.05
    far: float = 500.0
    min_distance: float = 0.1
    max_distance: float = 1000.0
    keep_in_view: bool = False
    _view: tuple = field(default=(None, None), init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        self.target = np.asarray(self.target, dtype=np.float64).reshape(3).copy()
        self.pitch = _clamp_pitch(self.pitch)

    @classmethod
    def from_hint(cls, hint: CameraHint) -> OrbitCamera:
        """A camera placed as a demo's CameraHint says; near/far scale with the distance."""
        d = float(hint.distance)
        return cls(target=np.array(hint.target, float), distance=d, yaw=float(hint.yaw),
                   pitch=float(hint.pitch), fov=float(hint.fov),
                   near=max(0.01, d * 0.005), far=max(100.0, d * 50.0),
                   keep_in_view=bool(hint.keep_in_view))

    # -- pose ------------------------------------------------------------------------------------
    @property
    def forward(self) -> np.ndarray:
        """Unit vector from the eye toward the target, shape (3,)."""
        yaw, pitch = math.radians(self.yaw), math.radians(self.pitch)
        back = np.array([math.cos(pitch) * math.sin(yaw), math.sin(pitch),
                         math.cos(pitch) * math.cos(yaw)])
        return -back

    @property
    def eye(self) -> np.ndarray:
        """The eye position [m], shape (3,)."""
        return self.target - self.distance * self.forward

    @property
    def right(self) -> np.ndarray:
        """Unit vector to the right of the view, shape (3,)."""
        r = np.cross(self.forward, _UP)
        return r / np.linalg.norm(r)

    @property
    def up(self) -> np.ndarray:
        """Unit vector up in the view plane, shape (3,)."""
        return np.cross(self.right, self.forward)

    # -- matrices --------------------------------------------------------------------------------
    def view_matrix(self) -> np.ndarray:
        """World → eye space, (4, 4) float32 (pyrr convention; a new array)."""
        # Kept while the pose stays put: pyrr's look-at costs ~0.1 ms of numpy calls, as much
        # as a whole frame's GL calls.
        key = (self.target.tobytes(), self.distance, self.yaw, self.pitch)
        if self._view[0] != key:
            self._view = (key, matrix44.create_look_at(self.eye, self.target, _UP,
                                                       dtype=np.float32))
        return self._view[1].copy()

    def projection_matrix(self, aspect: float) -> np.ndarray:
        """Eye → clip space for width/height ``aspect``, (4, 4) float32 (pyrr convention)."""
        return matrix44.create_perspective_projection(self.fov, aspect, self.near, self.far,
                                                      dtype=np.float32)

    def view_projection(self, aspect: float) -> np.ndarray:
        """World → clip space, (4, 4) float32: ``[p, 1] @ view_projection``."""
        return (self.view_matrix() @ self.projection_matrix(aspect)).astype(np.float32)

    # -- controls --------------------------------------------------------------------------------
    def orbit(self, d_yaw: float, d_pitch: float) -> None:
        """Turn around the target by ``d_yaw`` and ``d_pitch`` degrees."""
        self.yaw = (self.yaw + d_yaw) % 360.0
        self.pitch = _clamp_pitch(self.pitch + d_pitch)

    def pan(self, dx: float, dy: float) -> None:
        """Slide the target in the view plane by (dx, dy) × distance [m] (right, up)."""
        self.target = self.target + (dx * self.right + dy * self.up) * self.distance

    def zoom(self, factor: float) -> None:
        """Multiply the distance by ``factor`` (> 0), kept in [min_distance, max_distance]."""
        if not factor > 0:
            raise ValueError(f"zoom factor must be > 0, got {factor}")
        self.distance = min(max(self.distance * factor, self.min_distance), self.max_distance)

    def focus(self, point) -> None:
        """Look at ``point`` [m] from the same direction and distance."""
        self.target = np.asarray(point, dtype=np.float64).reshape(3).copy()

    def track(self, scene) -> None:
        """Keep the particle named by ``scene.camera.follow`` (or the rigid body named by
        ``scene.camera.follow_body``), if any, at the target; otherwise, with
        ``keep_in_view``, everything drawn in view (``keep``)."""
        hint = scene.camera
        for index, positions in ((hint.follow, scene.world.particles.position),
                                 (hint.follow_body, scene.world.bodies.position)):
            if index is not None and 0 <= index < len(positions):
                self.focus(positions[index])
                return
        if self.keep_in_view:
            self.keep(scene)

    def keep(self, scene) -> None:
        """Look at the centre of the bounds of every drawn particle and body of ``scene``, from
        at least as far as ``CameraHint.framing`` asks for them (the distance only grows, so
        the view does not pump as things bounce; it depends on the state alone, so a window,
        a recording and a screenshot of the same moment agree)."""
        p, b = scene.world.particles, scene.world.bodies
        shown = np.ones(p.count, bool) if scene.hidden is None else \
            ~np.asarray(scene.hidden, bool)[: p.count]
        points = np.vstack([p.position[shown], b.position])
        if not len(points):
            return
        radii = np.concatenate([p.radius[shown], np.linalg.norm(b.size, axis=1)])
        hint = CameraHint.framing(points, radii, yaw=self.yaw, pitch=self.pitch, fov=self.fov)
        self.target = np.array(hint.target, dtype=np.float64)
        self.distance = min(max(self.distance, hint.distance), self.max_distance)
        self.far = max(self.far, self.distance * 50.0)

    # -- screen <-> world ------------------------------------------------------------------------
    def project(self, points, size: tuple[int, int]) -> np.ndarray:
        """Pixel coordinates (origin top-left, x right, y down) of world points (K, 3) → (K, 2).

        Points behind the eye come out mirrored; check depth yourself when it matters.
        """
        w, h = size
        pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        clip = np.c_[pts, np.ones(len(pts))] @ self.view_projection(w / h).astype(np.float64)
        ndc = clip[:, :2] / clip[:, 3:4]
        return np.c_[(ndc[:, 0] + 1.0) * 0.5 * w, (1.0 - ndc[:, 1]) * 0.5 * h]

    def ray(self, px: float, py: float, size: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
        """The ray from the eye through pixel (px, py) (origin top-left): (origin (3,), unit
        direction (3,))."""
        w, h = size
        ndc_x = 2.0 * px / w - 1.0
        ndc_y = 1.0 - 2.0 * py / h
        inv = np.linalg.inv(self.view_projection(w / h).astype(np.float64))
        far = np.array([ndc_x, ndc_y, 1.0, 1.0]) @ inv
        far = far[:3] / far[3]
        origin = self.eye
        d = far - origin
        return origin, d / np.linalg.norm(d)


def _clamp_pitch(pitch: float) -> float:
    return float(min(max(pitch, -89.0), 89.0))
