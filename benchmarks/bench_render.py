"""Rendering and recording speed on this machine (no assertions; prints figures and ratios).

    .venv/bin/python benchmarks/bench_render.py [--spheres 10000] [--frames 60] [--size 1280x720]
        [--path auto|hardware|software] [--rounds 5] [--no-record] [--demo particle_storm]

0. The GL renderer's name, the path the renderer took (``render/path.py``: "software" on
   llvmpipe, "hardware" on a GPU, or forced), and the renderer's own CPU work per frame by
   stage (capture: positions, look, lines; shadows; uploads) apart from the GL calls that draw
   (the driver's: on llvmpipe they rasterize too) and the wait for the GPU to finish.
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


def timed_together(fns, frames: int, warmup: int = 3, rounds: int = 5, sync=None):
    """Like ``timed`` for several functions, their rounds interleaved, so that a slow spell of
    the machine hits them alike (ratios between them stay fair). ``sync`` (ctx.finish) ends
    each round inside its time, so frames left queued on the GPU are counted. Returns
    (frames/s, CPU seconds per frame) lists: each function's best round by each measure."""
    for fn in fns:
        for _ in range(warmup):
            fn()
        if sync is not None:
            sync()
    best = [float("inf")] * len(fns)
    cpu = [float("inf")] * len(fns)
    for _ in range(rounds):
        for k, fn in enumerate(fns):
            t0, c0 = time.perf_counter(), time.process_time()
            for _ in range(frames):
                fn()
            if sync is not None:
                sync()
            best[k] = min(best[k], time.perf_counter() - t0)
            cpu[k] = min(cpu[k], time.process_time() - c0)
    return [frames / b for b in best], [c / frames for c in cpu]


def bare_impostors(ctx: moderngl.Context, renderer: Renderer, scene: pm.Scene, camera, *,
                   read: bool = True):
    """A minimal instanced-impostor draw of the scene's spheres into the renderer's fbo, plus
    the same readback (``read``; else none, as a window): one upload, clear, one write of the camera
    block, one draw call of spheres.glsl, nothing else."""
    prog = renderer.programs["spheres"]
    try:
        from pointmass.render.frame_block import FrameUniforms
        frame_block = FrameUniforms(ctx, [prog])   # the camera and light (one buffer write)
    except ImportError:                            # a checkout from before the Frame block
        frame_block = None
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
        if frame_block is not None:
            frame_block.write(view, proj, view @ proj, (0.0, 0.6, 0.8), (0.0, 1.0, 0.0),
                              (0.0, 0.6, 0.8), (float(w), float(h)), 1.0)
        else:
            prog["u_view"].write(view.tobytes())
            prog["u_proj"].write(proj.tobytes())
            prog["u_light"].value = (0.0, 0.6, 0.8)
            prog["u_sky"].value = (0.0, 1.0, 0.0)
        vao.render(moderngl.TRIANGLE_STRIP, vertices=4, instances=p.count)
        if read:
            renderer.read_rgb()

    return frame


def cpu_breakdown(ctx, renderer: Renderer, scene, camera, frames: int) -> None:
    """Print the renderer's own CPU milliseconds per frame by stage, the GL calls' and the
    wait for the GPU (ctx.finish), averaged over ``frames`` frames."""
    total = dict.fromkeys(renderer.stats, 0.0)
    wait = 0.0
    for _ in range(frames):
        renderer.render(scene, camera)
        t0 = time.perf_counter()
        ctx.finish()
        wait += time.perf_counter() - t0
        for k, v in renderer.stats.items():
            total[k] += v / frames
    own = total["capture"] + total["shadows"] + total["upload"]
    print(f"renderer's own CPU/frame : {own:6.1f} ms (capture {total['capture']:.1f}, shadows "
          f"{total['shadows']:.1f}, uploads {total['upload']:.1f})")
    print(f"GL calls (driver)/frame  : {total['draw_calls']:6.1f} ms, then waiting for the GPU "
          f"{1e3 * wait / frames:.1f} ms")


