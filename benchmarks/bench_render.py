"""Rendering and recording speed on this machine (no assertions; prints figures and ratios).

    .venv/bin/python benchmarks/bench_render.py [--spheres 10000] [--frames 60] [--size 1280x720]

1. Full renderer (ground, blob shadows, impostor spheres, links) + readback, frames/s, with the
   camera still (the sky and ground kept from frame to frame) and orbiting (redrawn each frame).
2. A bare instanced-impostor draw of the same spheres (spheres.glsl alone, one upload, no ground,
   no shadows) + the same readback, in the same run: the ratio full / bare. Besides wall-clock
   frames/s, the process's CPU time per frame (every thread's: llvmpipe's rasterizer threads
   are ours), whose ratio says how much work each frame is and varies less on a shared machine.
3. Recording a 720p mp4 (render + readback + encode in a thread) vs encoding the same frames
   alone: the ratio record / encode-only.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import moderngl
import numpy as np

import pointmass as pm
from pointmass.render import OrbitCamera, Renderer, create_headless_context
from pointmass.render.video import VideoWriter


def sphere_scene(count: int, seed: int = 0) -> pm.Scene:
    """``count`` spheres (r = 0.12 m) over a 24 × 24 m patch, up to 3 m high; 1000 springs."""
    rng = np.random.default_rng(seed)
    world = pm.World()
    pos = np.c_[rng.uniform(-12, 12, count), rng.uniform(0.12, 3.0, count),
                rng.uniform(-12, 12, count)]
    # Every other pair of the first 2000 is a short spring (a partner 0.5 m away).
    springs = np.arange(0, min(count, 2000) - 1, 2)
    pos[springs + 1] = pos[springs] + rng.normal(0.0, 0.3, (len(springs), 3))
    pos[:, 1] = np.abs(pos[:, 1] - 0.12) + 0.12
    world.add_particles(pos, radii=0.12)
    world.add(pm.Spring(springs, springs + 1, 10.0, 0.5))
    return pm.Scene(world, camera=pm.CameraHint(target=(0, 0.5, 0), distance=26, yaw=30,
                                                pitch=28))


def timed(fn, frames: int, warmup: int = 3, rounds: int = 3) -> float:
    """Frames per second of ``fn``: the best of ``rounds`` runs of ``frames`` frames (after a
    warm-up). The best run is the one least disturbed by other work on a shared machine."""
    return timed_together([fn], frames, warmup, rounds)[0][0]


def timed_together(fns, frames: int, warmup: int = 3, rounds: int = 5):
    """Like ``timed`` for several functions, their rounds interleaved, so that a slow spell of
    the machine hits them alike (ratios between them stay fair). Returns (frames/s, CPU
    seconds per frame) lists: each function's best round by each measure."""
    for fn in fns:
        for _ in range(warmup):
            fn()
    best = [float("inf")] * len(fns)
    cpu = [float("inf")] * len(fns)
    for _ in range(rounds):
        for k, fn in enumerate(fns):
            t0, c0 = time.perf_counter(), time.process_time()
            for _ in range(frames):
                fn()
            best[k] = min(best[k], time.perf_counter() - t0)
            cpu[k] = min(cpu[k], time.process_time() - c0)
    return [frames / b for b in best], [c / frames for c in cpu]


