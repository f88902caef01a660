"""Static meshes and transforms for boxes and planes (numpy only)."""

from __future__ import annotations

import numpy as np

# Unit cube [-1, 1]^3: (+x, -x, +y, -y, +z, -z) faces, two triangles each.
_FACES = [
    ((1, 0, 0), (0, 1, 0), (0, 0, 1)),
    ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
    ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
    ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
    ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
    ((0, 0, -1), (0, 1, 0), (1, 0, 0)),
]


def cube_mesh() -> np.ndarray:
    """Triangles of the unit cube [-1, 1]^3 with face normals: (36, 6) float32 (pos, normal)."""
    rows = []
    for n, u, v in _FACES:
        n, u, v = (np.array(x, float) for x in (n, u, v))
        corners = [n + su * u + sv * v for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        for k in (0, 1, 2, 0, 2, 3):
            rows.append([*corners[k], *n])
    return np.array(rows, np.float32)


def quad_mesh() -> np.ndarray:
    """Two triangles of the square [-1, 1]^2 in the xz-plane, normal +y: (6, 6) float32."""
    c = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    return np.array([[c[k][0], 0, c[k][1], 0, 1, 0] for k in (0, 1, 2, 0, 2, 3)], np.float32)


_CUBE_CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
_CUBE_EDGES = np.array([(i, j) for i in range(8) for j in range(i + 1, 8)
                        if np.sum(_CUBE_CORNERS[i] != _CUBE_CORNERS[j]) == 1])


def box_model(center, half_size, rotation) -> np.ndarray:
    """The 4×4 model matrix (column vectors) taking the unit cube onto a box."""
    m = np.eye(4)
    m[:3, :3] = np.asarray(rotation, float).reshape(3, 3) * np.asarray(half_size, float)
    m[:3, 3] = center
    return m


#: Floats per box instance (mesh.glsl's INSTANCED variant): the model's 3 rows, rgba.
BOX_FLOATS = 16


def box_instances(boxes) -> np.ndarray:
    """Instance rows of ``boxes`` (each with center, half_size, rotation, rgb color), shape
    (N, BOX_FLOATS) float32: rows 0-2 of the model matrix of ``box_model``, then rgb and
    alpha 1."""
    out = np.empty((len(boxes), BOX_FLOATS), np.float32)
    if not len(boxes):
        return out
    center = np.array([b.center for b in boxes], float).reshape(-1, 3)
    half = np.array([b.half_size for b in boxes], float).reshape(-1, 3)
    rot = np.array([b.rotation for b in boxes], float).reshape(-1, 3, 3)
    model = np.concatenate([rot * half[:, None, :], center[:, :, None]], axis=2)   # (N, 3, 4)
    out[:, :12] = model.reshape(-1, 12)
    out[:, 12:15] = [tuple(b.color)[:3] for b in boxes]
    out[:, 15] = 1.0
    return out


def box_edge_lines(boxes) -> tuple[np.ndarray, np.ndarray]:
    """The 12 edges of every box, box by box: (start (12 N, 3), end (12 N, 3)) [m]."""
    if not len(boxes):
        return np.zeros((0, 3)), np.zeros((0, 3))
    model = box_instances(boxes)[:, :12].astype(float).reshape(-1, 3, 4)
    corners = np.einsum("nij,kj->nki", model[:, :, :3], _CUBE_CORNERS) + model[:, None, :, 3]
    return (corners[:, _CUBE_EDGES[:, 0]].reshape(-1, 3),
            corners[:, _CUBE_EDGES[:, 1]].reshape(-1, 3))


def box_edges(center, half_size, rotation) -> tuple[np.ndarray, np.ndarray]:
    """The 12 edges of a box as (start (12, 3), end (12, 3)) [m]."""
    m = box_model(center, half_size, rotation)
    corners = _CUBE_CORNERS @ m[:3, :3].T + m[:3, 3]
    return corners[_CUBE_EDGES[:, 0]], corners[_CUBE_EDGES[:, 1]]


def plane_model(center, normal, half_size) -> np.ndarray:
    """The 4×4 model matrix taking the unit xz-quad onto a rectangle with this normal."""
    n = np.asarray(normal, float)
    n = n / np.linalg.norm(n)
    helper = np.array([0.0, 0.0, 1.0]) if abs(n[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    u = np.cross(n, helper)
    u /= np.linalg.norm(u)
    v = np.cross(u, n)
    m = np.eye(4)
    m[:3, 0] = u * half_size[0]
    m[:3, 1] = n
    m[:3, 2] = v * half_size[1]
    m[:3, 3] = center
    return m


def gl_matrix(m: np.ndarray) -> bytes:
    """A column-vector 4×4 matrix as the bytes a GLSL ``mat4`` uniform reads (column-major)."""
    return np.ascontiguousarray(m.T, dtype=np.float32).tobytes()
