"""Screenshots (Ctrl+P) and the record key (V), both read from the renderer's framebuffer.

Never from the window's default framebuffer: reading it leaves GL_INVALID_OPERATION under Mesa
and pyglet then raises on close (viewer-notes, section 5). So captures show the 3D view (with a
grabbed particle's spring and contacts if shown) but not the panel, which users asked to keep out
of videos (bullet3 #2929).

Video frames are taken on *simulated* time, one per 1/fps simulated seconds, as ``pointmass
record`` does: the file plays at true speed whatever the window's frame rate or time scale, and
a paused simulation adds no frames. Frames are read back as ``record`` reads them, through
pixel-buffer objects with two in flight (``Renderer.read_rgb_later``): the window never waits
for the GPU's copy of the frame it just drew, only maps one copied a due frame earlier.
Encoding runs in a background thread behind a bounded queue.
"""

from __future__ import annotations

import math
import queue
import threading
import time
from collections import deque
from pathlib import Path

import numpy as np

_STOP = object()


def timestamped(folder: Path, stem: str, suffix: str) -> Path:
    """``folder/stem-20261121-193012.png`` (a counter is added if that exists)."""
    base = f"{stem}-{time.strftime('%Y%m%d-%H%M%S')}"
    path = folder / f"{base}{suffix}"
    n = 1
    while path.exists():
        path = folder / f"{base}-{n}{suffix}"
        n += 1
    return path


def save_png(rgb: np.ndarray, path: Path) -> Path:
    from PIL import Image

    Image.fromarray(rgb).save(path)
    return path


class ViewRecorder:
    """Writes frames of the view to an mp4 at ``fps`` frames per simulated second."""

    def __init__(self, path: Path, size: tuple[int, int], fps: int = 30) -> None:
        from ..render.video import VideoWriter

        self.writer = VideoWriter(path, size, fps)
        self.path = Path(path)
        self.fps = fps
        self.next_time: float | None = None
        self.error: BaseException | None = None
        self._queue: queue.Queue = queue.Queue(maxsize=8)
        #: How many video frames each read still in flight stands for, oldest first.
        self._in_flight: deque[int] = deque()
        self._thread = threading.Thread(target=self._run, name="pointmass-view-recorder",
                                        daemon=True)
        self._thread.start()

    def _run(self) -> None:
        while (rgb := self._queue.get()) is not _STOP:
            if self.error is None:
                try:
                    self.writer.write(rgb)
                except BaseException as exc:    # kept; the window reports it and stops
                    self.error = exc

    def frames_due(self, sim_time: float) -> int:
        """How many frames the view at ``sim_time`` stands for (0 while paused)."""
        if self.next_time is None or sim_time < self.next_time - 1.0:
            self.next_time = sim_time          # first frame, or the scene was reset
        if sim_time + 1e-9 < self.next_time:
            return 0
        count = math.floor((sim_time - self.next_time) * self.fps + 1e-6) + 1
        self.next_time += count / self.fps
        return count

    def offer(self, renderer, sim_time: float) -> None:
        """Queue the view as many times as the simulated time since the last frame needs. The
        view is read from ``renderer`` (a ``pointmass.render.Renderer`` that has just drawn it)
        only when a frame is due, asynchronously: what comes back is the view of the previous
        due frame, queued for as many frames as that one stood for."""
        count = self.frames_due(sim_time)
        if count:
            self._in_flight.append(count)
            rgb = renderer.read_rgb_later()
            if rgb is not None:
                self._put(rgb, self._in_flight.popleft())

    def _put(self, rgb, count: int) -> None:
        for _ in range(count):
            self._queue.put(rgb)

    def close(self, renderer=None) -> Path:
        """Finish the file: the reads still in flight on ``renderer`` (whose GL context must
        be current), then what is queued."""
        if renderer is not None:
            for rgb in renderer.read_pending():
                self._put(rgb, self._in_flight.popleft())
        self._in_flight.clear()
        self._queue.put(_STOP)
        self._thread.join()
        self.writer.close()
        return self.path
