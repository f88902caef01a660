"""Cyclone's flight simulator: a rigid-body aircraft held up by aerodynamic surfaces you steer.

One rigid body (2.5 kg) with four surfaces (``Aero`` tensors: body-space force = T · the air's
velocity at the surface, the velocity including ω × r so surfaces damp turning, R3): two wings
and a rudder with controls (``AeroControl``, the tensor blended min → base → max by a control
in [−1, 1]) and a fixed tail plane, plus 10 N of thrust along the nose. It starts in the air
at cruising speed; nose it down to land on the ground (or crash into it). The inertia comes
from the drawn shape, fuselage, wings and tail at one density (Cyclone gives a 2.5 kg aircraft
the inertia of a 1 kg block, R5). The ground is a real plane that a box inside the fuselage
lands on (Cyclone clamps y ≥ 0 by hand).

Cyclone's control surfaces change their tensor by 0.5 %, too little to see; ``authority``
scales that deflection (20× by default: 20 % of the wings' lift, a visible pitch and roll).

Keys (hold): W/S pitch down/up, A/D roll left/right, Q/E rudder (yaw left/right),
X centres the controls.   Run: pointmass run flightsim --set authority=40
"""

from __future__ import annotations

from dataclasses import astuple, dataclass

import numpy as np

from pointmass import BoxVisual, CameraHint, Ground, Scene, World, tweak
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.forces import Aero, AeroControl, BodyForceGenerator
from pointmass.rigid.shapes import Box, compound_boxes

TITLE = "Flight simulator (aero surfaces)"
#: Shown over the scene until the first key or click.
HINT = "Hold W/S to pitch, A/D to roll, Q/E for the rudder | X centres the controls"
MASS = 2.5
THRUST = 10.0
#: The drawing, in body coordinates (forward is −x, up +y): (centre [m], full sides [m]).
PARTS = {"fuselage": ((-0.5, 0.0, 0.0), (2.0, 0.8, 1.0)),
         "rear fuselage": ((1.0, 0.15, 0.0), (2.75, 0.5, 0.5)),
         "wings": ((0.0, 0.3, 0.0), (0.8, 0.1, 6.0)),
         "rudder": ((2.0, 0.775, 0.0), (0.75, 1.15, 0.1)),
         "tail plane": ((1.9, 0.0, 0.0), (0.85, 0.1, 2.0))}
#: Lift row of the wings and tail: F_y = −0.5·u_x − 0.5·u_y [N·s/m]. Cyclone's −1·u_x climbs
#: at 14 m/s once at full speed (3 surfaces × 17.9 N against 24.5 N of weight); half of it
#: cruises at the full 17.9 m/s (thrust against the 0.8 damping) climbing ~1 m/s.
LIFT = (-0.5, -0.5, 0.0)
#: Half-extents of the collision box [m]: centred on the centre of mass, so it fits inside the
#: drawn fuselage (whose centre lies 0.63 m ahead): drawn, it would poke out of the drawing.
HULL = (0.35, 0.28, 0.45)
#: It starts in the air (at ``Params.altitude``) at cruising speed.
START_VELOCITY = (-15.0, 0.0, 0.0)
#: Cyclone's control deflections at authority 1: wing lift ±0.5 %, rudder side force 0.01.
WING_DEFLECTION = 0.005
RUDDER_DEFLECTION = 0.01
#: How fast a held key moves a control [1/s] (Cyclone: 0.1 per key press).
CONTROL_RATE = 2.0


@dataclass
class Params:
    authority: float = tweak(20.0, 0.0, 100.0, "Control deflection, × Cyclone's")
    thrust: float = tweak(THRUST, 0.0, 30.0, "Propeller thrust [N]")
    altitude: float = tweak(15.0, 3.0, 100.0, "Height it starts at [m]", rebuild=True)


def composite_inertia() -> tuple[np.ndarray, np.ndarray]:
    """Centre of mass [m] (3,) and moments [kg m²] (3,) about the body axes of the drawn
    parts at one density. The body stores a diagonal, so the one product of inertia
    (I_xy = −0.16 kg m², from the rudder and wings sitting above the fuselage) is dropped: it
    would tilt the principal axes by 4° about z and change the moments by under 1 %."""
    com, tensor = compound_boxes([(c, np.array(s) / 2) for c, s in PARTS.values()], MASS)
    return com, np.diag(tensor).copy()


