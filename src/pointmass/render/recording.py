"""Recording a demo offscreen: render, read back, encode in a background thread.

The Simulation advances 1/fps simulated seconds per frame (its fixed steps, with the remainder
carried over, so the trajectory is the window's and a probe run's), whatever the machine's
speed, so videos play at true speed. Frames are read back through pixel-buffer objects, two in
flight (``Renderer.read_rgb_later``: the GPU copies a frame while the next is simulated and
drawn), and go to the encoder through a bounded queue (rendering and encoding overlap; memory
stays bounded). Ctrl-C or an error mid-recording still
closes the file, so it plays with the frames so far; a bad output path fails before any
simulation runs.
"""

from __future__ import annotations

import queue
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from .. import worker
from . import shadow_splat
from .camera import OrbitCamera
from .context import create_headless_context
from .progress import ProgressBar
from .renderer import Renderer
from .video import VideoWriter

_DONE = object()


@dataclass
class RecordResult:
    """What ``record`` wrote."""

    path: Path
    frames: int
    expected: int
    size: tuple[int, int]
    fps: int
    seconds: float          # wall-clock seconds the recording took
    complete: bool

    def summary(self) -> str:
        state = "wrote" if self.complete else "stopped early; wrote"
        rate = self.frames / self.seconds if self.seconds > 0 else 0.0
        return (f"{state} {self.path} ({self.frames}/{self.expected} frames, "
                f"{self.size[0]}x{self.size[1]} @ {self.fps} fps, {rate:.1f} frames/s)")


def open_target(path: str | Path, size: tuple[int, int], fps: int) -> VideoWriter:
    """Open the output now, so an unwritable path fails before anything is simulated."""
    return VideoWriter.open(path, size, fps)


class _Encoder(threading.Thread):
    """Takes frames off a bounded queue and writes them; keeps the first error it meets."""

    def __init__(self, writer: VideoWriter, maxsize: int) -> None:
        super().__init__(name="pointmass-encoder", daemon=True)
        self.writer = writer
        self.frames: queue.Queue = queue.Queue(maxsize=maxsize)
        self.error: BaseException | None = None

    def run(self) -> None:
        while True:
            rgb = self.frames.get()
            if rgb is _DONE:
                return
            if self.error is None:
                try:
                    self.writer.write(rgb)
                except BaseException as exc:  # reported to the producer, which stops
                    self.error = exc

    def put(self, rgb) -> None:
        """Queue a frame, waiting while the queue is full; re-raises an encoder error."""
        while True:
            if self.error is not None:
                raise RuntimeError(f"video encoding failed: {self.error}") from self.error
            try:
                self.frames.put(rgb, timeout=0.1)
                return
            except queue.Full:
                continue

    def finish(self) -> None:
        """Encode what is queued, then stop."""
        self.frames.put(_DONE)
        self.join()


def record(simulation, path: str | Path | VideoWriter, *, seconds: float, fps: int = 30,
           size: tuple[int, int] = (1280, 720), progress: bool = True,
           on_frame: Callable[[int], None] | None = None, queue_size: int = 8,
           show_contacts: bool = False, ctx=None, renderer: Renderer | None = None
           ) -> RecordResult:
    """Record ``seconds`` of simulated time of a demo ``Simulation`` to ``path``.

    Frame k shows the simulation at its start time + k/fps; after each frame the simulation
    advances 1/fps (so it ends ``seconds`` later). The camera is the scene's hint.

    Args:
        path: ``.mp4``, ``.gif``, a folder for PNG frames, or an open ``VideoWriter``.
        seconds: Simulated seconds to record (> 0); frames = round(seconds × fps).
        fps: Frames per simulated second.
        size: (width, height) [px]; odd sides are rounded down for mp4 (and a note printed).
        progress: Show a progress bar on stderr.
        on_frame: Called with the frame index after each frame is queued (tests, hooks).
        queue_size: Frames that may wait for the encoder.
        ctx: A moderngl context to reuse (default: a new EGL one, released at the end).
        renderer: A Renderer to reuse (resized to the video size; not released here).

    Returns:
        A RecordResult. Ctrl-C and errors are re-raised after the file is closed.
    """
    if not seconds > 0:
        raise ValueError(f"seconds must be > 0, got {seconds}")
    writer = path if isinstance(path, VideoWriter) else open_target(path, size, fps)
    if writer.note and progress:
        print(f"note: {writer.note}", file=sys.stderr)
    total = max(1, round(seconds * fps))
    own_renderer = renderer is None
    if renderer is not None:
        ctx = renderer.ctx
    own_ctx = ctx is None
    started = time.perf_counter()
    encoder = _Encoder(writer, queue_size)
    bar = ProgressBar(total) if progress else None
    done = 0
    try:
        if own_ctx:
            ctx = create_headless_context()
        if renderer is None:  # own_renderer
            renderer = Renderer(ctx, writer.size)
        else:
            renderer.resize(writer.size)
        camera = OrbitCamera.from_hint(simulation.scene.camera)
        worker.call(shadow_splat.warm)      # not in the main thread (see shadow_splat.warm)
        encoder.start()
        for index in range(total):
            camera.track(simulation.scene)
            renderer.render(simulation.scene, camera, trails=simulation.trails,
                            show_contacts=show_contacts)
            rgb = renderer.read_rgb_later()
            if rgb is not None:
                encoder.put(rgb)
            done = index + 1
            if on_frame is not None:
                on_frame(index)
            if bar is not None:
                bar.update(done)
            # In the physics worker: a first step's compile leaves Ctrl-C prompt (see worker).
            worker.call(simulation.advance, 1.0 / fps)
        for rgb in renderer.read_pending():      # the last frames, still in flight
            encoder.put(rgb)
    finally:
        # Whatever happened, encode what was drawn and is queued, and close the file so it
        # plays.
        if renderer is not None and encoder.is_alive():
            try:
                for rgb in renderer.read_pending():
                    encoder.put(rgb)
            except Exception:  # already failing: keep the first error
                pass
        if encoder.is_alive():
            encoder.finish()
        writer.close()
        if bar is not None:
            bar.close()
        if own_renderer and renderer is not None:
            renderer.release()
        if own_ctx and ctx is not None:
            ctx.release()
        if writer.frames < total and progress:
            print(f"recording stopped: {writer.frames} of {total} frames written to "
                  f"{writer.path}", file=sys.stderr)
    if encoder.error is not None:
        raise RuntimeError(f"video encoding failed: {encoder.error}") from encoder.error
    return RecordResult(writer.path, writer.frames, total, writer.size, fps,
                        time.perf_counter() - started, writer.frames == total)
