"""Cyclone's sailboat: a 200 kg catamaran floating on its two hulls, pushed by a gusty wind.

One rigid body: two hulls, a deck and a mast, its inertia from those parts at one density
(Cyclone gives the 200 kg boat the inertia of a 100 kg block, R5). ``BodyBuoyancy`` at two
points of each hull lifts it by the water it displaces (ρ·V·g, Cyclone's forgets g), so it
floats at the draft its mass implies, m / (ρ · waterplane area), and rights itself when it
heels. The sail is an
``Aero`` flat plate at mid-mast (force along its normal, from the wind's velocity relative to
the sail); the hulls' keels are an ``Aero`` in the water (little drag along the hulls, much
across), the water damps the bobbing (``BodyForce``), the rudder is an ``AeroControl`` at the
stern.
The wind blows along +x with seeded gusts (a random walk pulled back to the mean, Cyclone's
w ← 0.9·w + random, made independent of the step). Cyclone's Q/E/W change a sail control it
never applies; here they turn the sail, and A/D the rudder.

Keys (hold): Q/E turn the sail, A/D the rudder (A: bow to port), W centres both.
Run: pointmass run sailboat --set wind=8
"""

from __future__ import annotations

import math
from dataclasses import astuple, dataclass

import numpy as np

from pointmass import BoxVisual, CameraHint, PlaneVisual, Scene, World, tweak
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.forces import Aero, AeroControl, BodyBuoyancy, BodyForce
from pointmass.rigid.shapes import compound_boxes

TITLE = "Sailboat (buoyancy and sail)"
#: Shown over the scene until the first key or click.
HINT = "Hold Q/E to turn the sail, A/D for the rudder | W centres both"
MASS = 200.0
WATER_DENSITY = 1000.0
G = 9.81
#: The boat, bow along +x: (centre [m], half-extents [m]); the hulls are Cyclone's 2 × 0.4 ×
#: 0.4 m, 2 m apart.
PARTS = {"port hull": ((0.0, 0.0, -1.0), (1.0, 0.2, 0.2)),
         "starboard hull": ((0.0, 0.0, 1.0), (1.0, 0.2, 0.2)),
         "deck": ((0.0, 0.3, 0.0), (0.5, 0.05, 1.0)),
         "mast": ((0.0, 1.8, 0.0), (0.05, 1.5, 0.05))}
HULLS = ("port hull", "starboard hull")
#: The sail's pressure: force along its normal per m/s of wind across it [N·s/m].
SAIL = 60.0
SAIL_HEIGHT = 1.2
#: Keels in the water, per boat: drag along and across the hulls [N·s/m].
KEEL = (30.0, 0.0, 2000.0)
#: The water's resistance to bobbing, on the vertical velocity [N·s/m] (about half critical
#: for the hulls' 7.8 kN/m of buoyancy stiffness and 200 kg). World-vertical: a body-frame
#: term would push a pitched boat down as it sails.
HEAVE = 1300.0
#: Rudder side force per m/s of speed through the water at full helm [N·s/m].
RUDDER = 120.0
#: Held keys turn the sail and rudder at this rate [1/s of control].
CONTROL_RATE = 1.0
#: Gusts: pulled back to the mean wind at this rate [1/s].
GUST_RETURN = 0.5


@dataclass
class Params:
    wind: float = tweak(5.0, 0.0, 12.0, "Mean wind speed along +x [m/s]")
    gusts: float = tweak(1.5, 0.0, 5.0, "Gust strength [m/s per √s]")
    seed: int = tweak(7, 0, 9999, "Random seed of the gusts", rebuild=True)
    drop: float = tweak(0.3, 0.0, 1.0, "Height above its floating draft it starts at [m]",
                        rebuild=True)


def hull_points(offset: np.ndarray) -> list[np.ndarray]:
    """Two points per hull, in body coordinates (relative to the centre of mass) [m], each
    standing for half of it: at ±L/√12 from its middle (L the hull's length), so the pair has
    the hull's waterplane moment of inertia and rights the boat in pitch as the hull would."""
    out = []
    for h in HULLS:
        centre, half = np.array(PARTS[h][0]), PARTS[h][1]
        for sign in (-1.0, 1.0):
            out.append(centre + offset + (sign * half[0] / math.sqrt(3.0), 0.0, 0.0))
    return out


def draft() -> float:
    """How deep the hulls' bottoms float [m]: the displaced volume m/ρ spread over the
    waterplane of the two box hulls (Archimedes)."""
    area = sum(4.0 * PARTS[h][1][0] * PARTS[h][1][2] for h in HULLS)
    return MASS / (WATER_DENSITY * area)


