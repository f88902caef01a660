"""pointmass beside PyBullet, MuJoCo and pymunk (2-D) on one ball pit, measured the same way.

    .venv/bin/python benchmarks/bench_peers.py [--n 1000 10000] [--repeats 3]
    (pip install "pointmass[bench]" for the peers; an engine that is missing is skipped)

The pit: N spheres (r = 0.5 m, 1 kg) on a jittered lattice of spacing 1.1 m, 4 layers, the
lowest 1 m above the floor, in a box of side 1.1·⌈√(N/4)⌉ with four walls, restitution 0.5,
frictionless, 600 steps at dt = 1/60. For every engine: body-steps/s (median of ``repeats``
runs), its ratio to pointmass, and after the run the max and mean speed, the largest
sphere–sphere and sphere–wall overlap, the touching pairs and the escapes, all computed here
from the positions and velocities each engine reports.

Engine settings: PyBullet in DIRECT mode, maximal-coordinate spheres, 10 and 50 solver
iterations (restitution is multiplied per pair in Bullet, so each body gets √0.5); MuJoCo,
free-joint spheres, condim 1 (frictionless), the CG solver, default soft contacts (MuJoCo has
no coefficient of restitution); pymunk, N circles in a 2-D box of the same depth (a reference,
not the same problem). ``--engines ... "soft spheres (physics)"`` adds the pit solved as stiff
soft spheres with a tiny step (reference_dem_pit.py): the physics the others approximate.
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

R = 0.5
DT = 1.0 / 60.0
STEPS = 600
E = 0.5


def layout(n: int, seed: int = 0) -> tuple[np.ndarray, float]:
    """Sphere centres (N, 3) and the box side [m]."""
    rng = np.random.default_rng(seed)
    per = math.ceil(math.sqrt(n / 4))
    side = 1.1 * per
    grid = np.stack(np.meshgrid(np.arange(per), np.arange(4), np.arange(per), indexing="ij"),
                    axis=-1).reshape(-1, 3)[:n]
    pos = np.column_stack([-side / 2 + 0.55 + 1.1 * grid[:, 0], 1.0 + 1.1 * grid[:, 1],
                           -side / 2 + 0.55 + 1.1 * grid[:, 2]])
    return pos + rng.uniform(-0.05, 0.05, pos.shape), side


@dataclass
class Outcome:
    engine: str
    rate: float
    pos: np.ndarray
    vel: np.ndarray


# --- engines: each returns (seconds for STEPS steps, positions, velocities) --------------------

def pointmass_pit(pos: np.ndarray, side: float) -> pm.World:
    """The pit in a default pointmass World (also reference_dem_pit.py's)."""
    world = pm.World()
    world.add_particles(pos, radii=R)
    world.add(pm.BoxContainer((-side / 2, 0, -side / 2), (side / 2, 100, side / 2), restitution=E))
    world.add(pm.SphereCollisions(restitution=E))
    return world


def run_pointmass(n: int, settings=None):
    world = pointmass_pit(*layout(n))
    if settings is not None:
        world.settings = settings
    start = time.perf_counter()
    for _ in range(STEPS):
        world.step(DT)
    return time.perf_counter() - start, world.particles.position.copy(), \
        world.particles.velocity.copy()


def run_pybullet(n: int, iterations: int):
    import pybullet as p

    pos, side = layout(n)
    cid = p.connect(p.DIRECT)
    try:
        p.setGravity(0, -9.81, 0, physicsClientId=cid)
        p.setTimeStep(DT, physicsClientId=cid)
        p.setPhysicsEngineParameter(numSolverIterations=iterations, physicsClientId=cid)
        e = math.sqrt(E)
        thick = 1.0
        walls = [((0, -thick / 2, 0), (side, thick / 2, side))]
        for sx, sz in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            walls.append(((sx * (side / 2 + thick / 2), 25, sz * (side / 2 + thick / 2)),
                          (thick / 2 if sx else side / 2 + thick, 25,
                           thick / 2 if sz else side / 2 + thick)))
        for center, half in walls:
            shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=half, physicsClientId=cid)
            body = p.createMultiBody(0, shape, basePosition=center, physicsClientId=cid)
            p.changeDynamics(body, -1, restitution=e, lateralFriction=0.0,
                             physicsClientId=cid)
        sphere = p.createCollisionShape(p.GEOM_SPHERE, radius=R, physicsClientId=cid)
        ids = []
        for x in pos:
            body = p.createMultiBody(1.0, sphere, basePosition=x.tolist(),
                                     useMaximalCoordinates=True, physicsClientId=cid)
            p.changeDynamics(body, -1, restitution=e, lateralFriction=0.0, linearDamping=0.0,
                             angularDamping=0.0, physicsClientId=cid)
            ids.append(body)
        start = time.perf_counter()
        for _ in range(STEPS):
            p.stepSimulation(physicsClientId=cid)
        seconds = time.perf_counter() - start
        out = np.array([p.getBasePositionAndOrientation(b, physicsClientId=cid)[0] for b in ids])
        vel = np.array([p.getBaseVelocity(b, physicsClientId=cid)[0] for b in ids])
        return seconds, out, vel
    finally:
        p.disconnect(physicsClientId=cid)