def bare_impostors(ctx: moderngl.Context, renderer: Renderer, scene: pm.Scene, camera):
    """A minimal instanced-impostor draw of the scene's spheres into the renderer's fbo, plus
    the same readback: one upload, clear, one draw call of spheres.glsl, nothing else."""
    prog = renderer.programs["spheres"]
    quad = ctx.buffer(np.array([-1, -1, 1, -1, -1, 1, 1, 1], "f4").tobytes())
    p = scene.world.particles
    data = np.zeros((p.count, 8), "f4")
    inst = ctx.buffer(reserve=data.nbytes, dynamic=True)
    vao = ctx.vertex_array(prog, [(quad, "2f", "in_corner"),
                                  (inst, "4f 4f/i", "in_sphere", "in_color")])
    w, h = renderer.size
    view, proj = camera.view_matrix(), camera.projection_matrix(w / h)
    colors = scene.particle_colors()

    def frame() -> None:
        data[:, 0:3] = p.position
        data[:, 3] = p.radius
        data[:, 4:7] = colors
        inst.write(data)
        renderer.fbo.use()
        ctx.clear(0.1, 0.1, 0.1, 1.0, depth=1.0)
        ctx.enable(moderngl.DEPTH_TEST)
        prog["u_view"].write(view.tobytes())
        prog["u_proj"].write(proj.tobytes())
        prog["u_light"].value = (0.0, 0.6, 0.8)
        prog["u_sky"].value = (0.0, 1.0, 0.0)
        vao.render(moderngl.TRIANGLE_STRIP, vertices=4, instances=p.count)
        renderer.read_rgb()

    return frame


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spheres", type=int, default=10_000)
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--size", default="1280x720")
    ap.add_argument("--record-frames", type=int, default=300)
    ap.add_argument("--save", help="write the full renderer's frame to this PNG")
    args = ap.parse_args()
    size = tuple(int(x) for x in args.size.split("x"))

    ctx = create_headless_context()
    scene = sphere_scene(args.spheres)
    camera = OrbitCamera.from_hint(scene.camera)
    renderer = Renderer(ctx, size)

    def full() -> None:
        renderer.render(scene, camera)
        renderer.read_rgb()

    def full_no_read() -> None:
        renderer.render(scene, camera)
        ctx.finish()

    orbit = OrbitCamera.from_hint(scene.camera)

    def full_orbit() -> None:
        orbit.yaw += 0.5                        # [deg]: the sky and ground are redrawn
        renderer.render(scene, orbit)
        renderer.read_rgb()

    print(f"{ctx.info['GL_RENDERER']}, {size[0]}x{size[1]}, {args.spheres} spheres")
    bare = bare_impostors(ctx, renderer, scene, camera)
    (fps_full, fps_bare, fps_full_nr, fps_orbit), (cpu_full, cpu_bare, _, cpu_orbit) = \
        timed_together([full, bare, full_no_read, full_orbit], args.frames)
    if args.save:
        from PIL import Image
        renderer.render(scene, camera)
        Image.fromarray(renderer.read_rgb()).save(args.save)
    fps_read = timed(renderer.read_rgb, args.frames)
    print(f"full renderer + readback : {fps_full:6.1f} frames/s, "
          f"{1e3 * cpu_full:5.1f} ms CPU/frame")
    print(f"  camera orbiting        : {fps_orbit:6.1f} frames/s, "
          f"{1e3 * cpu_orbit:5.1f} ms CPU/frame")
    print(f"full renderer, no read   : {fps_full_nr:6.1f} frames/s")
    print(f"bare impostors + readback: {fps_bare:6.1f} frames/s, "
          f"{1e3 * cpu_bare:5.1f} ms CPU/frame")
    print(f"readback alone           : {fps_read:6.1f} frames/s")
    print(f"ratio full / bare        : {fps_full / fps_bare:6.2f} (CPU time: "
          f"{cpu_bare / cpu_full:.2f}); orbiting {fps_orbit / fps_bare:.2f} "
          f"(CPU time: {cpu_bare / cpu_orbit:.2f})")

    # Recording: the side-library demo at 720p (shaders already compiled: one renderer), vs
    # encoding the same frames alone.
    from pointmass.demo import Simulation, load_demo
    from pointmass.render.recording import record

    n = args.record_frames
    rec = Renderer(ctx, (1280, 720))
    with tempfile.TemporaryDirectory() as tmp:
        sim = Simulation(load_demo("side_library"))
        cam = OrbitCamera.from_hint(sim.scene.camera)
        frames = []
        t0 = time.perf_counter()
        for _ in range(n):
            rec.render(sim.scene, cam, trails=sim.trails)
            frames.append(rec.read_rgb())
            sim.advance(1 / 30)
        fps_render_only = n / (time.perf_counter() - t0)
        t0 = time.perf_counter()
        with VideoWriter(Path(tmp) / "enc.mp4", (1280, 720), 30) as w:
            for f in frames:
                w.write(f)
        fps_encode = n / (time.perf_counter() - t0)
        del frames
        sim = Simulation(load_demo("side_library"))
        result = record(sim, Path(tmp) / "rec.mp4", seconds=n / 30, fps=30, size=(1280, 720),
                        progress=False, renderer=rec)
        fps_record = result.frames / result.seconds
    rec.release()
    print(f"record 720p mp4          : {fps_record:6.1f} frames/s ({n} frames, side_library)")
    print(f"render + read + step     : {fps_render_only:6.1f} frames/s")
    print(f"encode only (same frames): {fps_encode:6.1f} frames/s")
    print(f"ratio record / encode    : {fps_record / fps_encode:6.2f}")


if __name__ == "__main__":
    main()