class Thrust(BodyForceGenerator):
    """A force of ``strength`` [N] along the body's nose (−x), through the centre of mass."""

    def __init__(self, index: int, strength: float) -> None:
        self.index, self.strength = index, strength

    def apply(self, bodies, dt: float) -> None:
        nose = -world_rotation(bodies.orientation[self.index])[:, 0]
        bodies.force[self.index] += self.strength * nose


def _deflections(authority: float) -> tuple[np.ndarray, np.ndarray]:
    """What full control adds to the wings' and the rudder's tensors [N·s/m], (3, 3) each."""
    wing = np.zeros((3, 3))
    wing[1, 0] = -WING_DEFLECTION * authority  # more lift at +1 (u_x < 0 flying forward)
    rudder = np.zeros((3, 3))
    rudder[2, 0] = RUDDER_DEFLECTION * authority  # side force from the airspeed
    return wing, rudder


def _surfaces(world: World, body, authority: float) -> dict:
    """The four aero surfaces of Cyclone's aircraft (positions relative to the centre of mass),
    added to ``world``."""
    lift = np.zeros((3, 3))
    lift[1] = LIFT
    wing, rudder = _deflections(authority)
    tail = lift.copy()
    tail[2, 2] = -0.1  # the tail's keel: damps sideslip
    return {
        # +z is the pilot's left (forward −x, up +y)
        "left": world.add(AeroControl(body, lift, lift - wing, lift + wing, (-1.0, 0.0, 2.0))),
        "right": world.add(AeroControl(body, lift, lift - wing, lift + wing,
                                       (-1.0, 0.0, -2.0))),
        "rudder": world.add(AeroControl(body, np.zeros((3, 3)), -rudder, rudder,
                                        (2.0, 0.5, 0.0))),
        "tail": world.add(Aero(body, tail, (2.0, 0.0, 0.0))),
    }


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -9.81, 0.0))
    world.add(Ground(friction=0.3))
    com, moments = composite_inertia()
    plane = world.add_body(Box(HULL), (0.0, p.altitude, 0.0), velocity=START_VELOCITY, mass=MASS,
                           inertia=moments, friction=0.3, linear_damping=0.8,
                           angular_damping=0.8)
    surfaces = _surfaces(world, plane, p.authority)
    thrust = world.add(Thrust(plane.index, p.thrust))
    visuals = [BoxVisual(half_size=tuple(np.array(s) / 2), color=color)
               for (_, s), color in zip(PARTS.values(), _COLORS)]
    scene = Scene(world, camera=CameraHint(target=(0.0, 1.0, 0.0), distance=12.0, yaw=-60.0,
                                           pitch=15.0, follow_body=plane.index),
                  boxes=visuals, dt=1.0 / 120.0,
                  handles={"plane": plane, "surfaces": surfaces, "thrust": thrust,
                           "offset": -com, "airborne_since": None, "params": p},
                  plots={"altitude [m]": lambda s: float(plane.position[1]),
                         "speed [m/s]": lambda s: float(np.linalg.norm(plane.velocity))})
    _place_visuals(scene)
    return scene


_COLORS = [(0.85, 0.85, 0.88), (0.75, 0.75, 0.8), (0.85, 0.3, 0.25), (0.25, 0.45, 0.85),
           (0.25, 0.45, 0.85)]


def _place_visuals(scene: Scene) -> None:
    """The drawing at the body's pose, shifted so that its centre of mass is the body's (the
    collision box ``HULL`` hides inside the fuselage)."""
    for (centre, _), visual in zip(PARTS.values(), scene.boxes):
        visual.attach(scene.handles["plane"], np.array(centre) + scene.handles["offset"])


def apply(scene: Scene, p: Params) -> None:
    h = scene.handles
    h["params"] = p
    h["thrust"].strength = p.thrust
    wing, rudder = _deflections(p.authority)
    for name, delta in (("left", wing), ("right", wing), ("rudder", rudder)):
        surface = h["surfaces"][name]
        surface.minimum, surface.maximum = surface.base - delta, surface.base + delta
        surface.control = surface.control  # the tensor in use, from the new ends