def run_mujoco(n: int):
    import mujoco

    pos, side = layout(n)
    h = side / 2
    bodies = "".join(
        f'<body pos="{x:.4f} {-z:.4f} {y:.4f}"><freejoint/>'
        f'<geom type="sphere" size="{R}" mass="1"/></body>' for x, y, z in pos)
    walls = "".join(
        f'<geom type="box" pos="{px} {py} 25" size="{sx} {sy} 25"/>'
        for px, py, sx, sy in ((h + 0.5, 0, 0.5, h + 1), (-h - 0.5, 0, 0.5, h + 1),
                               (0, h + 0.5, h + 1, 0.5), (0, -h - 0.5, h + 1, 0.5)))
    xml = (f'<mujoco><option timestep="{DT}" solver="CG" gravity="0 0 -9.81"/>'
           f'<size memory="{max(64, n // 8)}M"/>'
           f'<default><geom condim="1" friction="0 0 0"/></default><worldbody>'
           f'<geom type="plane" size="{h + 1} {h + 1} 0.1"/>{walls}{bodies}</worldbody>'
           f'</mujoco>')
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    start = time.perf_counter()
    for _ in range(STEPS):
        mujoco.mj_step(model, data)
    seconds = time.perf_counter() - start
    q = data.qpos.reshape(n, 7)[:, :3]
    v = data.qvel.reshape(n, 6)[:, :3]
    # MuJoCo is z-up: back to y-up (x, z, -y) as laid out above.
    return seconds, np.column_stack([q[:, 0], q[:, 2], -q[:, 1]]), \
        np.column_stack([v[:, 0], v[:, 2], -v[:, 1]])


