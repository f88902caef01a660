"""Why the soft step runs its passes to a tolerance: box stacks, the contact stiffness, the
substeps and the points of a manifold.

    .venv/bin/python benchmarks/soft_stack.py            # the engine: towers and the pyramid
    .venv/bin/python benchmarks/soft_stack.py --model    # the soft step on a 1-D stack

**The engine** (``--seconds``, default 20): for each ``SolverSettings`` of the grid, towers of
10, 20 and 30 unit boxes (1 kg, μ 0.5, e 0, stacked exactly; bench_rigid's tower) and the
210-box pyramid (10 s), sleep off, ``World()`` otherwise: the top box's sideways drift and
sink, the passes a step (whole run, and the last second), the fastest body at the end, CPU
time. The grid: the defaults; Box2D's one solve and one relax pass a substep; the default
stiffness at Box2D's cap (a quarter of the substep rate) by more substeps; a softer contact.

**The model** (``--model``): Box2D v3's soft step (Catto, "Solver2D", 2024; the kernels of
``solver/body_soft.py``: kick, warm start, the biased pass, drift, the relax pass) on a
vertical stack of 10 unit masses that cannot turn, each interface ``points`` identical rows
(a box face's manifold has 4; a 2-D box's 2) with the ground's stiffness doubled, as the
engine's. With one pass a stage, warm started, does the stack come to rest? Each interface's
rows are swept once per pass (``plain``, Gauss–Seidel as the engine does) or solved among
themselves to convergence first (``block``). Prints the largest speed over the last second
of 10 s and the top's sink.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

DT = 1.0 / 60.0
G = 9.81


def softness(hertz: float, zeta: float, h: float) -> tuple[float, float, float]:
    """Box2D's ``b2MakeSoft`` (as ``body_soft.softness``): bias rate, mass and impulse scales."""
    omega = 2.0 * math.pi * hertz
    a1 = 2.0 * zeta + h * omega
    a2 = h * omega * a1
    return omega / a1, a2 / (1.0 + a2), 1.0 / (1.0 + a2)


def model_stack(n: int = 10, hertz: float = 60.0, substeps: int = 4, points: int = 1,
                block: bool = False, relaxation: float = 1.0, seconds: float = 10.0,
                zeta: float = 10.0, push_out: float = 3.0) -> tuple[float, float]:
    """The soft step, one biased and one relax pass a substep, on ``n`` unit masses stacked
    on the ground (unit spacing, starting exactly touching). Returns (the largest speed in the
    last second [m/s], the top mass's sink [m])."""
    h = DT / substeps
    y = np.arange(n) + 0.5
    v = np.zeros(n)
    # interfaces bottom-up, the ground's last (as the engine's collision lists them)
    pairs = [(i - 1, i) for i in range(1, n)] + [(-1, 0)]
    rows = [pair for pair in pairs for _ in range(points)]
    lam = np.zeros(len(rows))
    body = softness(hertz, zeta, h)
    ground = softness(2.0 * hertz, zeta, h)
    inner = 50 if block and points > 1 else 1  # (until the rows stop moving)
    steps = round(seconds / DT)
    fastest = 0.0
    for step in range(steps):
        for _ in range(substeps):
            v -= G * h
            for c, (lo, up) in enumerate(rows):  # warm start
                v[up] += lam[c]
                if lo >= 0:
                    v[lo] -= lam[c]
            for bias_on in (True, False):
                for first in range(0, len(rows), points):
                    for _ in range(inner):
                        moved = 0.0
                        for c in range(first, first + points):
                            lo, up = rows[c]
                            mass = 0.5 if lo >= 0 else 1.0
                            s = y[up] - (y[lo] + 1.0 if lo >= 0 else 0.5)
                            vn = v[up] - (v[lo] if lo >= 0 else 0.0)
                            rate, mass_scale, impulse_scale = body if lo >= 0 else ground
                            if s > 0.0:  # speculative: close the gap, no more
                                bias, mass_scale, impulse_scale = s / h, 1.0, 0.0
                            elif bias_on:
                                bias = max(mass_scale * rate * s, -push_out)
                            else:
                                bias, mass_scale, impulse_scale = 0.0, 1.0, 0.0
                            over = relaxation if bias_on else 1.0
                            new = max(lam[c] - over * (mass * (mass_scale * vn + bias)
                                                       + impulse_scale * lam[c]), 0.0)
                            d = new - lam[c]
                            lam[c] = new
                            v[up] += d
                            if lo >= 0:
                                v[lo] -= d
                            moved = max(moved, abs(d))
                        if moved < 1e-15:
                            break
                if bias_on:
                    y += v * h  # drift between the biased and the relax pass
        if step >= steps - round(1.0 / DT):
            fastest = max(fastest, float(np.abs(v).max()))
    return fastest, float(y[-1] - (n - 0.5))


