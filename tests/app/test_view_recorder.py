"""The record key's recorder (``app/capture.py``) reads the view asynchronously, as ``record``
does: each due frame's view reaches the file in order, as many times as the simulated time it
stood for, the reads still in flight included when the recording stops."""

from __future__ import annotations

from collections import deque

import numpy as np

from pointmass.app.capture import ViewRecorder

SIZE = (64, 48)


class _Renderer:
    """Hands back each view two reads late, as two pixel buffers in flight do."""

    def __init__(self) -> None:
        self.view = np.zeros((SIZE[1], SIZE[0], 3), np.uint8)
        self._flight: deque[np.ndarray] = deque()
        self.reads = 0

    def show(self, level: int) -> None:
        self.view = np.full((SIZE[1], SIZE[0], 3), level, np.uint8)

    def read_rgb_later(self):
        self.reads += 1
        out = self._flight.popleft() if len(self._flight) == 2 else None
        self._flight.append(self.view.copy())
        return out

    def read_pending(self):
        out = list(self._flight)
        self._flight.clear()
        return out


def test_each_due_view_reaches_the_file_in_order_for_the_time_it_stood_for(tmp_path):
    import av

    renderer = _Renderer()
    recorder = ViewRecorder(tmp_path / "v.mp4", SIZE, fps=30)
    # (simulated time, grey level of the view): frames at 0, 1/30, 2/30; the view at 4.5/30
    # stands for the frames due at 3/30 and 4/30; one drawn at 4.7/30 is not due (not read);
    # the last, at 5/30, is still in flight when the recording stops.
    shown = [(0.0, 20), (1 / 30, 60), (2 / 30, 100), (4.5 / 30, 140), (4.7 / 30, 250),
             (5 / 30, 180)]
    for time, level in shown:
        renderer.show(level)
        recorder.offer(renderer, time)
    assert renderer.reads == 5  # read only when a frame was due
    recorder.close(renderer)
    with av.open(str(tmp_path / "v.mp4")) as container:
        levels = [round(float(frame.to_ndarray(format="rgb24").mean()))
                  for frame in container.decode(video=0)]
    want = [20, 60, 100, 140, 140, 180]
    assert len(levels) == len(want)
    assert np.abs(np.array(levels) - want).max() <= 3, levels