def run_pymunk(n: int):
    import pymunk

    width = 1.1 * math.ceil(n / 4)
    space = pymunk.Space()
    space.gravity = (0, -9.81)
    e = math.sqrt(E)
    static = space.static_body
    for a, b in (((-width / 2, 0), (width / 2, 0)), ((-width / 2, 0), (-width / 2, 100)),
                 ((width / 2, 0), (width / 2, 100))):
        seg = pymunk.Segment(static, a, b, 0.0)
        seg.elasticity, seg.friction = e, 0.0
        space.add(seg)
    rng = np.random.default_rng(0)
    bodies = []
    for k in range(n):
        body = pymunk.Body(1.0, pymunk.moment_for_circle(1.0, 0, R))
        body.position = (-width / 2 + 0.55 + 1.1 * (k // 4) + rng.uniform(-0.05, 0.05),
                         1.0 + 1.1 * (k % 4) + rng.uniform(-0.05, 0.05))
        shape = pymunk.Circle(body, R)
        shape.elasticity, shape.friction = e, 0.0
        space.add(body, shape)
        bodies.append(body)
    start = time.perf_counter()
    for _ in range(STEPS):
        space.step(DT)
    seconds = time.perf_counter() - start
    pos = np.array([(b.position.x, b.position.y, 0.0) for b in bodies])
    vel = np.array([(b.velocity.x, b.velocity.y, 0.0) for b in bodies])
    return seconds, pos, vel


# --- the same measurements for every engine ---------------------------------------------------

def measure(pos: np.ndarray, vel: np.ndarray, side: float, two_d: bool = False) -> dict:
    speed = np.linalg.norm(vel, axis=1)
    particles = pm.Particles()
    particles.add_many(pos, radii=R)
    contacts = pm.ContactBuffer()
    pm.SphereCollisions(margin=1e-3).generate(particles, contacts)
    pen = contacts.penetration
    h = side / 2
    wall = np.maximum.reduce([R - pos[:, 1], pos[:, 0] + R - h, -pos[:, 0] + R - h] +
                             ([] if two_d else [pos[:, 2] + R - h, -pos[:, 2] + R - h]))
    inside = (pos[:, 1] > -R) & (np.abs(pos[:, 0]) < h + R) & \
        (two_d | (np.abs(pos[:, 2]) < h + R))
    return {"max |v|": float(speed.max()), "mean |v|": float(speed.mean()),
            "sphere overlap [mm]": 1e3 * float(max(pen.max(initial=0.0), 0.0)),
            "wall overlap [mm]": 1e3 * float(max(wall.max(), 0.0)),
            "touching": int((pen > -1e-3).sum()), "escapes": int((~inside).sum())}


def run_fused(n: int):
    """The in-run limit (fused_pit.py): one thread, 10 velocity + 4 position passes, no warm
    start — a bare sequential-impulse loop, fast but never at rest."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).parent))
    from fused_pit import fused_pit

    pos, side = layout(n)
    vel = np.zeros_like(pos)
    g = np.array([0.0, -9.81, 0.0])
    fused_pit(pos[:8].copy(), vel[:8].copy(), R, side / 2, 100.0, E, g, DT, 1, 10, 4)  # compile
    start = time.perf_counter()
    fused_pit(pos, vel, R, side / 2, 100.0, E, g, DT, STEPS, 10, 4)
    return time.perf_counter() - start, pos, vel


def run_reference(n: int):
    """The same pit as stiff soft spheres with a 170× shorter step (reference_dem_pit.py): not
    a peer but the physics the engines approximate — how quiet the pile really is at 10 s. Run
    once (it is deterministic and slow); its rate is the reference's own, not comparable."""
    from reference_dem_pit import reference_run

    pos, side = layout(n)
    start = time.perf_counter()
    pos, vel = reference_run(pos, side, STEPS * DT)
    return time.perf_counter() - start, pos, vel


ENGINES = {
    "pointmass": run_pointmass,
    "fused SI loop (1 thread)": run_fused,
    "PyBullet, 10 iterations": lambda n: run_pybullet(n, 10),
    "PyBullet, 50 iterations": lambda n: run_pybullet(n, 50),
    "MuJoCo CG (condim 1)": run_mujoco,
    "pymunk 2-D (reference)": run_pymunk,
    "soft spheres (physics)": run_reference,
}
#: Run only when asked (``--engines ... "soft spheres (physics)"``): ~15 s at N = 1 000.
OPT_IN = ("soft spheres (physics)",)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, nargs="+", default=[1000])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--engines", nargs="+", default=[e for e in ENGINES if e not in OPT_IN])
    args = parser.parse_args()
    for n in args.n:
        _, side = layout(n)
        print(f"\nball pit N = {n}, {STEPS} steps at dt = 1/60 (median of {args.repeats})")
        print(f"{'engine':26s} {'body-steps/s':>12s} {'ratio':>6s} {'max|v|':>7s} "
              f"{'mean|v|':>8s} {'ovl mm':>7s} {'wall mm':>8s} {'touch':>6s} {'esc':>4s}")
        base = None
        for name in args.engines:
            if name == "pointmass":
                run_pointmass(min(n, 100))  # compile outside the timing
            try:
                runs = [ENGINES[name](n) for _ in range(1 if name in OPT_IN else args.repeats)]
            except ImportError as exc:
                print(f"{name:26s} skipped ({exc.name} not installed)")
                continue
            rate = n * STEPS / statistics.median(r[0] for r in runs)
            base = rate if name == "pointmass" else base
            m = measure(runs[-1][1], runs[-1][2],
                        1.1 * math.ceil(n / 4) if "2-D" in name else side, "2-D" in name)
            ratio = f"{rate / base:6.2f}" if base else "     -"
            print(f"{name:26s} {rate:12.3g} {ratio} {m['max |v|']:7.3f} {m['mean |v|']:8.4f} "
                  f"{m['sphere overlap [mm]']:7.2f} {m['wall overlap [mm]']:8.2f} "
                  f"{m['touching']:6d} {m['escapes']:4d}", flush=True)
    sys.stdout.flush()


if __name__ == "__main__":
    main()