def sail_tensor(control: float) -> np.ndarray:
    """The sail plate's tensor at ``control`` in [−1, 1] (the sail's angle to the hulls,
    ±90°): force = −SAIL·(u·n)·n along its normal n, u the air's velocity relative to the
    sail, in body coordinates."""
    angle = 0.5 * math.pi * control
    n = np.array([math.sin(angle), 0.0, math.cos(angle)])
    return -SAIL * np.outer(n, n)


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -G, 0.0))
    com, tensor = compound_boxes(list(PARTS.values()), MASS)
    offset = -com
    hull_half = PARTS[HULLS[0]][1]
    # the hull centres sit half a hull height minus the draft above the water
    height = hull_half[1] - draft() - PARTS[HULLS[0]][0][1] + com[1] + p.drop
    boat = world.bodies.add((0.0, height, 0.0), inertia=np.diag(tensor), mass=MASS,
                            linear_damping=0.8, angular_damping=0.8)
    volume = 4.0 * np.prod(hull_half)  # half a hull per point
    for point in hull_points(offset):
        world.add(BodyBuoyancy(boat, point, hull_half[1], volume, 0.0, WATER_DENSITY, G))
    wind = np.array([p.wind, 0.0, 0.0])
    sail = world.add(Aero(boat, sail_tensor(1.0), (0.0, SAIL_HEIGHT + offset[1], 0.0), wind))
    world.add(Aero(boat, [-k for k in KEEL], (0.0, offset[1], 0.0)))
    world.add(BodyForce(lambda bodies, i, dt: (0.0, -HEAVE * bodies.velocity[i, 1], 0.0),
                        [boat]))
    helm = np.zeros((3, 3))
    helm[2, 0] = RUDDER  # side force at the stern from the forward speed
    rudder = world.add(AeroControl(boat, np.zeros((3, 3)), -helm, helm,
                                   (-PARTS[HULLS[0]][1][0], offset[1], 0.0)))
    visuals = [BoxVisual(half_size=half, color=(0.9, 0.88, 0.82)) for _, half in
               PARTS.values()]
    visuals.append(BoxVisual(half_size=(0.02, 0.85, 0.6), color=(0.95, 0.95, 0.97)))  # sail
    visuals.append(BoxVisual(half_size=(0.6, 0.1, 0.01), color=(0.9, 0.2, 0.15)))  # pennant
    water = PlaneVisual(center=(0.0, 0.0, 0.0), half_size=(200.0, 200.0),
                        color=(0.2, 0.45, 0.85, 0.45))
    scene = Scene(world, camera=CameraHint(target=(0.0, 0.5, 0.0), distance=11.0, yaw=-35.0,
                                           pitch=20.0, follow_body=boat),
                  boxes=visuals, planes=[water], ground_height=-3.0,
                  shadow_height=0.0, dt=1.0 / 120.0,
                  handles={"boat": world.bodies[boat], "sail": sail, "rudder": rudder,
                           "sail_control": 1.0, "offset": offset, "params": p,
                           "rng": np.random.default_rng(p.seed), "mean_wind": wind.copy(),
                           "start": world.bodies.position[boat].copy()},
                  plots={"speed [m/s]": lambda s: float(np.linalg.norm(
                      s.handles["boat"].velocity)),
                      "draft [m]": measured_draft})
    _place_visuals(scene)
    return scene


def measured_draft(scene: Scene) -> float:
    """How deep the hulls' bottoms are now [m]: half a hull height minus the mean height of
    the buoyancy points (their mean sets the total lift)."""
    boat = scene.handles["boat"]
    turn = world_rotation(boat.orientation)
    heights = [boat.position[1] + (turn @ point)[1] for point in
               hull_points(scene.handles["offset"])]
    return PARTS[HULLS[0]][1][1] - float(np.mean(heights))


def _place_visuals(scene: Scene) -> None:
    h = scene.handles
    boat = h["boat"]
    for (centre, _), visual in zip(PARTS.values(), scene.boxes):
        visual.attach(boat, np.array(centre) + h["offset"])
    angle = 0.5 * math.pi * h["sail_control"]
    c, s = math.cos(angle), math.sin(angle)
    # the sail plate: its normal is the sail tensor's; it hangs aft of the mast
    spin = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    local = np.array([0.0, SAIL_HEIGHT, 0.0]) + h["offset"] + spin @ np.array([-0.6, 0, 0])
    scene.boxes[len(PARTS)].attach(boat, local, spin @ np.array([[0.0, 0.0, 1.0],
                                                                 [0.0, 1.0, 0.0],
                                                                 [-1.0, 0.0, 0.0]]))
    masthead = np.array(PARTS["mast"][0]) + h["offset"] + (0.0, PARTS["mast"][1][1], 0.0)
    _place_pennant(scene, boat.to_world(masthead))


def _place_pennant(scene: Scene, top: np.ndarray) -> None:
    """A red pennant streaming from the masthead along the wind (the true wind: what blows
    past a boat at rest)."""
    wind = scene.handles["sail"].wind
    speed = float(np.linalg.norm(wind))
    along = wind / speed if speed > 1e-9 else np.array([1.0, 0.0, 0.0])
    side = np.cross((0.0, 1.0, 0.0), along)
    side /= max(float(np.linalg.norm(side)), 1e-12)
    pennant = scene.boxes[len(PARTS) + 1]
    pennant.rotation = np.column_stack([along, np.cross(side, along), side])
    pennant.center = tuple(top + 0.6 * along)


def apply(scene: Scene, p: Params) -> None:
    scene.handles["params"] = p
    scene.handles["mean_wind"] = np.array([p.wind, 0.0, 0.0])


