"""Keyboard steering for demos: WASD as a direction, held or pressed (no GL, no window).

A demo that moves something with WASD binds the presses with ``wasd_keys`` and walks while keys
are held in its ``on_keys_held`` hook (the Simulation calls it before each step with the keys
held now):

    KEYS = wasd_keys(lambda scene, p, dx, dz: move(scene, 0.5 * dx, 0.5 * dz), "the load")

    def on_keys_held(scene, keys, dt):
        walk(scene, keys, dt, move)    # held keys move it at 4 m/s
"""

from __future__ import annotations

from collections.abc import Callable

from .scene import Scene

#: Key -> (x, z) direction on the ground, as seen from a camera looking along -z.
WASD = {"W": (0.0, -1.0), "S": (0.0, 1.0), "A": (-1.0, 0.0), "D": (1.0, 0.0)}
_NAMES = {"W": "back", "S": "forward", "A": "left", "D": "right"}


def wasd_keys(action: Callable[[Scene, object, float, float], None],
              what: str = "the load") -> dict[str, tuple[str, Callable]]:
    """Demo KEYS for W, A, S and D, each calling ``action(scene, params, dx, dz)``."""
    def binding(key: str) -> Callable:
        dx, dz = WASD[key]
        return lambda scene, params: action(scene, params, dx, dz)

    return {key: (f"Move {what} {_NAMES[key]}", binding(key)) for key in WASD}


def held_direction(keys) -> tuple[float, float]:
    """The (x, z) direction of the WASD keys among ``keys`` (each component in [-1, 1])."""
    dx = sum(WASD[k][0] for k in keys if k in WASD)
    dz = sum(WASD[k][1] for k in keys if k in WASD)
    return max(-1.0, min(1.0, dx)), max(-1.0, min(1.0, dz))


def walk(scene: Scene, keys, dt: float, move: Callable[[Scene, float, float], None],
         speed: float = 4.0) -> None:
    """Call ``move(scene, dx, dz)`` with the step [m] that the held WASD ``keys`` make in
    ``dt`` [s] at ``speed`` [m/s]."""
    dx, dz = held_direction(keys)
    if dx or dz:
        move(scene, speed * dx * dt, speed * dz * dt)