def demo_fps(ctx, name: str, overrides: list[str], size, path: str | None,
             frames: int) -> None:
    """A demo stepped and drawn window-less, 1/60 s of simulation per frame (what its window
    does at 60 Hz), one after the other (the window overlaps them): frames/s of step +
    render, of the steps alone and of the render alone."""
    from pointmass.demo import Simulation, load_demo

    sim = Simulation(load_demo(name), overrides=overrides)
    renderer = Renderer(ctx, size, path=path)
    camera = OrbitCamera.from_hint(sim.scene.camera)
    n = sim.world.particles.count
    for _ in range(3):                                    # compile, warm up
        sim.advance(1 / 60)
        renderer.render(sim.scene, camera)
        ctx.finish()
    t0 = time.perf_counter()
    for _ in range(frames):
        sim.advance(1 / 60)
    step = (time.perf_counter() - t0) / frames
    t0 = time.perf_counter()
    for _ in range(frames):
        renderer.render(sim.scene, camera)
    ctx.finish()
    draw = (time.perf_counter() - t0) / frames
    t0 = time.perf_counter()
    for _ in range(frames):                               # no wait per frame, as a window
        sim.advance(1 / 60)
        renderer.render(sim.scene, camera)
    ctx.finish()
    both = (time.perf_counter() - t0) / frames
    print(f"demo {name} ({n} particles, {renderer.path} path, {size[0]}x{size[1]}): "
          f"step + render {1 / both:6.1f} frames/s; steps alone {1 / step:6.1f}/s; "
          f"render alone {1 / draw:6.1f} frames/s")
    renderer.release()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spheres", type=int, default=10_000)
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--size", default="1280x720")
    ap.add_argument("--path", default=None, help="hardware, software or auto (default: "
                    "$POINTMASS_RENDER_PATH, else auto)")
    ap.add_argument("--record-frames", type=int, default=300)
    ap.add_argument("--no-record", action="store_true", help="skip the recording figures")
    ap.add_argument("--no-bare", action="store_true", help="skip the timed comparisons "
                    "(only the CPU breakdown)")
    ap.add_argument("--demo", help="also step and draw this demo window-less")
    ap.add_argument("--set", action="append", default=[], help="the demo's NAME=VALUE")
    ap.add_argument("--save", help="write the full renderer's frame to this PNG")
    args = ap.parse_args()
    size = tuple(int(x) for x in args.size.split("x"))

    ctx = create_headless_context()
    scene = sphere_scene(args.spheres)
    camera = OrbitCamera.from_hint(scene.camera)
    renderer = Renderer(ctx, size, path=args.path)
    print(f"GL renderer: {ctx.info['GL_RENDERER']} ({ctx.info['GL_VERSION']}); "
          f"path: {renderer.path}; {size[0]}x{size[1]}, {args.spheres} spheres")
    renderer.render(scene, camera)                        # first frame: the look goes up
    ctx.finish()
    cpu_breakdown(ctx, renderer, scene, camera, max(2, min(args.frames, 20)))
    if args.demo:
        demo_fps(ctx, args.demo, args.set, size, args.path, max(3, args.frames))
    if args.no_bare:
        return

    def full() -> None:
        renderer.render(scene, camera)
        renderer.read_rgb()

    def full_async() -> None:
        renderer.render(scene, camera)
        renderer.read_rgb_later()

    def full_no_read() -> None:
        # As a window draws: no wait per frame (the round ends with a finish), so the CPU
        # prepares a frame while the GPU draws the last.
        renderer.render(scene, camera)

    orbit = OrbitCamera.from_hint(scene.camera)

    def full_orbit() -> None:
        orbit.yaw += 0.5                        # [deg]: the sky and ground are redrawn
        renderer.render(scene, orbit)
        renderer.read_rgb()

    bare = bare_impostors(ctx, renderer, scene, camera)
    bare_nr = bare_impostors(ctx, renderer, scene, camera, read=False)
    (fps_full, fps_bare, fps_full_nr, fps_orbit, fps_async, fps_bare_nr), \
        (cpu_full, cpu_bare, _, cpu_orbit, _, _) = \
        timed_together([full, bare, full_no_read, full_orbit, full_async, bare_nr],
                       args.frames, rounds=args.rounds, sync=ctx.finish)
    renderer.read_pending()
    if args.save:
        from PIL import Image
        renderer.render(scene, camera)
        Image.fromarray(renderer.read_rgb()).save(args.save)
    fps_read = timed(renderer.read_rgb, args.frames, rounds=min(args.rounds, 3))
    print(f"full renderer + readback : {fps_full:6.1f} frames/s, "
          f"{1e3 * cpu_full:5.1f} ms CPU/frame")
    print(f"full + PBO readback      : {fps_async:6.1f} frames/s (two frames in flight)")
    print(f"  camera orbiting        : {fps_orbit:6.1f} frames/s, "
          f"{1e3 * cpu_orbit:5.1f} ms CPU/frame")
    print(f"full renderer, no read   : {fps_full_nr:6.1f} frames/s")
    print(f"bare impostors + readback: {fps_bare:6.1f} frames/s, "
          f"{1e3 * cpu_bare:5.1f} ms CPU/frame")
    print(f"bare impostors, no read  : {fps_bare_nr:6.1f} frames/s")
    print(f"readback alone           : {fps_read:6.1f} frames/s")
    print(f"ratio full / bare        : {fps_full / fps_bare:6.2f} (CPU time: "
          f"{cpu_bare / cpu_full:.2f}); orbiting {fps_orbit / fps_bare:.2f} "
          f"(CPU time: {cpu_bare / cpu_orbit:.2f}); no read {fps_full_nr / fps_bare_nr:.2f}")
    if args.no_record:
        return

    # Recording: the side-library demo at 720p (shaders already compiled: one renderer), vs
    # encoding the same frames alone.
    from pointmass.demo import Simulation, load_demo
    from pointmass.render.recording import record

    n = args.record_frames
    rec = Renderer(ctx, (1280, 720), path=args.path)
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
