"""Cyclone's ragdoll: 12 box bones held by 11 joints, thrown down with a random push.

Bones: lower and upper legs, pelvis, abdomen, chest, head, upper and lower arms (1000 kg/m³).
Joints: knees and elbows are hinges that bend one way (a knee backward, an elbow forward, to
137°); hips, shoulders, the spine and the neck are ball joints with a swing cone and a twist
range. Jointed bones do not collide with each other; every bone meets the ground and the other
bones (μ 0.9 as the book's).

What differs from the book (rigid-notes R11): Cyclone's joints are contacts with friction 1
that act only once the two points are 0.15 m apart and only pull, with no angular limits, so
its ragdoll's limbs dangle on slack strings and bend any way; here the points stay together
(under a millimetre at rest) and the limits hold.

Keys: SPACE pushes the ragdoll again; R rebuilds it (a new seed gives another fall).
Run: pointmass run ragdoll --set seed=3
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import CameraHint, Ground, Scene, World, tweak
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.joints import BallJoint, HingeJoint
from pointmass.rigid.shapes import Box

TITLE = "Ragdoll (joints with limits)"
#: Shown over the scene until the first key or click.
HINT = "Press SPACE to push the ragdoll again"
#: name: (centre [m], half extents [m]) standing, facing +x, left side at +z.
BONES = {
    "shin_r": ((0.0, 0.27, -0.1), (0.06, 0.22, 0.06)),
    "shin_l": ((0.0, 0.27, 0.1), (0.06, 0.22, 0.06)),
    "thigh_r": ((0.0, 0.73, -0.1), (0.07, 0.22, 0.07)),
    "thigh_l": ((0.0, 0.73, 0.1), (0.07, 0.22, 0.07)),
    "pelvis": ((0.0, 1.05, 0.0), (0.1, 0.08, 0.17)),
    "abdomen": ((0.0, 1.23, 0.0), (0.09, 0.08, 0.15)),
    "chest": ((0.0, 1.45, 0.0), (0.1, 0.12, 0.19)),
    "head": ((0.0, 1.70, 0.0), (0.1, 0.11, 0.09)),
    "arm_r": ((0.0, 1.39, -0.26), (0.05, 0.15, 0.05)),
    "arm_l": ((0.0, 1.39, 0.26), (0.05, 0.15, 0.05)),
    "forearm_r": ((0.0, 1.07, -0.26), (0.045, 0.14, 0.045)),
    "forearm_l": ((0.0, 1.07, 0.26), (0.045, 0.14, 0.045)),
}
BEND = math.radians(137.0)
UP = (0.0, 1.0, 0.0)
#: Every joint's friction [N·m] (Box2D's ragdoll gives its joints some too): without it a shin
#: that comes to hang off a propped knee swings on it for ever (the joints keep energy), as
#: seed 2's did (0.12 m/s at 8 s), and a head on its neck's cone at 0.05 N·m (seed 5). 0.2 N·m
#: is 9 % of the shin's weight's torque about the knee held level (2.2 N·m): no limb is held
#: up by it (a shin hangs within 5° of straight down).
FRICTION = 0.2


def joints(bone) -> list:
    """The 11 joints: child bone (A) to parent (B), at the child's end (world points), each
    given in the child's coordinates (all bones start unturned, so world offsets are local)."""
    out = []

    def at(child, parent, point, make):
        local = np.asarray(point) - np.asarray(BONES[child][0])
        out.append(make(bone[child], local, bone[parent]))

    for side, z in (("r", -0.1), ("l", 0.1)):
        # a knee: the shin turns about +z only backward (its foot toward -x)
        at(f"shin_{side}", f"thigh_{side}", (0.0, 0.50, z),
           lambda a, p, b: HingeJoint(a, p, b, axis=(0, 0, 1), limits=(-BEND, 0.0),
                                      friction=FRICTION))
        at(f"thigh_{side}", "pelvis", (0.0, 0.96, z),
           lambda a, p, b: BallJoint(a, p, b, axis=UP, cone=math.radians(60),
                                     twist=(-0.5, 0.5), friction=FRICTION))
    for side, z in (("r", -0.26), ("l", 0.26)):
        at(f"forearm_{side}", f"arm_{side}", (0.0, 1.225, z),  # an elbow bends forward
           lambda a, p, b: HingeJoint(a, p, b, axis=(0, 0, 1), limits=(0.0, BEND),
                                      friction=FRICTION))
        at(f"arm_{side}", "chest", (0.0, 1.55, z),
           lambda a, p, b: BallJoint(a, p, b, axis=UP, cone=math.radians(80),
                                     twist=(-0.8, 0.8), friction=FRICTION))
    for child, parent, y, cone, twist in (("abdomen", "pelvis", 1.14, 25, 0.4),
                                          ("chest", "abdomen", 1.32, 25, 0.4),
                                          ("head", "chest", 1.58, 40, 0.8)):
        at(child, parent, (0.0, y, 0.0),
           lambda a, p, b, c=cone, t=twist: BallJoint(a, p, b, axis=UP, cone=math.radians(c),
                                                      twist=(-t, t), friction=FRICTION))
    return out


