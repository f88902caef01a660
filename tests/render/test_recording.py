"""Recording end to end: mp4 / gif / PNG folder, interrupted recordings, bad paths."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

av = pytest.importorskip("av")

from pointmass.demo import Simulation, load_demo  # noqa: E402

pytestmark = pytest.mark.gl

SIZE = (96, 64)


def _sim() -> Simulation:
    return Simulation(load_demo("side_library"))


def _decode(path: Path) -> tuple[int, int, int, float]:
    """(frames, width, height, fps) of a video, decoded with PyAV."""
    with av.open(str(path)) as c:
        stream = c.streams.video[0]
        frames = sum(1 for _ in c.decode(stream))
        return frames, stream.width, stream.height, float(stream.average_rate or 0)


def test_mp4_frame_count_size_fps_and_sim_time(ctx, tmp_path):
    """12 frames at 24 fps: 12 decoded frames of the right size and rate; sim time + 0.5 s."""
    from pointmass.render.recording import record

    sim = _sim()
    result = record(sim, tmp_path / "clip.mp4", seconds=0.5, fps=24, size=SIZE,
                    progress=False, ctx=ctx)
    assert result.complete and result.frames == 12
    assert _decode(tmp_path / "clip.mp4") == (12, 96, 64, 24.0)
    assert sim.scene.time == pytest.approx(0.5, abs=1e-9)


def test_mp4_odd_size_is_rounded_to_even(ctx, tmp_path, capsys):
    from pointmass.render.recording import record

    result = record(_sim(), tmp_path / "odd.mp4", seconds=0.1, fps=30, size=(97, 65),
                    progress=True, ctx=ctx)
    assert result.size == (96, 64)
    assert _decode(tmp_path / "odd.mp4")[1:3] == (96, 64)
    err = capsys.readouterr().err
    assert "even" in err and "frames" in err          # the note and the progress bar


def test_gif(ctx, tmp_path):
    from PIL import Image

    from pointmass.render.recording import record

    record(_sim(), tmp_path / "clip.gif", seconds=0.4, fps=10, size=SIZE, progress=False,
           ctx=ctx)
    with Image.open(tmp_path / "clip.gif") as im:
        assert im.size == SIZE and im.n_frames == 4
        assert im.info["duration"] == 100


def test_png_folder(ctx, tmp_path):
    from PIL import Image

    from pointmass.render.recording import record

    out = tmp_path / "frames"
    record(_sim(), out, seconds=0.1, fps=30, size=SIZE, progress=False, ctx=ctx)
    files = sorted(out.glob("frame_*.png"))
    assert [f.name for f in files] == ["frame_00000.png", "frame_00001.png", "frame_00002.png"]
    assert Image.open(files[0]).size == SIZE


def test_interrupted_recording_leaves_a_playable_file(ctx, tmp_path):
    """Ctrl-C after frame 5 re-raises, and the mp4 plays with the frames so far."""
    from pointmass.render.recording import record

    def interrupt(index: int) -> None:
        if index == 4:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        record(_sim(), tmp_path / "cut.mp4", seconds=2.0, fps=30, size=SIZE, progress=False,
               on_frame=interrupt, ctx=ctx)
    frames, w, h, _ = _decode(tmp_path / "cut.mp4")
    assert frames == 5 and (w, h) == SIZE


def test_error_in_the_simulation_still_closes_the_file(ctx, tmp_path):
    """An exception from the demo mid-recording: the mp4 is closed with the frames so far."""
    from pointmass.render.recording import record

    sim = _sim()
    calls = {"n": 0}

    def boom(scene, dt):
        calls["n"] += 1
        if calls["n"] > 8:
            raise RuntimeError("demo failed")

    sim.demo.module.on_step, saved = boom, sim.demo.module.on_step
    try:
        with pytest.raises(RuntimeError, match="demo failed"):
            record(sim, tmp_path / "cut.mp4", seconds=1.0, fps=30, size=SIZE,
                   progress=False, ctx=ctx)
    finally:
        sim.demo.module.on_step = saved
    # Frames 0-2 were rendered; the third advance (steps 9-12) raised.
    assert _decode(tmp_path / "cut.mp4")[0] == 3


def test_unwritable_folder_fails_before_simulating(tmp_path):
    """An output folder we may not write to fails at once, before any simulation."""
    from pointmass.render.recording import record

    if hasattr(os, "geteuid") and os.geteuid() == 0:
        locked = Path("/proc")  # root may write anywhere on disk, but not into /proc
    else:
        locked = tmp_path / "locked"
        locked.mkdir()
        locked.chmod(0o500)
    sim = _sim()
    with pytest.raises(PermissionError):
        record(sim, locked / "x.mp4", seconds=1.0, size=SIZE, progress=False)
    assert sim.scene.time == 0.0


@pytest.mark.parametrize("name", ["missing/x.mp4", "missing/x.gif", "missing/frames"])
def test_missing_folder_fails_before_simulating(tmp_path, name, monkeypatch):
    """No rendering or simulation happens when the output cannot be created."""
    from pointmass.render import recording

    sim = _sim()
    monkeypatch.setattr(sim, "advance", lambda s: pytest.fail("simulated before failing"))
    monkeypatch.setattr(recording, "create_headless_context",
                        lambda: pytest.fail("made a context before failing"))
    with pytest.raises(FileNotFoundError):
        recording.record(sim, tmp_path / name, seconds=1.0, size=SIZE, progress=False)


def test_unknown_suffix_is_refused(tmp_path):
    from pointmass.render.video import VideoWriter

    with pytest.raises(ValueError, match=r"\.mp4"):
        VideoWriter(tmp_path / "x.avi", SIZE, 30)


def test_video_writer_for_the_viewer(tmp_path):
    """open / write / close, cropping odd-sized frames to the even video size."""
    from pointmass.render.video import VideoWriter

    w = VideoWriter.open(tmp_path / "v.mp4", (33, 21), 15)
    assert w.size == (32, 20) and w.note
    for k in range(6):
        w.write(np.full((21, 33, 3), 40 * k, np.uint8))
    w.close()
    w.close()                                   # idempotent
    assert _decode(tmp_path / "v.mp4") == (6, 32, 20, 15.0)
    with pytest.raises(RuntimeError):
        w.write(np.zeros((20, 32, 3), np.uint8))


def test_notebook_clip_embeds_an_mp4(gl_session, tmp_path):
    from pointmass.render.notebook import video

    clip = video(_sim(), seconds=0.2, fps=20, size=(64, 48))
    assert clip.frames == 4 and clip.size == (64, 48)
    assert clip._repr_html_().startswith("<video") and "base64," in clip._repr_html_()
    assert _decode(clip.save(tmp_path / "c.mp4"))[:3] == (4, 64, 48)


@pytest.mark.gl
def test_a_notebook_clip_is_short_to_print_and_gives_its_frames(gl_session, tmp_path):
    """repr is one short line (it printed 43–270 kB of bytes); frames decode to the right
    count and size; .gif and .mp4 save."""
    from pointmass.demo import Simulation, load_demo
    from pointmass.render.notebook import video

    clip = video(Simulation(load_demo("side_library")), seconds=1.0, size=(160, 90))
    text = repr(clip)
    assert text.startswith("Clip(160x90, 30 frames at 30 fps = 1.00 s, ") and len(text) < 80
    frames = clip.to_array()
    assert frames.shape == (30, 90, 160, 3)
    assert "<video" in clip._repr_html_() and "muted" in clip._repr_html_()
    from PIL import Image

    gif = clip.save(tmp_path / "clip.gif")
    assert Image.open(gif).n_frames == 30
    assert clip.save(tmp_path / "clip.mp4").read_bytes() == clip.data