def model_table() -> None:
    print("the soft step on a 1-D stack of 10 (one biased + one relax pass a substep; "
          "largest speed in the 10th second, top's sink)\n")
    print("| substeps | hertz | ω·h | points | rows | ω (SOR) | largest \\|v\\| [m/s] "
          "| sink [mm] |")
    print("|---|---|---|---|---|---|---|---|")
    for substeps, hertz in ((4, 30.0), (4, 60.0), (4, 120.0), (4, 240.0), (8, 120.0),
                            (16, 240.0)):
        for points, block in ((1, False), (4, False), (4, True)):
            for relaxation in (1.0, 1.5):
                speed, sink = model_stack(hertz=hertz, substeps=substeps, points=points,
                                          block=block, relaxation=relaxation)
                wh = 2.0 * math.pi * hertz * DT / substeps
                kind = "block" if block else "plain"
                print(f"| {substeps} | {hertz:g} | {wh:.2f} | {points} | {kind} | "
                      f"{relaxation:g} | {speed:.1e} | {sink * 1e3:.2f} |", flush=True)


def engine_table(seconds: float) -> None:
    import pointmass as pm
    from pointmass.rigid.shapes import Box

    sys.path.insert(0, str(Path(__file__).parent))
    import bench_rigid

    def run(build, steps):
        world, top = build()
        passes = []
        start = top.position.copy()
        clock = time.process_time()
        for _ in range(steps):
            passes.append(world.step(DT).velocity_passes)
        clock = time.process_time() - clock
        d = top.position - start
        return (math.hypot(d[0], d[2]), float(d[1]), float(np.mean(passes)),
                float(np.mean(passes[-60:])),
                float(np.linalg.norm(world.bodies.velocity, axis=1).max()), clock)

    def tower(n, settings):
        def build():
            world = pm.World(gravity=(0.0, -G, 0.0), sleep=False, settings=settings)
            world.add(pm.Ground(restitution=0.0, friction=0.5))
            boxes = [world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.5 + k, 0.0), mass=1.0,
                                    friction=0.5, restitution=0.0) for k in range(n)]
            return world, boxes[-1]
        return build

    def pyramid(settings):
        def build():
            scene = bench_rigid.pyramid()
            world = pm.World(gravity=(0.0, -G, 0.0), sleep=False, settings=settings)
            world.add(pm.Ground(restitution=0.0, friction=0.5))
            bodies = [world.add_body(Box((scene.half,) * 3), x, mass=1.0, friction=0.5,
                                     restitution=0.0) for x in scene.position]
            return world, bodies[-1]
        return build

    grid = {"defaults": {},
            "Box2D's passes (1 + 1)": dict(soft_solve_passes=1, soft_relax_passes=1),
            "16 substeps (ω·h = π/2), 1 + 1": dict(soft_substeps=16, soft_solve_passes=1,
                                                   soft_relax_passes=1),
            "16 substeps (ω·h = π/2)": dict(soft_substeps=16),
            "120 Hz": dict(contact_hertz=120.0)}
    print(f"the engine, sleep off: towers {seconds:g} s, the 210-box pyramid 10 s\n")
    print("| settings | scene | drift xy [mm] | dz [mm] | passes/step (last 1 s) "
          "| max \\|v\\| at the end [m/s] | CPU [s] |")
    print("|---|---|---|---|---|---|---|")
    for name, fields in grid.items():
        settings = pm.SolverSettings(**fields)
        scenes = [(f"tower of {n}", tower(n, settings), round(seconds / DT))
                  for n in (10, 20, 30)] + [("pyramid", pyramid(settings), round(10 / DT))]
        for label, build, steps in scenes:
            xy, dz, passes, last, speed, clock = run(build, steps)
            print(f"| {name} | {label} | {xy * 1e3:.2f} | {dz * 1e3:.2f} | {passes:.1f} "
                  f"({last:.1f}) | {speed:.1e} | {clock:.2f} |", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--model", action="store_true", help="the 1-D model's table instead")
    parser.add_argument("--seconds", type=float, default=20.0, help="the towers' run [s]")
    args = parser.parse_args()
    if args.model:
        model_table()
    else:
        engine_table(args.seconds)


if __name__ == "__main__":
    main()
