"""Random rigid scenes (issue 30): the generator, one scene's run with its checks, and a
command that counts what goes wrong over many seeds.

A scene, from its seed alone: 1–6 moving boxes and spheres of 0.05–2 m and 1 g–10 t (log-
uniform), speeds to 50 m/s, spins to 20 rad/s, friction and restitution in [0, 1]; 0–2 static
bodies; 0–3 ball or hinge joints, at a random point of body A, to another body (met where the
point is) or to a world point (where it is, or up to 0.5 m off, inside the walls); 0–4
particles with a radius; no scenery, a ground, or six walls (a third each); gravity or none
(half each: the force-free scenes, where no step may gain kinetic energy). World() defaults,
300 steps at 1/60 s.

``python benchmarks/rigid_fuzz.py --seeds 0:1000`` runs each scene in a child process under a
watchdog (a step that has not returned after ``--hang`` seconds is a hang) and prints the
counts of issue 30's "What was measured"; the test (tests/physics/test_fuzz_rigid.py) runs the
same scenes in process. ``--combine LOG ...`` counts over the logs of such runs made side
by side (benchmarks/rigid_device_check.sh, on a many-core machine).
"""

from __future__ import annotations

import argparse
import faulthandler
import math
import sys
import time
from dataclasses import dataclass, field

import numpy as np

import pointmass as pm
from pointmass.rigid import collide as body_collide
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.contacts import BodyContacts
from pointmass.rigid.joints import BallJoint, HingeJoint
from pointmass.rigid.shapes import Box, Sphere

DT = 1.0 / 60.0
STEPS = 300
#: A speed above this [m/s] that no error reported is an explosion.
SPEED_LIMIT = 1e4
#: A force-free step may gain at most this fraction of the kinetic energy (round-off).
ENERGY_SLACK = 1e-9
#: Overlap [m] at the end of a step that counts as deep.
DEEP = 0.02
#: The angular velocity [rad/s] an instrumented copy of the solver leaves where a step would
#: never return (the free rotation asked for more than 1e7 pieces), so a measurement of the old
#: code counts hangs without a process per hang; the code itself never writes it.
HANG_MARK = -7.25e300


def _unit(rng) -> np.ndarray:
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def _log_uniform(rng, low: float, high: float) -> float:
    return float(math.exp(rng.uniform(math.log(low), math.log(high))))


def _quaternion(rng) -> tuple[float, ...]:
    q = rng.normal(size=4)
    return tuple((q / np.linalg.norm(q)).tolist())


