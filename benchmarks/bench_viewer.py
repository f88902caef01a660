"""The viewer's speed in a real window (run it under Xvfb; prints figures, asserts nothing).

    xvfb-run -a -s "-screen 0 1920x1080x24" .venv/bin/python benchmarks/bench_viewer.py \
        [--counts 1000 10000] [--frames 90] [--size 1280x720]

For each sphere count: the ball pit (``demos/14_ball_pit.py`` when it exists, else an equivalent
built here: spheres dropped into a walled pit) runs in a ViewerWindow, frames driven by ``tick``
with the real time between them (so the clock's caps act as in use), after ``--settle``
simulated seconds so the pile is at rest (the steady state a user watches). Reported per count:
frames/s with the panel shown and hidden, the panel's cost per frame (ImGui new_frame to the
end of its draw), physics ms per step, and the physics share of the frame (with the
viewer's default, overlap on, the physics runs beside the drawing, so the share nears 100% when
physics is the longer of the two). Pure rendering (paused) frames/s is also shown.

Then overlap (issue 9): the same window with physics stepped in line and in the worker thread
beside the drawing, in alternating blocks of frames (the pile keeps pouring, so alternating
keeps the two comparable), panel shown. Per frame (medians): physics ms (the frame's steps,
in the worker with overlap), drawing ms (main thread: panel, capture, render, blit, flip),
frame ms (events to the end of both), frames/s, and the ratio fps / (1000 / max(physics,
drawing)): 1 when a frame takes only as long as the longer of the two.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

import pointmass as pm


def pit_scene(count: int, seed: int = 0) -> pm.Scene:
    """``count`` spheres (r = 0.15 m) dropped in layers into a walled pit sized for them."""
    rng = np.random.default_rng(seed)
    r = 0.15
    side = max(3.0, float(np.sqrt(count / 4.0)) * 2 * r * 1.2)    # ~4 layers when settled
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    per_layer = max(1, int((side / (2.2 * r)) ** 2))
    layers = int(np.ceil(count / per_layer))
    pos = np.c_[rng.uniform(-side / 2 + r, side / 2 - r, count),
                r + 2.4 * r * (np.arange(count) // per_layer) + rng.uniform(0, 0.1, count),
                rng.uniform(-side / 2 + r, side / 2 - r, count)]
    world.add_particles(pos, radii=r)
    world.add(pm.Ground(height=0.0, restitution=0.3))
    for n in ((1, 0, 0), (-1, 0, 0), (0, 0, 1), (0, 0, -1)):
        world.add(pm.Plane(normal=n, offset=-side / 2, restitution=0.3))
    world.add(pm.SphereCollisions(restitution=0.3))
    del layers
    return pm.Scene(world, camera=pm.CameraHint(target=(0, 0.5, 0), distance=side * 1.6,
                                                yaw=30, pitch=35))


def ball_pit(count: int):
    """The demo's Simulation when the demo exists (its count parameter set), else ours."""
    try:
        from pointmass.demo import Simulation, load_demo
        from pointmass.params import param_specs

        demo = load_demo("ball_pit")
        sim = Simulation(demo)
        ints = [s for s in param_specs(sim.params) if s.kind is int and s.rebuild]
        if ints:
            sim.set_param(ints[0].name, count)
            if sim.scene.world.particles.count >= count * 0.9:
                return sim, "demos/14_ball_pit.py"
    except (ValueError, FileNotFoundError):
        pass
    from pointmass import Simulation

    return Simulation(pit_scene(count)), "bench pit scene"


def measure(window, frames: int) -> dict:
    v = window.viewer
    fps, gui, share, step = [], [], [], []
    last = time.perf_counter()
    for _ in range(frames):
        window.dispatch_events()
        now = time.perf_counter()
        v.update(now - last)
        last = now
        window.switch_to()
        window.on_draw()
        window.flip()
        v.join_physics()                      # the frame's steps (in line, or beside the draw)
        frame = time.perf_counter() - now
        fps.append(1.0 / frame)
        gui.append(v.stats.gui_ms)
        share.append(v.physics_seconds / frame)
        if v.physics_steps:
            step.append(1e3 * v.physics_seconds / v.physics_steps)
    med = statistics.median
    return {"fps": med(fps), "gui_ms": med(gui), "share": med(share),
            "step_ms": med(step) if step else float("nan")}


def measure_overlap(window, frames: int, block: int = 15) -> dict:
    """Frames in alternating blocks with overlap off and on; per mode the medians of physics,
    drawing and frame ms."""
    v = window.viewer
    got = {False: ([], [], []), True: ([], [], [])}
    last = time.perf_counter()
    for i in range(2 * frames):
        overlap = (i // block) % 2 == 1
        v.overlap = overlap
        t0 = time.perf_counter()
        window.dispatch_events()
        v.update(t0 - last)
        last = t0
        t1 = time.perf_counter()
        window.switch_to()
        window.on_draw()
        window.flip()
        t2 = time.perf_counter()
        v.join_physics()
        t3 = time.perf_counter()
        physics, drawing, frame = got[overlap]
        physics.append(1e3 * v.physics_seconds)
        drawing.append(1e3 * (t2 - t1))
        frame.append(1e3 * (t3 - t0))
    out = {}
    for overlap, (physics, drawing, frame) in got.items():
        p, d, f = (statistics.median(x) for x in (physics, drawing, frame))
        out[overlap] = {"physics": p, "drawing": d, "frame": f, "fps": 1e3 / f,
                        "ratio": (1e3 / f) / (1e3 / max(p, d))}
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--counts", type=int, nargs="+", default=[1000, 10000])
    parser.add_argument("--frames", type=int, default=90)
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--settle", type=float, default=2.0,
                        help="simulated seconds run before measuring (a resting pile)")
    args = parser.parse_args()
    size = tuple(int(x) for x in args.size.split("x"))

    from pointmass.app import open_window

    for count in args.counts:
        sim, source = ball_pit(count)
        t0 = time.perf_counter()
        steps = max(3, round(args.settle / sim.scene.dt))
        for _ in range(steps):                 # compile the kernels, let the pile settle
            sim.step()
        settle_s = time.perf_counter() - t0
        window = open_window(sim, size=size, output_dir="/tmp")
        window.dispatch_events()
        measure(window, 10)                    # warm up: shaders, buffers, the atlas
        shown = measure(window, args.frames)
        window.viewer.act("panel")
        hidden = measure(window, args.frames)
        window.viewer.act("pause")
        paused = measure(window, max(20, args.frames // 3))
        window.viewer.act("pause")
        window.viewer.act("panel")
        overlap = measure_overlap(window, args.frames)
        window.close()
        print(f"{count:>6} spheres ({source}, {size[0]}x{size[1]}): "
              f"{shown['fps']:.1f} frames/s with the panel, {hidden['fps']:.1f} without, "
              f"{paused['fps']:.1f} paused (render only); panel {shown['gui_ms']:.2f} ms/frame; "
              f"physics {shown['step_ms']:.2f} ms/step, {100 * shown['share']:.0f}% of the "
              f"frame ({sim.scene.world.contacts.count} contacts; settling took {settle_s:.1f} s)")
        for on in (False, True):
            m = overlap[on]
            print(f"{count:>6} spheres, overlap {'on ' if on else 'off'}: physics "
                  f"{m['physics']:.1f} ms, drawing {m['drawing']:.1f} ms, frame "
                  f"{m['frame']:.1f} ms per frame, {m['fps']:.1f} frames/s; fps / (1000 / "
                  f"max(physics, drawing)) = {m['ratio']:.2f}")


if __name__ == "__main__":
    main()