@dataclass
class Params:
    seed: int = tweak(1, 0, 1000, "Seed of the random push", rebuild=True)
    height: float = tweak(0.6, 0.0, 3.0, "Drop height of the feet [m]", rebuild=True)
    push: float = tweak(2.0, 0.0, 8.0, "Speed of the random push [m/s]", rebuild=True)


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    world.add(Ground(friction=0.9))
    lift = np.array([0.0, p.height, 0.0])
    bone = {name: world.add_body(Box(half), np.asarray(centre) + lift, friction=0.9,
                                 restitution=0.1)
            for name, (centre, half) in BONES.items()}
    made = [world.add(j) for j in joints(bone)]
    # the camera follows the chest: the push sends the body a metre or two any way, and
    # a fixed view 6 m off showed it small, off centre, once it lay on the ground
    chest = bone["chest"]
    scene = Scene(world, camera=CameraHint(target=tuple(chest.position), distance=3.5,
                                           yaw=40.0, pitch=25.0, follow_body=chest.index),
                  dt=1.0 / 60.0,
                  handles={"bones": bone, "joints": made, "worst_gap": 0.0, "lowest": 0.0,
                           "worst_angle": 0.0, "rng": np.random.default_rng(p.seed),
                           "params": p},
                  plots={"largest joint gap [mm]":
                         lambda s: 1e3 * float(s.world.joints.separations().max())})
    push(scene, p)
    return scene


def push(scene: Scene, p: Params) -> None:
    """Cyclone's reset push: the whole body sideways at random, and the chest off centre."""
    h = scene.handles
    rng = h["rng"]
    side = rng.normal(size=3) * (1.0, 0.2, 1.0)
    side *= p.push / max(np.linalg.norm(side), 1e-9)
    for body in h["bones"].values():
        body.velocity = body.velocity + side
    chest = h["bones"]["chest"]
    chest.velocity = chest.velocity + rng.uniform(-1.0, 1.0, 3) * p.push * 0.5


KEYS = {"SPACE": ("Push the ragdoll", push)}


def on_step(scene: Scene, dt: float) -> None:
    """Keep the largest joint gap and limit excess and the lowest bone corner seen (for
    ``check``)."""
    h = scene.handles
    h["worst_gap"] = max(h["worst_gap"], float(scene.world.joints.separations().max()))
    h["lowest"] = min(h["lowest"], lowest_corner(scene.world.bodies))
    errors = scene.world.joints.angular_errors(scene.world.bodies)
    h["worst_angle"] = max(h["worst_angle"], float(errors.max()))


def lowest_corner(bodies) -> float:
    """The lowest height of any bone's corner [m]: y − Σₖ |R₁ₖ|·hₖ for a box."""
    low = math.inf
    for i in range(bodies.count):
        up = world_rotation(bodies.orientation[i])[1]
        low = min(low, bodies.position[i, 1] - float(np.abs(up) @ bodies.size[i]))
    return low


def check(scene: Scene) -> None:
    """Joints held to < 1 cm and limits to 3° all along (measured, seeds 1–5: 7.8 mm and
    2.4° at worst, in the impact), no bone more than 1 cm into the ground, limits held to
    0.5° now, and, after 4 s, everything at rest (< 5 cm/s)."""
    h = scene.handles
    world = scene.world
    assert h["worst_gap"] < 0.01, f"a joint opened by {h['worst_gap'] * 1e3:.1f} mm"
    assert h["lowest"] > -0.01, f"a bone went {-h['lowest'] * 1e3:.1f} mm into the ground"
    assert h["worst_angle"] < math.radians(3.0), \
        f"a limit was exceeded by {math.degrees(h['worst_angle']):.2f}°"
    worst = float(world.joints.angular_errors(world.bodies).max())
    assert worst < math.radians(0.5), f"a limit is exceeded by {math.degrees(worst):.2f}°"
    if world.time >= 4.0:
        speed = float(np.abs(world.bodies.velocity).max())
        assert speed < 0.05, f"still moving at {speed:.3f} m/s after {world.time:.1f} s"