def build(seed: int, **world_args) -> tuple[pm.World, bool]:
    """The world of ``seed`` (``World(**world_args)`` besides its gravity), and whether it is
    force-free (no gravity)."""
    rng = np.random.default_rng(seed)
    force_free = bool(rng.random() < 0.5)
    world = pm.World(gravity=(0.0, 0.0, 0.0) if force_free else (0.0, -9.81, 0.0),
                     **world_args)
    room = float(rng.uniform(3.0, 6.0))  # the walls' half size [m]
    scenery = int(rng.integers(0, 3))  # none, a ground, six walls
    if scenery == 1:
        world.add(pm.Ground(-room, restitution=float(rng.uniform(0, 1)),
                            friction=float(rng.uniform(0, 1))))
    elif scenery == 2:
        for axis in range(3):
            for sign in (1.0, -1.0):
                n = np.zeros(3)
                n[axis] = sign
                world.add(pm.Plane(n, -room, restitution=float(rng.uniform(0, 1)),
                                   friction=float(rng.uniform(0, 1))))
    moving = int(rng.integers(1, 7))
    static = int(rng.integers(0, 3))
    placed: list[tuple[np.ndarray, float]] = []  # centres and bounding radii, kept apart
    for i in range(moving + static):
        if rng.random() < 0.5:
            r = _log_uniform(rng, 0.025, 1.0)
            shape, bound = Sphere(r), r
        else:
            half = np.array([_log_uniform(rng, 0.025, 1.0) for _ in range(3)])
            shape, bound = Box(tuple(half.tolist())), float(np.linalg.norm(half))
        for _ in range(50):  # a free spot inside the walls
            limit = max(room - bound, 0.0)
            at = rng.uniform(-limit, limit, 3)
            if all(np.linalg.norm(at - c) > bound + rc for c, rc in placed):
                break
        else:
            continue
        placed.append((at, bound))
        is_static = i >= moving
        world.add_body(shape, at, _quaternion(rng),
                       velocity=(0, 0, 0) if is_static else _unit(rng) * rng.uniform(0, 50),
                       angular_velocity=(0, 0, 0) if is_static else _unit(rng) * rng.uniform(0, 20),
                       mass=math.inf if is_static else _log_uniform(rng, 1e-3, 1e4),
                       friction=float(rng.uniform(0, 1)), restitution=float(rng.uniform(0, 1)))
    bodies = world.bodies.count
    for _ in range(int(rng.integers(0, 4))):
        a = int(rng.integers(0, bodies))
        if world.bodies.inv_mass[a] == 0.0:
            continue
        local = rng.uniform(-0.5, 0.5, 3) * float(world.bodies.size[a].max())
        kind = HingeJoint if rng.random() < 0.5 else BallJoint
        axis = tuple(_unit(rng).tolist())
        if bodies > 1 and rng.random() < 0.6:
            b = int(rng.integers(0, bodies - 1))
            b += b >= a
            world.add(kind(a, local, b, None, axis=axis))
        else:  # the point where it is, or up to 0.5 m off (pulled there), inside the walls
            anchor = world.bodies.position[a] + world_rotation(world.bodies.orientation[a]) \
                @ local
            if rng.random() < 0.5:
                anchor = np.clip(anchor + rng.uniform(-0.5, 0.5, 3), -room + 0.05, room - 0.05)
            world.add(kind(a, local, None, anchor, axis=axis))
    count = int(rng.integers(0, 5))
    for _ in range(count):
        r = float(rng.uniform(0.05, 0.5))
        limit = max(room - r, 0.0)
        world.add_particle(rng.uniform(-limit, limit, 3), _unit(rng) * rng.uniform(0, 50),
                           mass=_log_uniform(rng, 1e-3, 1e3), radius=r)
    return world, force_free


@dataclass
class Outcome:
    """What one scene did: per check, the first step where it failed (None: never)."""

    seed: int
    force_free: bool
    joints: int
    steps: int = 0
    refused: str | None = None  # the error that ended it, if any
    hang: int | None = None  # a step that would not have returned (see ``HANG_MARK``)
    explosion: int | None = None
    speed: float = 0.0
    gain: int | None = None  # first step gaining > ENERGY_SLACK relative (force-free)
    gain_1e3: int | None = None  # ... > 1e-3 relative
    worst_gain: float = 0.0
    deep: int | None = None
    deepest: float = 0.0
    slowest: float = 0.0  # the longest step [s]
    final: bytes = field(default=b"", repr=False)


def overlap(world: pm.World, contacts: BodyContacts) -> float:
    """The deepest overlap [m] between two bodies or a body and a plane, measured now."""
    b = world.bodies
    planes = [g for g in world.contact_generators if isinstance(g, pm.Plane)]
    exclude = world.joints.pair_keys(b.count) if world.joints else None
    body_collide.generate(b, planes, DT, contacts, margin=0.0, exclude=exclude)
    return float(contacts.depth.max()) if contacts.count else 0.0


def speed(world: pm.World) -> float:
    v = np.concatenate([world.bodies.velocity, world.particles.velocity])
    return float(np.sqrt((v * v).sum(axis=1)).max()) if v.size else 0.0


