"""Cyclone's rope bridge: a deck of rods hung from cables, sagging under a load you walk across.

Twelve particles in two rows make six planks (rods across the deck). Cables join consecutive
particles along each side, and twelve more cables hang the deck from fixed anchors above. A
load is spread bilinearly over the four deck particles nearest to it (its weight as forces),
so the deck sags where it stands. The box shows where the load is.

Keys: A/D move the load along the bridge, W/S across it (hold them to walk).
Run: pointmass run bridge --set load_mass=30
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import (
    AnchoredCable,
    BoxVisual,
    Cable,
    CameraHint,
    ForceGenerator,
    Ground,
    Rod,
    Scene,
    World,
    tweak,
)
from pointmass.controls import walk, wasd_keys

TITLE = "Rope bridge"
#: Shown over the scene until the first key or click.
HINT = "Hold A/D to walk the load along the bridge, W/S to move it across"
G = 9.81


@dataclass
class Params:
    load_mass: float = tweak(10.0, 0.0, 50.0, "Mass of the load [kg]")
    planks: int = tweak(6, 2, 12, "Number of deck planks", rebuild=True)
    sag: float = tweak(0.5, 0.0, 1.5, "Extra hanger length at mid-span [m]", rebuild=True)
    side_slack: float = tweak(-0.05, -0.1, 0.2, "Side cable length minus plank spacing [m]",
                              rebuild=True)


class Load(ForceGenerator):
    """The load's weight, shared bilinearly by the four deck particles around (x, z)."""

    def __init__(self, planks: int, mass: float) -> None:
        self.planks, self.mass, self.x, self.z = planks, mass, 0.0, 0.0

    def weights(self) -> tuple[np.ndarray, np.ndarray]:
        """The four particle indices under the load and their shares (summing to 1)."""
        u = np.clip((self.x + self.planks - 1) / 2.0, 0.0, self.planks - 1 - 1e-9)
        j, fx = int(u), u - int(u)
        fz = np.clip((self.z + 1.0) / 2.0, 0.0, 1.0)
        idx = np.array([2 * j, 2 * j + 1, 2 * j + 2, 2 * j + 3])
        w = np.array([(1 - fx) * (1 - fz), (1 - fx) * fz, fx * (1 - fz), fx * fz])
        keep = idx < 2 * self.planks
        return idx[keep], w[keep] / w[keep].sum()

    def apply(self, particles, dt: float) -> None:
        idx, w = self.weights()
        particles.force[idx, 1] -= self.mass * G * w


def build(p: Params) -> Scene:
    n = 2 * p.planks
    world = World(gravity=(0.0, -G, 0.0))
    i = np.arange(n)
    span = p.planks - 1  # the deck runs from x = -span to x = span, planks 2 m apart
    pos = np.column_stack([(i // 2) * 2.0 - span, np.full(n, 4.0), (i % 2) * 2.0 - 1.0])
    world.add_particles(pos, masses=1.0, damping=0.9)
    world.add(Rod(i[0::2], i[1::2], 2.0))
    sides = world.add(Cable(i[:-2], i[2:], 2.0 + p.side_slack, restitution=0.3))
    anchors = pos * np.array([1.1, 0.0, 0.8]) + np.array([0.0, 6.0, 0.0])
    mid = np.abs(pos[:, 0]) / max(span, 1)  # 0 at mid-span, 1 at the ends
    world.add(AnchoredCable(i, anchors, 2.0 + p.sag * (1 - mid), restitution=0.5))
    world.add(Ground(restitution=0.2))
    load = world.add(Load(p.planks, p.load_mass))
    box = BoxVisual(half_size=(0.3, 0.3, 0.3), color=(0.85, 0.3, 0.2))
    scene = Scene(world, camera=CameraHint(target=(0.0, 4.5, 0.0), distance=1.6 * span + 7.0,
                                           yaw=25.0, pitch=12.0),
                  colors=np.tile([0.95, 0.8, 0.4], (n, 1)), boxes=[box],
                  point_radius=0.15, dt=1.0 / 120.0,
                  handles={"load": load, "box": box, "sides": sides, "planks": p.planks})
    _place_box(scene)
    return scene


def apply(scene: Scene, p: Params) -> None:
    scene.handles["load"].mass = p.load_mass


def _place_box(scene: Scene) -> None:
    idx, w = scene.handles["load"].weights()
    under = w @ scene.world.particles.position[idx]
    scene.handles["box"].center = tuple(under + np.array([0.0, 0.35, 0.0]))


def move(scene: Scene, dx: float, dz: float) -> None:
    load = scene.handles["load"]
    span = scene.handles["planks"] - 1
    load.x = float(np.clip(load.x + dx, -span, span))
    load.z = float(np.clip(load.z + dz, -1.0, 1.0))
    _place_box(scene)


def on_keys_held(scene: Scene, keys: frozenset, dt: float) -> None:
    walk(scene, keys, dt, move)  # held keys walk the load at 4 m/s


def on_step(scene: Scene, dt: float) -> None:
    _place_box(scene)


KEYS = wasd_keys(lambda scene, p, dx, dz: move(scene, 0.5 * dx, 0.5 * dz), "the load")


def check(scene: Scene) -> None:
    """The deck stays above the ground, and no side cable is stretched more than 2 %."""
    parts = scene.world.particles
    assert np.isfinite(parts.position).all()
    assert (parts.position[:, 1] > 0).all(), "the bridge touched the ground"
    sides = scene.handles["sides"]
    stretch = sides.current_lengths(parts) / sides.max_length - 1
    assert stretch.max() < 0.02, f"a side cable is over-extended by {stretch.max():.1%}"
