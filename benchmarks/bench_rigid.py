"""pointmass rigid bodies beside PyBullet and MuJoCo on three box scenes, measured the same way.

    PYTHONPATH=src .venv/bin/python benchmarks/bench_rigid.py [--scenes tower pyramid pit]
        [--engines ...] [--repeats 1] [--budget 300] [--quick] [--seed 0]
    (pip install "pointmass[bench]" for the peers; an engine that is missing is skipped)

The scenes (rigid-notes §3; unit cubes of 1 kg unless named, μ = 0.5 combined, e = 0):

* tower:   10 unit cubes stacked exactly on the floor;
* pyramid: a one-box-deep wall of unit cubes, 20 at the base (210 boxes), 2 cm gaps between
  neighbours in a row, rows stacked exactly, each row centred on the one below;
* pit:     1000 cubes of 0.5 m (1 kg) with random orientations on a jittered lattice (0.9 m
  spacing, ±5 cm, 16 × 16 × 4 less 24, lowest layer at 0.5 m) dropped into a 14.6 m square pit
  with four walls (``--quick``: 250 cubes in a 7.4 m pit, and 120 steps for every scene).

dt = 1/60, g = 9.81, 600 steps (10 s). The build is not timed; the first step is the warm-up
(numba compiles outside the timing; every kernel is also compiled beforehand on a small scene)
and the other steps are timed: body-steps/s = N × timed steps / seconds, the median of
``--repeats`` runs. ``--budget`` caps the timed stepping of one run in wall-clock seconds: an
engine that runs out stops there, and its row is marked ``*`` with the steps it did (the
after-run state is then that of the earlier time).

After the run, the same measurements for every engine, computed here from the poses and
velocities each engine reports (y up): "stands" (no box's height changed by ≥ 0.1 m from its
start; tower and pyramid), the top box's horizontal drift and height change (tower: the
highest box, pyramid: the apex), the max and mean linear speed, the deepest box–box overlap
(pointmass's 15-axis SAT box–box kernel on the final poses, margin 0) and the deepest corner
beyond the floor or a wall, and the escapes (centre below the floor or outside the walls).
"At rest" for the pit is max speed ≤ 0.1 m/s and box overlap ≤ 1 cm.

Engine settings: pointmass, ``World()``'s defaults (its soft step; islands sleep), and
", sleep off" is ``World(sleep=False)``, the baseline for what sleeping buys, with the awake
count and the time everything was asleep printed under the table (``--engines
pointmass-nosleep mujoco`` for issue 26's point 10); PyBullet, DIRECT mode,
defaults (50 solver iterations, no substeps), maximal coordinates, damping zeroed (the others
have none), friction √0.5 per shape (Bullet multiplies the two), restitution 0; MuJoCo 4,
free-joint boxes, condim 3, friction 0.5 on every geom (MuJoCo takes the larger), pyramidal
cones, default soft contacts and 100 iterations, with the Newton solver (its default) and with
CG; z up in MuJoCo, converted back here.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from dataclasses import dataclass

import numpy as np

import pointmass as pm
from pointmass.rigid.box_box import box_box
from pointmass.rigid.manifold import empty_outputs
from pointmass.rigid.quaternion import quat_mul
from pointmass.rigid.shapes import Box

DT = 1.0 / 60.0
G = 9.81
STEPS = 600
MU = 0.5


# --- scenes ------------------------------------------------------------------------------------

@dataclass
class Scene:
    name: str
    position: np.ndarray  # (N, 3), y up
    orientation: np.ndarray  # (N, 4) w, x, y, z
    half: float  # cube half-side [m]
    pit: float | None  # half-width of the walled pit [m], or None (floor only)
    top: int | None  # index of the box whose drift is reported


def tower() -> Scene:
    pos = np.array([(0.0, 0.5 + k, 0.0) for k in range(10)])
    return Scene("tower", pos, _identity(10), 0.5, None, 9)


def pyramid(base: int = 20, gap: float = 0.02) -> Scene:
    pos = [((k - (base - row - 1) / 2) * (1.0 + gap), 0.5 + row, 0.0)
           for row in range(base) for k in range(base - row)]
    return Scene("pyramid", np.array(pos), _identity(len(pos)), 0.5, None, len(pos) - 1)


def pit(n: int = 1000, seed: int = 0) -> Scene:
    rng = np.random.default_rng(seed)
    per = math.ceil(math.sqrt(n / 4))
    side = 0.9 * per + 0.2
    grid = np.stack(np.meshgrid(np.arange(per), np.arange(4), np.arange(per), indexing="ij"),
                    axis=-1).reshape(-1, 3)[:n]
    pos = np.column_stack([-side / 2 + 0.55 + 0.9 * grid[:, 0], 0.5 + 0.9 * grid[:, 1],
                           -side / 2 + 0.55 + 0.9 * grid[:, 2]])
    pos += rng.uniform(-0.05, 0.05, pos.shape)
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    return Scene("pit", pos, q, 0.25, side / 2, None)


def _identity(n: int) -> np.ndarray:
    return np.tile([1.0, 0.0, 0.0, 0.0], (n, 1))


# --- engines: each returns (timed seconds, timed steps, positions, orientations, velocities) ---

def _stepper(step, steps: int, budget: float) -> tuple[float, int]:
    """One untimed warm-up step, then up to steps − 1 timed ones within ``budget`` seconds."""
    step()
    start = time.perf_counter()
    done = 0
    for _ in range(steps - 1):
        step()
        done += 1
        if time.perf_counter() - start > budget:
            break
    return time.perf_counter() - start, done


def build_pointmass(scene: Scene, sleep: bool = True) -> pm.World:
    world = pm.World(gravity=(0.0, -G, 0.0), sleep=sleep)
    world.add(pm.Ground(restitution=0.0, friction=MU))
    if scene.pit is not None:
        for normal in ((1, 0, 0), (-1, 0, 0), (0, 0, 1), (0, 0, -1)):
            world.add(pm.Plane(normal, -scene.pit, restitution=0.0, friction=MU))
    shape = Box((scene.half,) * 3)
    for x, q in zip(scene.position, scene.orientation):
        world.add_body(shape, x, q, mass=1.0, friction=MU, restitution=0.0)
    return world


#: What the last pointmass run saw of sleeping: (engine name, note), printed under the table.
SLEEP_NOTES: list[tuple[str, str]] = []


def run_pointmass(scene: Scene, steps: int, budget: float, sleep: bool = True):
    world = build_pointmass(scene, sleep)
    asleep_since = [None]  # the time the last body fell asleep, if all still sleep

    def step():
        awake = world.step(DT).awake_bodies
        asleep_since[0] = (asleep_since[0] or world.time) if awake == 0 else None

    seconds, done = _stepper(step, steps, budget)
    b = world.bodies
    since = "never all" if asleep_since[0] is None else f"all from t = {asleep_since[0]:.2f} s"
    SLEEP_NOTES.append((f"pointmass{'' if sleep else ', sleep off'}",
                        f"{int(b.awake.sum())}/{b.count} awake at the end; asleep: {since}"))
    return seconds, done, b.position.copy(), b.orientation.copy(), b.velocity.copy()


def warm_pointmass() -> None:
    """Compile every kernel the scenes use (box–box faces and edges, planes) outside timing."""
    scene = pit(16)
    scene.position = scene.position[:16]
    world = build_pointmass(scene)
    for _ in range(90):
        world.step(DT)


def run_pybullet(scene: Scene, steps: int, budget: float):
    import pybullet as p

    cid = p.connect(p.DIRECT)
    try:
        p.setGravity(0, -G, 0, physicsClientId=cid)
        p.setTimeStep(DT, physicsClientId=cid)
        mu = math.sqrt(MU)
        statics = [p.createMultiBody(0, p.createCollisionShape(
            p.GEOM_PLANE, planeNormal=[0, 1, 0], physicsClientId=cid), physicsClientId=cid)]
        if scene.pit is not None:
            h, t = scene.pit, 0.5
            for sx, sz in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                half = (t if sx else h + 2 * t, 5.0, t if sz else h + 2 * t)
                shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=half, physicsClientId=cid)
                statics.append(p.createMultiBody(0, shape, basePosition=(
                    sx * (h + t), 5.0, sz * (h + t)), physicsClientId=cid))
        for body in statics:
            p.changeDynamics(body, -1, restitution=0.0, lateralFriction=mu, physicsClientId=cid)
        cube = p.createCollisionShape(p.GEOM_BOX, halfExtents=[scene.half] * 3,
                                      physicsClientId=cid)
        ids = []
        for x, (w, qx, qy, qz) in zip(scene.position, scene.orientation):
            body = p.createMultiBody(1.0, cube, basePosition=x.tolist(),
                                     baseOrientation=[qx, qy, qz, w],
                                     useMaximalCoordinates=True, physicsClientId=cid)
            p.changeDynamics(body, -1, restitution=0.0, lateralFriction=mu, linearDamping=0.0,
                             angularDamping=0.0, physicsClientId=cid)
            ids.append(body)
        seconds, done = _stepper(lambda: p.stepSimulation(physicsClientId=cid), steps, budget)
        poses = [p.getBasePositionAndOrientation(b, physicsClientId=cid) for b in ids]
        pos = np.array([x for x, _ in poses])
        quat = np.array([(q[3], q[0], q[1], q[2]) for _, q in poses])
        vel = np.array([p.getBaseVelocity(b, physicsClientId=cid)[0] for b in ids])
        return seconds, done, pos, quat, vel
    finally:
        p.disconnect(physicsClientId=cid)


# y up (pointmass, PyBullet) to z up (MuJoCo): a quarter turn about x, (x, y, z) -> (x, -z, y).
_Y_TO_Z = np.array([math.cos(math.pi / 4), math.sin(math.pi / 4), 0.0, 0.0])
_Z_TO_Y = _Y_TO_Z * np.array([1.0, -1.0, -1.0, -1.0])


def run_mujoco(scene: Scene, steps: int, budget: float, solver: str = "Newton"):
    import mujoco

    n, s = len(scene.position), scene.half
    bodies = "".join(
        f'<body pos="{x:.6f} {-z:.6f} {y:.6f}" quat="{" ".join(f"{c:.9f}" for c in qm)}">'
        f'<freejoint/><geom type="box" size="{s} {s} {s}" mass="1"/></body>'
        for (x, y, z), qm in zip(scene.position,
                                 (quat_mul(_Y_TO_Z, q) for q in scene.orientation)))
    walls = ""
    if scene.pit is not None:
        h, t = scene.pit, 0.5
        walls = "".join(
            f'<geom type="box" pos="{px} {py} 5" size="{sx} {sy} 5"/>'
            for px, py, sx, sy in ((h + t, 0, t, h + 2 * t), (-h - t, 0, t, h + 2 * t),
                                   (0, h + t, h + 2 * t, t), (0, -h - t, h + 2 * t, t)))
    xml = (f'<mujoco><option timestep="{DT}" solver="{solver}" gravity="0 0 {-G}"/>'
           f'<size memory="{max(64, n // 2)}M"/>'
           f'<default><geom friction="{MU} 0.005 0.0001"/></default><worldbody>'
           f'<geom type="plane" size="50 50 0.1"/>{walls}{bodies}</worldbody></mujoco>')
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    seconds, done = _stepper(lambda: mujoco.mj_step(model, data), steps, budget)
    q = data.qpos.reshape(n, 7)
    v = data.qvel.reshape(n, 6)[:, :3]
    pos = np.column_stack([q[:, 0], q[:, 2], -q[:, 1]])
    quat = np.array([quat_mul(_Z_TO_Y, qm) for qm in q[:, 3:]])
    return seconds, done, pos, quat, np.column_stack([v[:, 0], v[:, 2], -v[:, 1]])


ENGINES = {
    "pointmass": run_pointmass,
    "pointmass, sleep off": lambda scene, steps, budget: run_pointmass(scene, steps, budget,
                                                                       sleep=False),
    "PyBullet (50 it)": run_pybullet,
    "MuJoCo Newton": run_mujoco,
    "MuJoCo CG": lambda scene, steps, budget: run_mujoco(scene, steps, budget, "CG"),
}
ALIASES = {"pointmass": "pointmass", "pointmass-nosleep": "pointmass, sleep off",
           "pybullet": "PyBullet (50 it)",
           "mujoco": "MuJoCo Newton", "mujoco-cg": "MuJoCo CG"}


# --- the same measurements for every engine ----------------------------------------------------

def _rotations(q: np.ndarray) -> np.ndarray:
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], 1)


def box_overlap(pos: np.ndarray, quat: np.ndarray, half: float) -> float:
    """Deepest box–box penetration [m] over all pairs (0 when none overlap)."""
    quat = quat / np.linalg.norm(quat, axis=1, keepdims=True)
    h = np.full(3, half)
    reach = 2 * math.sqrt(3) * half
    normal, points, depth, ids = empty_outputs()
    worst = 0.0
    order = np.argsort(pos[:, 0])
    xs = pos[order, 0]
    for i_sorted, i in enumerate(order):
        stop = np.searchsorted(xs, xs[i_sorted] + reach, side="right")
        for j in order[i_sorted + 1:stop]:
            if np.sum((pos[i] - pos[j]) ** 2) > reach * reach:
                continue
            count = box_box(pos[i], quat[i], h, pos[j], quat[j], h, 0.0, normal, points, depth,
                            ids)
            if count:
                worst = max(worst, float(depth[:count].max()))
    return worst


def measure(scene: Scene, pos: np.ndarray, quat: np.ndarray, vel: np.ndarray) -> dict:
    speed = np.linalg.norm(vel, axis=1)
    signs = np.array([[(k >> a & 1) * 2 - 1 for a in range(3)] for k in range(8)], float)
    corners = pos[:, None, :] + np.einsum("nij,kj->nki", _rotations(quat), scene.half * signs)
    beyond = -corners[..., 1]
    inside = pos[:, 1] > 0.0
    if scene.pit is not None:
        beyond = np.maximum(beyond, np.maximum(np.abs(corners[..., 0]),
                                               np.abs(corners[..., 2])) - scene.pit)
        inside &= (np.abs(pos[:, 0]) < scene.pit) & (np.abs(pos[:, 2]) < scene.pit)
    out = {"max |v|": float(speed.max()), "mean |v|": float(speed.mean()),
           "box pen": box_overlap(pos, quat, scene.half),
           "floor pen": float(max(beyond.max(), 0.0)), "escapes": int((~inside).sum())}
    if scene.pit is None:
        out["stands"] = bool(np.abs(pos[:, 1] - scene.position[:, 1]).max() < 0.1)
        d = pos[scene.top] - scene.position[scene.top]
        out["top xy"] = float(math.hypot(d[0], d[2]))
        out["top dz"] = float(d[1])
    else:
        out["stands"] = out["max |v|"] <= 0.1 and out["box pen"] <= 0.01  # "at rest"
    return out


# --- table ------------------------------------------------------------------------------------

HEADER = ("| engine | steps | body-steps/s | × 1st pointmass | ms/step | stands / at rest | "
          "top drift xy [m] | top dz [m] | max / mean \\|v\\| [m/s] | max pen box / floor [m] | "
          "escapes |")


def row(name: str, steps: int, full: bool, rate: float, base: float | None, n: int,
        m: dict) -> str:
    ratio = f"{rate / base:.2f}" if base else "–"
    top = (f"{m['top xy']:.4f} | {m['top dz']:+.4f}" if "top xy" in m else "– | –")
    return (f"| {name} | {steps}{'' if full else '*'} | {rate / 1e3:.1f}k | {ratio} | "
            f"{1e3 * n / rate:.2f} | {'yes' if m['stands'] else 'NO'} | {top} | "
            f"{m['max |v|']:.3g} / {m['mean |v|']:.2g} | "
            f"{m['box pen']:.4f} / {m['floor pen']:.4f} | {m['escapes']} |")


STAGES = ("step", "generate", "contact_step", "soft_passes", "sweep_back",
          "kinetic_energy")


def profile_pointmass(scene: Scene, steps: int) -> None:
    """cProfile of ``world.step`` over the timed steps: the rigid stages' share, then the top
    functions by own time."""
    import cProfile
    import pstats

    world = build_pointmass(scene)
    world.step(DT)
    profiler = cProfile.Profile()
    profiler.enable()
    for _ in range(steps - 1):
        world.step(DT)
    profiler.disable()
    stats = pstats.Stats(profiler)
    total = max(ct for (_, _, fn), (_, _, _, ct, _) in stats.stats.items() if fn == "step")
    print(f"\nprofile, pointmass on {scene.name} ({len(scene.position)} boxes, {steps - 1} "
          f"steps): {1e3 * total / (steps - 1):.2f} ms/step under cProfile")
    for (path, line, fn), (_, calls, _, ct, _) in sorted(stats.stats.items(),
                                                        key=lambda kv: -kv[1][3]):
        if fn in STAGES and "pointmass" in path:
            where = path.split("pointmass/")[-1]
            print(f"  {fn:22s} {where}:{line:<5d} {1e3 * ct / (steps - 1):7.2f} ms/step "
                  f"{100 * ct / total:5.1f} %  ({calls} calls)")
    stats.sort_stats("tottime").print_stats(12)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", nargs="+", default=["tower", "pyramid", "pit"],
                        choices=["tower", "pyramid", "pit"])
    parser.add_argument("--engines", nargs="+", default=list(ALIASES),
                        choices=list(ALIASES),
                        help="pointmass, pointmass-nosleep (World(sleep=False), the baseline "
                        "of sleeping), pybullet, mujoco (Newton), mujoco-cg")
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--budget", type=float, default=300.0,
                        help="wall-clock cap [s] on one run's timed stepping")
    parser.add_argument("--quick", action="store_true",
                        help=f"120 steps instead of {STEPS}, and a 250-box pit")
    parser.add_argument("--seed", type=int, default=0,
                        help="the pit's random seed (orientations and jitter): when the pile "
                        "calms, and so when it sleeps, differs from seed to seed")
    parser.add_argument("--profile", action="store_true",
                        help="instead of the tables: cProfile pointmass's world.step per scene")
    args = parser.parse_args()
    steps = 120 if args.quick else STEPS
    builders = {"tower": tower, "pyramid": pyramid,
                "pit": lambda: pit(250 if args.quick else 1000, args.seed)}
    if args.profile:
        warm_pointmass()
        for scene_name in args.scenes:
            profile_pointmass(builders[scene_name](), steps)
        return
    if any(alias.startswith("pointmass") for alias in args.engines):
        warm_pointmass()
    for scene_name in args.scenes:
        scene = builders[scene_name]()
        n = len(scene.position)
        print(f"\n{scene_name}: {n} boxes, {steps} steps at dt = 1/60 "
              f"(median of {args.repeats}; budget {args.budget:g} s a run)\n\n{HEADER}\n"
              + "|---" * 11 + "|", flush=True)
        base = None
        SLEEP_NOTES.clear()
        for alias in args.engines:
            name = ALIASES[alias]
            try:
                runs = [ENGINES[name](scene, steps, args.budget) for _ in range(args.repeats)]
            except ImportError as exc:
                print(f"| {name} | skipped ({exc.name} not installed) |")
                continue
            rate = statistics.median(n * r[1] / r[0] for r in runs)
            base = rate if base is None and name.startswith("pointmass") else base
            last = runs[-1]
            m = measure(scene, last[2], last[3], last[4])
            print(row(name, last[1] + 1, last[1] == steps - 1, rate, base, n, m), flush=True)
        for name, note in dict(SLEEP_NOTES).items():  # the last run of each
            print(f"\n{name}: {note}", flush=True)
    sys.stdout.flush()


if __name__ == "__main__":
    main()