def run(seed: int, steps: int = STEPS, watchdog: float | None = None,
        **world_args) -> Outcome:
    """Run scene ``seed`` (``world_args``: as ``build``); ``watchdog`` [s]: a step that has not
    returned by then dumps the stacks and ends the process (a numba loop cannot be interrupted
    any other way)."""
    world, force_free = build(seed, **world_args)
    out = Outcome(seed, force_free, len(world.joints))
    contacts = BodyContacts()
    energy = world.kinetic_energy()
    for n in range(1, steps + 1):
        if watchdog is not None:
            faulthandler.dump_traceback_later(watchdog, exit=True)
        start = time.perf_counter()
        try:
            world.step(DT)
        except FloatingPointError as error:
            out.refused = f"step {n}: {type(error).__name__}: {error}"[:300]
            break
        finally:
            if watchdog is not None:
                faulthandler.cancel_dump_traceback_later()
        out.slowest = max(out.slowest, time.perf_counter() - start)
        out.steps = n
        if (world.bodies.angular_velocity == HANG_MARK).any():
            out.hang = n
            break
        fast = speed(world)
        out.speed = max(out.speed, fast)
        if not math.isfinite(fast) or fast > SPEED_LIMIT:
            out.explosion = n
            break
        now = world.kinetic_energy()
        if force_free and energy > 0.0:
            gain = (now - energy) / energy
            out.worst_gain = max(out.worst_gain, gain)
            if gain > ENERGY_SLACK and out.gain is None:
                out.gain = n
            if gain > 1e-3 and out.gain_1e3 is None:
                out.gain_1e3 = n
        energy = now
        depth = overlap(world, contacts)
        out.deepest = max(out.deepest, depth)
        if depth > DEEP and out.deep is None:
            out.deep = n
    b = world.bodies
    out.final = b"".join(np.ascontiguousarray(x).tobytes() for x in (
        b.position, b.orientation, b.velocity, b.angular_velocity, world.particles.position,
        world.particles.velocity))
    return out


def warm_up() -> None:
    """Compile (or load) every kernel the scenes use, before any watchdog runs."""
    world = pm.World()
    world.add(pm.Ground(0.0, friction=0.5))
    a = world.add_body(Box((0.3, 0.2, 0.1)), (0, 0.5, 0))
    b = world.add_body(Sphere(0.2), (0.6, 0.5, 0))
    c = world.add_body(Sphere(0.2), (0, 1.5, 0), mass=math.inf)
    world.add(BallJoint(a, (0.3, 0, 0), b, None))
    world.add(HingeJoint(b, (0, 0.2, 0), None, (0.6, 0.9, 0)))
    world.add(BallJoint(a, (0, 0.2, 0), c, None))
    world.add_particle((0.0, 0.9, 0.0), (0, -3, 0), radius=0.1)
    contacts = BodyContacts()
    for _ in range(30):
        world.step(DT)
        overlap(world, contacts)
        speed(world)
    # a path only some steps take: a light fast sphere between heavy ones (issue 31's)
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    for x in (-2.46, 2.46):
        world.add_body(Sphere(1.0), (x, 0.0, 0.0), mass=7061.0, restitution=1.0)
    world.add_body(Sphere(0.77), (0, 0, 0), mass=0.0125, velocity=(147.5, -20.9, 0),
                   restitution=1.0)
    world.step(DT)


def _child(seeds: list[int], steps: int, hang: float) -> None:
    """Run ``seeds`` in order, printing one line per scene (the parent reads them)."""
    warm_up()
    print("warm", flush=True)
    for seed in seeds:
        print(f"start {seed}", flush=True)
        o = run(seed, steps, watchdog=hang)
        print(f"done {seed} {o.force_free:d} {o.joints} {o.steps} {o.explosion} {o.speed:.3g} "
              f"{o.gain} {o.gain_1e3} {o.worst_gain:.3g} {o.deep} {o.deepest:.3g} "
              f"{o.slowest:.3g} {o.refused is not None:d} {o.hang}", flush=True)


