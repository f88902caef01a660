"""Clips for notebooks: record offscreen, embed as an H.264 ``<video>`` (as MuJoCo's tutorial
does with mediapy), or save.

    >>> from pointmass.render.notebook import video
    >>> video("side_library", seconds=3)   # doctest: +SKIP
"""

from __future__ import annotations

import base64
import tempfile
from dataclasses import dataclass
from pathlib import Path

from .recording import record
from .video import VideoWriter


@dataclass(repr=False)
class Clip:
    """An encoded mp4 (``data``) that shows itself in Jupyter (muted, looping), saves to .mp4
    or .gif, and gives its frames as an array."""

    data: bytes
    size: tuple[int, int]
    fps: int
    frames: int

    def __repr__(self) -> str:
        w, h = self.size
        return (f"Clip({w}x{h}, {self.frames} frames at {self.fps} fps = "
                f"{self.frames / self.fps:.2f} s, {len(self.data) / 1000:.0f} kB)")

    def to_array(self):
        """The decoded frames, shape (frames, height, width, 3), uint8."""
        import io

        import av
        import numpy as np

        with av.open(io.BytesIO(self.data)) as container:
            return np.stack([f.to_ndarray(format="rgb24") for f in container.decode(video=0)])

    def _repr_html_(self) -> str:
        b64 = base64.b64encode(self.data).decode("ascii")
        w, h = self.size
        return (f'<video width="{w}" height="{h}" controls autoplay loop muted playsinline>'
                f'<source src="data:video/mp4;base64,{b64}" type="video/mp4"></video>')

    def save(self, path: str | Path) -> Path:
        """Write the clip to ``path``: ``.mp4`` as it is, ``.gif`` re-encoded (looping)."""
        path = Path(path)
        if path.suffix.lower() == ".gif":
            from PIL import Image

            images = [Image.fromarray(f) for f in self.to_array()]
            images[0].save(path, save_all=True, append_images=images[1:], loop=0,
                           duration=round(1000 / self.fps))
        else:
            path.write_bytes(self.data)
        return path


def video(source, seconds: float = 5.0, *, fps: int = 30, size: tuple[int, int] = (640, 360),
          crf: int = 28) -> Clip:
    """Record ``seconds`` of ``source`` offscreen into an in-memory mp4 clip.

    ``source`` is a ``Simulation`` (it goes on from where it is, and is left ``seconds``
    later), a ``Scene`` built in a script, or a demo name. Defaults keep notebooks small
    (640x360, crf 28: about 330 kB for 5 s).
    """
    from ..simulation import Simulation

    simulation = source if isinstance(source, Simulation) else Simulation(source)
    with tempfile.TemporaryDirectory() as tmp:
        writer = VideoWriter(Path(tmp) / "clip.mp4", size, fps, crf=crf)
        result = record(simulation, writer, seconds=seconds, fps=fps, size=writer.size,
                        progress=False)
        return Clip(writer.path.read_bytes(), result.size, fps, result.frames)