def set_sail(scene: Scene, control: float) -> None:
    """Turn the sail to ``control`` (clamped to [−1, 1]; ±1 across the boat, 0 along it)."""
    h = scene.handles
    h["sail_control"] = float(np.clip(control, -1.0, 1.0))
    h["sail"].tensor = sail_tensor(h["sail_control"])


def set_rudder(scene: Scene, control: float) -> None:
    """Put the helm to ``control`` (clamped to [−1, 1]; > 0 turns the bow to port, −z)."""
    scene.handles["rudder"].control = float(np.clip(control, -1.0, 1.0))


def centre(scene: Scene, p=None) -> None:
    """Sail across the boat (running before the wind) and rudder straight."""
    set_sail(scene, 1.0)
    set_rudder(scene, 0.0)


#: Held key -> (sail, rudder) direction.
HELM = {"Q": (1, 0), "E": (-1, 0), "A": (0, 1), "D": (0, -1)}


def on_keys_held(scene: Scene, keys: frozenset, dt: float) -> None:
    if "W" in keys:
        centre(scene)
    h = scene.handles
    sail = sum(HELM[k][0] for k in keys if k in HELM)
    helm = sum(HELM[k][1] for k in keys if k in HELM)
    if sail:
        set_sail(scene, h["sail_control"] + CONTROL_RATE * dt * sail)
    if helm:
        set_rudder(scene, h["rudder"].control + CONTROL_RATE * dt * helm)


def _press(sail: float, helm: float):
    def press(scene: Scene, p) -> None:
        set_sail(scene, scene.handles["sail_control"] + 0.1 * sail)
        set_rudder(scene, scene.handles["rudder"].control + 0.1 * helm)
    return press


KEYS = {k: (name, _press(*HELM[k])) for k, name in
        zip(HELM, ("Sail: turn one way", "Sail: turn the other way", "Rudder: bow to port",
                   "Rudder: bow to starboard"))}
KEYS["W"] = ("Sail across, rudder straight", centre)


def on_step(scene: Scene, dt: float) -> None:
    """Gusts: the wind relaxes toward its mean and takes a seeded random step in the
    horizontal plane (an Ornstein–Uhlenbeck walk, the same statistics at any step)."""
    h = scene.handles
    sail = h["sail"]
    kick = h["rng"].normal(size=2) * h["params"].gusts * math.sqrt(dt)
    wind = h["mean_wind"] + (sail.wind - h["mean_wind"]) * math.exp(-GUST_RETURN * dt)
    sail.wind = wind + np.array([kick[0], 0.0, kick[1]])
    _place_visuals(scene)


def heading(boat) -> float:
    """The bow's compass angle in the water plane [rad] (0 along +x, positive toward −z)."""
    bow = world_rotation(boat.orientation)[:, 0]
    return math.atan2(-bow[2], bow[0])


def sail_for(scene: Scene, seconds: float, sail: float = 1.0, helm: float = 0.0) -> None:
    """Step ``scene`` for ``seconds`` with the sail and rudder held at these controls."""
    set_sail(scene, sail)
    set_rudder(scene, helm)
    for _ in range(round(seconds / scene.dt)):
        on_step(scene, scene.dt)
        scene.world.step(scene.dt)


def control_response(p: Params) -> dict[str, tuple[float, float]]:
    """(heading [rad], speed [m/s]) of fresh boats sailed 3 s, then 4 s more with the sail
    across and the rudder straight, at full helm, or with the sail along the hulls."""
    runs = {}
    for name, sail, helm in (("straight", 1.0, 0.0), ("helm", 1.0, 1.0), ("luffed", 0.0, 0.0)):
        trial = build(p)
        sail_for(trial, 3.0)
        sail_for(trial, 4.0, sail, helm)
        boat = trial.handles["boat"]
        runs[name] = heading(boat), float(np.linalg.norm(boat.velocity[[0, 2]]))
    return runs


def check(scene: Scene) -> None:
    """After 3 s afloat: it floats at the draft its mass implies (±5 %), it has moved
    downwind; and the controls act (fresh copies sailed 3 s, then 4 s more): full helm turns
    the bow by over 15° more than a straight rudder, a sail turned along the hulls makes it
    at least 30 % slower than one across them."""
    if scene.time < 3.0:
        return
    h = scene.handles
    p = h["params"]
    depth = measured_draft(scene)
    assert abs(depth - draft()) < 0.05 * draft(), f"draft {depth:.4f} m, expected {draft():.4f}"
    if p.wind < 2.0 or p.gusts > 3.0:
        return
    moved = h["boat"].position[0] - h["start"][0]
    assert moved > 1.0, f"the boat moved {moved:.2f} m downwind"
    key = astuple(p)  # the trials depend on the parameters only: run them once for each
    if h.get("response", (None,))[0] != key:
        h["response"] = key, control_response(p)
    runs = h["response"][1]
    turned = math.degrees(abs(runs["helm"][0] - runs["straight"][0]))
    assert turned > 15.0, f"full helm turned the bow {turned:.1f}° ({runs})"
    assert runs["luffed"][1] < 0.7 * runs["straight"][1], runs