def main() -> None:
    import subprocess

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", default="0:200", help="first:last (exclusive)")
    parser.add_argument("--steps", type=int, default=STEPS)
    parser.add_argument("--hang", type=float, default=5.0, help="a step this long [s] is a hang")
    parser.add_argument("--joint-free", action="store_true",
                        help="only the scenes without joints")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--combine", nargs="+", metavar="LOG",
                        help="count over the logs of runs made in parallel (each one's output)")
    args = parser.parse_args()
    if args.combine:
        _combine(args.combine)
        return
    first, last = (int(s) for s in args.seeds.split(":"))
    seeds = list(range(first, last))
    if args.joint_free:
        seeds = [s for s in seeds if not len(build(s)[0].joints)]
    if args.child:
        _child(seeds, args.steps, args.hang)
        return
    rows, hangs = [], []
    while seeds:
        extra = []
        if args.joint_free:
            extra.append("--joint-free")
        proc = subprocess.Popen([sys.executable, __file__, "--child", "--steps", str(args.steps),
                                 "--hang", str(args.hang), "--seeds",
                                 f"{seeds[0]}:{seeds[-1] + 1}", *extra],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        started = None
        for line in proc.stdout:  # streamed, so a long run shows its progress
            parts = line.split()
            if parts[0] == "warm":
                started = None
                continue
            if parts[0] == "start":
                started = int(parts[1])
            elif parts[0] == "done":
                print(line, end="", flush=True)
                rows.append(parts[1:])
                started = None
        err = proc.stderr.read()
        proc.wait()
        if started is None:
            break
        if "Timeout" not in err:
            raise RuntimeError(f"seed {started} failed:\n{err[-3000:]}")
        hangs.append(started)
        print(f"seed {started}: a step did not return within {args.hang} s", flush=True)
        seeds = [s for s in seeds if s > started]
    _report(rows, hangs)


def _combine(logs: list[str]) -> None:
    """The counts over several runs' logs (parts of a seed range run side by side,
    benchmarks/rigid_device_check.sh): their "done" rows and hangs, reported as one run."""
    rows, hangs = [], []
    for log in logs:
        with open(log) as f:
            for line in f:
                parts = line.split()
                if parts[:1] == ["done"]:
                    rows.append(parts[1:])
                elif line.startswith("seed ") and "did not return" in line:
                    hangs.append(int(parts[1].rstrip(":")))
    _report(rows, hangs)


def _report(rows, hangs) -> None:
    def num(v):
        return None if v == "None" else float(v)

    hangs = hangs + [int(r[0]) for r in rows if r[13] != "None"]
    rows = [r for r in rows if r[13] == "None"]
    n = len(rows) + len(hangs)
    joints = {int(r[0]): int(r[2]) for r in rows}
    expl = [r for r in rows if r[4] != "None"]
    free = [r for r in rows if r[1] == "1"]
    gain9 = [r for r in free if r[6] != "None"]
    gain3 = [r for r in free if r[7] != "None"]
    deep = [r for r in rows if r[9] != "None"]
    deep10 = [r for r in rows if num(r[10]) > 0.1]
    slow = [r for r in rows if num(r[11]) > 1.0]
    refused = [r for r in rows if r[12] == "1"]
    print(f"scenes {n}")
    print(f"hangs (no return within the watchdog): {len(hangs)} {hangs[:20]}")
    print(f"steps slower than 1 s (returned): {len(slow)} {[int(r[0]) for r in slow][:20]}")
    print(f"explosions > {SPEED_LIMIT:g} m/s without error: {len(expl)} "
          f"({sum(joints[int(r[0])] > 0 for r in expl)} with joints) "
          f"{[int(r[0]) for r in expl][:20]}")
    print(f"force-free scenes: {len(free)}; with a step gaining > 1e-9: {len(gain9)}, "
          f"> 1e-3: {len(gain3)} ({sum(int(r[2]) > 0 for r in gain3)} with joints) "
          f"{[int(r[0]) for r in gain9][:30]}")
    print(f"overlap > 2 cm after a step: {len(deep)} scenes (> 10 cm: {len(deep10)}) "
          f"{[int(r[0]) for r in deep][:20]}")
    print(f"refused with an error: {len(refused)}")
    print(f"slowest step: {max((num(r[11]) for r in rows), default=0):.3g} s")


if __name__ == "__main__":
    main()
