"""The tennis racket theorem: a box spun about its middle axis flips over and over; about its
longest or shortest axis it spins steadily.

Three copies of one box with three different sides float in zero gravity, each spun at the
same rate about the vertical. The left one spins about its axis of largest moment, the middle
one about its intermediate axis, the right one about its axis of smallest moment; each also
gets a tiny, seeded wobble (a sideways angular momentum, ``wobble`` times the spin's).
Rotation about the intermediate axis is unstable (Euler's equations: a perturbation grows like
e^(λt), λ = ω·√((I₁−I₂)(I₂−I₃)/(I₁I₃))), so the middle box turns upside down (its white face
down) every few seconds (the Dzhanibekov effect) while its angular momentum stays fixed; the
other two only wobble by the size of their perturbation. It needs an integrator that keeps L
(Cyclone's, without the gyroscopic term, never flips, rigid-notes R1).

Keys: none beyond the viewer's.   Run: pointmass run tennis_racket --set spin=8
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import BoxVisual, CameraHint, Scene, World, tweak
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.shapes import Box

TITLE = "Tennis racket (intermediate-axis flip)"
#: Half-extents [m]: moments about x > y > z (a book: x is its largest axis, z its smallest).
HALF = (0.12, 0.35, 0.7)
#: The body axis each box spins about: largest, intermediate, smallest moment.
AXES = (0, 1, 2)
LABELS = ("largest", "intermediate", "smallest")
SPACING = 2.2
#: Stable spins stay within this angle of the vertical [degrees].
STEADY_DEGREES = 8.0


@dataclass
class Params:
    spin: float = tweak(5.0, 1.0, 12.0, "Spin rate about the vertical [rad/s]", rebuild=True)
    wobble: float = tweak(0.02, 0.001, 0.1, "Perturbation: sideways / spin angular momentum",
                          rebuild=True)
    seed: int = tweak(3, 0, 9999, "Random seed of the perturbation", rebuild=True)


def axis_up(axis: int) -> np.ndarray:
    """A quaternion (w, x, y, z) turning body ``axis`` onto the world's vertical (y)."""
    if axis == 0:  # x -> y: +90° about z
        return np.array([math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4)])
    if axis == 2:  # z -> y: -90° about x
        return np.array([math.cos(math.pi / 4), -math.sin(math.pi / 4), 0.0, 0.0])
    return np.array([1.0, 0.0, 0.0, 0.0])


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, 0.0, 0.0))
    rng = np.random.default_rng(p.seed)
    boxes = []
    inertia = Box(HALF).unit_inertia()  # per kg; the boxes weigh 1 kg
    for k, axis in enumerate(AXES):
        # body angular momentum: the spin about ``axis``, plus ``wobble`` of it sideways
        momentum = np.zeros(3)
        momentum[axis] = inertia[axis] * p.spin
        side = rng.normal(size=2)
        momentum[[a for a in range(3) if a != axis]] = \
            p.wobble * momentum[axis] * side / np.linalg.norm(side)
        turn = axis_up(axis)
        omega = world_rotation(turn) @ (momentum / inertia)
        boxes.append(world.add_body(Box(HALF), ((k - 1) * SPACING, 0.0, 0.0), turn,
                                    angular_velocity=omega, mass=1.0))
    start = [b.bodies.angular_momentum(b.index) for b in boxes]
    caps = [BoxVisual(color=(0.95, 0.95, 0.95)) for _ in boxes]
    scene = Scene(world, camera=CameraHint(target=(0.0, 0.0, 0.0), distance=6.0, yaw=0.0,
                                           pitch=12.0),
                  show_ground=False, dt=1.0 / 120.0, boxes=caps,
                  handles={"boxes": boxes, "L0": start, "lowest": [1.0, 1.0, 1.0],
                           "params": p},
                  plots={f"{name} axis · up": _uprightness(boxes[k], AXES[k])
                         for k, name in enumerate(LABELS)})
    _place_caps(scene)
    return scene


def _place_caps(scene: Scene) -> None:
    """A white plate on the face each box was spun about (+axis end), so a flip shows."""
    for body, axis, cap in zip(scene.handles["boxes"], AXES, scene.boxes):
        half = np.array(HALF) * 0.8
        half[axis] = 0.02
        cap.half_size = tuple(half)
        cap.attach(body, np.eye(3)[axis] * (HALF[axis] + 0.02))


def _uprightness(body, axis: int):
    return lambda scene: float(spin_axis_up(body, axis))


def spin_axis_up(body, axis: int) -> float:
    """The world vertical component of the body axis that was spun (1 upright, −1 flipped)."""
    return float(world_rotation(body.orientation)[1, axis])


def on_step(scene: Scene, dt: float) -> None:
    h = scene.handles
    for k, body in enumerate(h["boxes"]):
        h["lowest"][k] = min(h["lowest"][k], spin_axis_up(body, AXES[k]))
    _place_caps(scene)


def check(scene: Scene) -> None:
    """The intermediate-axis box has turned over (its spun axis pointed down at some moment,
    by 3 s, at wobble ≥ 0.01 and spin ≥ 4 rad/s); the others stayed within
    ``STEADY_DEGREES`` of the vertical; each box's angular momentum is what it was (1e-9
    relative)."""
    h = scene.handles
    for body, start in zip(h["boxes"], h["L0"]):
        now = body.bodies.angular_momentum(body.index)
        drift = np.linalg.norm(now - start) / np.linalg.norm(start)
        assert drift < 1e-9, f"angular momentum drifted by {drift:.2e}"
    steady = math.cos(math.radians(STEADY_DEGREES))
    for k in (0, 2):
        assert h["lowest"][k] > steady, (
            f"the {LABELS[k]}-axis spin tilted {math.degrees(math.acos(h['lowest'][k])):.1f}°")
    if scene.time >= 3.0 and h["params"].wobble >= 0.01 and h["params"].spin >= 4.0:
        assert h["lowest"][1] < 0.0, (
            f"the intermediate-axis box never flipped (lowest {h['lowest'][1]:.3f})")