def steer(scene: Scene, pitch: float = 0.0, roll: float = 0.0, yaw: float = 0.0) -> None:
    """Move the controls by these amounts (each clamped to [−1, 1]): ``pitch`` > 0 noses
    down (both wings lose lift: they sit ahead of the centre of mass), ``roll`` > 0 rolls
    right (left wing up), ``yaw`` > 0 turns the nose left (rudder)."""
    s = scene.handles["surfaces"]
    s["left"].control = float(np.clip(s["left"].control - pitch + roll, -1.0, 1.0))
    s["right"].control = float(np.clip(s["right"].control - pitch - roll, -1.0, 1.0))
    s["rudder"].control = float(np.clip(s["rudder"].control + yaw, -1.0, 1.0))


def centre(scene: Scene, p=None) -> None:
    """All controls back to 0."""
    for name in ("left", "right", "rudder"):
        scene.handles["surfaces"][name].control = 0.0


#: Held key -> (pitch, roll, yaw) direction.
STICK = {"W": (1, 0, 0), "S": (-1, 0, 0), "A": (0, -1, 0), "D": (0, 1, 0), "Q": (0, 0, 1),
         "E": (0, 0, -1)}


def on_keys_held(scene: Scene, keys: frozenset, dt: float) -> None:
    if "X" in keys:
        centre(scene)
    move = sum((np.array(STICK[k]) for k in keys if k in STICK), np.zeros(3))
    if move.any():
        steer(scene, *(CONTROL_RATE * dt * move))


def _press(direction):
    return lambda scene, p: steer(scene, *(0.1 * np.array(direction)))


KEYS = {k: (f"Control: {name}", _press(STICK[k])) for k, name in
        zip(STICK, ("pitch down", "pitch up", "roll left", "roll right", "rudder left",
                    "rudder right"))}
KEYS["X"] = ("Centre the controls", centre)


def on_step(scene: Scene, dt: float) -> None:
    h = scene.handles
    _place_visuals(scene)
    if h["plane"].position[1] > 1.0:
        if h["airborne_since"] is None:
            h["airborne_since"] = scene.time
    else:
        h["airborne_since"] = None


def body_rates(plane) -> np.ndarray:
    """Body rates [rad/s]: (roll, yaw, pitch) = the angular velocity about the nose (−x),
    the body's up (y) and its left (z); roll > 0 rolls right, yaw > 0 turns the nose left,
    pitch > 0 noses down."""
    return world_rotation(plane.orientation).T @ plane.angular_velocity * (-1.0, 1.0, 1.0)


def fly(scene: Scene, seconds: float, pitch: float = 0.0, roll: float = 0.0) -> None:
    """Step ``scene`` for ``seconds`` with the controls held at (pitch, roll) as ``steer``
    sets them (from centre)."""
    centre(scene)
    steer(scene, pitch, roll)
    for _ in range(round(seconds / scene.dt)):
        on_step(scene, scene.dt)
        scene.world.step(scene.dt)


def control_response(p: Params) -> dict[str, np.ndarray]:
    """Body rates (``body_rates``) of fresh aircraft flown 4 s, then 0.5 s with half pitch
    down / up, half roll right / left, or the controls centred ("level")."""
    rates = {}
    for name, pitch, roll in (("level", 0.0, 0.0), ("down", 0.5, 0.0), ("up", -0.5, 0.0),
                              ("right", 0.0, 0.5), ("left", 0.0, -0.5)):
        trial = build(p)
        fly(trial, 4.0)
        fly(trial, 0.5, pitch, roll)
        rates[name] = body_rates(trial.handles["plane"])
    return rates


def check(scene: Scene) -> None:
    """The aircraft flies: after 4 s it has been above 1 m for over 3 s. And the
    controls act (on fresh copies flown 4 s): half pitch-down makes the body pitch nose-down
    faster than with centred controls, half pitch-up nose-up; half roll-right rolls right, half
    roll-left left."""
    h = scene.handles
    if scene.time < 4.0:
        return
    assert h["airborne_since"] is not None and scene.time - h["airborne_since"] > 3.0, \
        f"not airborne at t = {scene.time:.1f} s (altitude {h['plane'].position[1]:.2f} m)"
    p = h["params"]
    if p.authority < 5.0 or p.thrust < 8.0:
        return
    key = astuple(p)  # the trials depend on the parameters only: run them once for each
    if h.get("response", (None,))[0] != key:
        h["response"] = key, control_response(p)
    rates = h["response"][1]
    assert rates["down"][2] > rates["level"][2] + 0.05, rates
    assert rates["up"][2] < rates["level"][2] - 0.05, rates
    assert rates["right"][0] > rates["level"][0] + 0.05, rates
    assert rates["left"][0] < rates["level"][0] - 0.05, rates
