"""The renderer's figures on a GPU in one process (one numba compile, one GL context), for
``gpu_render_check.sh`` on the device machine; runs anywhere (llvmpipe with small sizes).

    python benchmarks/gpu_check.py [--sizes 10000,100000,1000000] [--size 1920x1080]
        [--frames 120] [--storm] [--label after]

Per sphere count (bench_render.py's crowd, 1 000 springs, the hardware path unless --path):
frames/s of the full renderer with a synchronous readback (``read_rgb``), with the pixel-buffer
readback (``read_rgb_later``), without readback, and of the bare impostor draw with and without
readback, their rounds interleaved (best of 3); full / bare; the CPU per ``render`` with the
GPU wait excluded (many renders, then one finish); GPU milliseconds per frame from timer
queries (full, without shadows, without ground and shadows, bare). Then, with --storm,
particle_storm stepped and drawn window-less. Ends with one table row per size (lines that
start ``ROW``).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_render import bare_impostors, demo_fps, sphere_scene, timed_together

from pointmass.render import OrbitCamera, Renderer, create_headless_context


def gpu_ms(ctx, fn, n: int = 30) -> float:
    """GPU milliseconds per call of ``fn`` (a timer query around ``n`` calls)."""
    fn()
    ctx.finish()
    q = ctx.query(time=True)
    with q:
        for _ in range(n):
            fn()
    ctx.finish()
    return q.elapsed / n / 1e6


def cpu_ms(ctx, fn, n: int = 30) -> float:
    """Wall milliseconds per call of ``fn`` issued back to back, the GPU wait excluded (one
    finish before; the finish after is not counted)."""
    fn()
    ctx.finish()
    t0 = time.perf_counter()
    for _ in range(n):
        fn()
    t = 1e3 * (time.perf_counter() - t0) / n
    ctx.finish()
    return t


def one_size(ctx, n: int, size, frames: int, path: str | None, save: str | None) -> dict:
    scene = sphere_scene(n)
    cam = OrbitCamera.from_hint(scene.camera)
    r = Renderer(ctx, size, path=path)
    for _ in range(3):
        r.render(scene, cam)
    ctx.finish()

    def full_read():
        r.render(scene, cam)
        r.read_rgb()

    def full_pbo():
        r.render(scene, cam)
        r.read_rgb_later()

    def full():
        r.render(scene, cam)

    bare_read = bare_impostors(ctx, r, scene, cam)
    bare = bare_impostors(ctx, r, scene, cam, read=False)
    fps, _ = timed_together([full_read, full_pbo, full, bare_read, bare], frames, rounds=3,
                            sync=ctx.finish)
    r.read_pending()
    out = dict(zip(("full_read", "full_pbo", "full", "bare_read", "bare"), fps))
    k = max(5, min(frames, 60))
    out["cpu_render"] = cpu_ms(ctx, full, k)
    out["cpu_bare"] = cpu_ms(ctx, bare, k)
    frame = r.capture(scene)
    out["cpu_capture"] = cpu_ms(ctx, lambda: r.capture(scene), k)
    out["cpu_draw"] = cpu_ms(ctx, lambda: r.draw(frame, cam), k)
    try:
        out["gpu_full"] = gpu_ms(ctx, lambda: r.draw(frame, cam), k)
        if hasattr(r, "shadows"):               # (not on a checkout from before it)
            r.shadows = False
            out["gpu_no_shadows"] = gpu_ms(ctx, lambda: r.draw(frame, cam), k)
            r.shadows = True
        no_ground = dataclasses.replace(frame, show_ground=False)
        out["gpu_no_ground"] = gpu_ms(ctx, lambda: r.draw(no_ground, cam), k)
        out["gpu_bare"] = gpu_ms(ctx, bare, k)
    except Exception as e:                      # no timer queries on this context
        print(f"(no GPU timer queries: {e})")
    if save:
        from PIL import Image
        r.render(scene, cam)
        Image.fromarray(r.read_rgb()).save(save)
    print(f"{n} spheres, {r.path} path: " + ", ".join(f"{k} {v:.3f}" for k, v in out.items()),
          flush=True)
    r.release()
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="10000,100000,1000000")
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--frames", type=int, default=120, help="frames per round at 10 000 "
                    "spheres (fewer for more: 10 000 / N of it, at least 10)")
    ap.add_argument("--path", default=None)
    ap.add_argument("--storm", action="store_true", help="also particle_storm (1 M particles)")
    ap.add_argument("--storm-frames", type=int, default=60)
    ap.add_argument("--set", action="append", default=[], help="particle_storm's NAME=VALUE")
    ap.add_argument("--label", default="")
    ap.add_argument("--save-dir", default=None, help="write each size's frame as a PNG here")
    args = ap.parse_args()
    size = tuple(int(x) for x in args.size.split("x"))
    ctx = create_headless_context()
    print(f"GL renderer: {ctx.info['GL_RENDERER']} ({ctx.info['GL_VERSION']}); "
          f"{size[0]}x{size[1]}; {args.label}", flush=True)
    head = ("spheres", "full+read", "full+PBO", "full", "bare+read", "bare", "f/b read",
            "f/b", "CPU render", "CPU bare", "capture", "draw", "GPU full", "GPU no shadows",
            "GPU no ground", "GPU bare")
    print("ROW | " + " | ".join(head) + f" | {args.label}", flush=True)
    for n in (int(s) for s in args.sizes.split(",") if s):
        frames = max(10, round(args.frames * min(1.0, (10_000 / n) ** 0.5)))
        save = f"{args.save_dir}/frame_{n}.png" if args.save_dir else None
        o = one_size(ctx, n, size, frames, args.path, save)
        # Each row as soon as it is measured: a run cut short keeps what it had.
        cells = [f"{n}", *(f"{o[k]:.1f}" for k in ("full_read", "full_pbo", "full",
                                                   "bare_read", "bare")),
                 f"{o['full_read'] / o['bare_read']:.2f}", f"{o['full'] / o['bare']:.2f}",
                 *(f"{o[k]:.3f}" if k in o else "-"
                   for k in ("cpu_render", "cpu_bare", "cpu_capture", "cpu_draw", "gpu_full",
                             "gpu_no_shadows", "gpu_no_ground", "gpu_bare"))]
        print("ROW | " + " | ".join(cells) + f" | {args.label}", flush=True)
    if args.storm:
        demo_fps(ctx, "particle_storm", args.set, size, args.path, args.storm_frames)


if __name__ == "__main__":
    main()
