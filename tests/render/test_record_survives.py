"""Nothing lost: a recording killed by a signal still plays, the CLI refuses to overwrite and
checks every value, and a demo that fails mid-recording costs one line, not the file."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.gl

BLOW_UP_DEMO = '''"""Falls, then a user force throws the particle (a blow-up) after 0.5 s."""
import pointmass as pm

TITLE = "Blows up"


def build(params):
    world = pm.World()
    p = world.add_particle((0, 5, 0), radius=0.3)
    world.add(pm.CustomForce(lambda q: (0, 1e12 if world.time > 0.5 else 0, 0)))
    return pm.Scene(world)
'''


def _pointmass(*args: str, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "pointmass", *args], capture_output=True,
                          text=True, timeout=300, check=False, **kwargs)


def _decoded_frames(path: Path) -> int:
    import av

    with av.open(str(path)) as container:
        return sum(1 for _ in container.decode(video=0))


def _default_sigint() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _record_then(sig: int, out: Path) -> int:
    """Start a long recording, wait until the file has real content, send ``sig``."""
    proc = subprocess.Popen([sys.executable, "-m", "pointmass", "record", "ball_pit", "-o",
                             str(out), "--seconds", "120", "--size", "320x180", "--quiet"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            # A test run in the background (`pytest &`) inherits an ignored
                            # SIGINT, and Python then keeps ignoring it, as POSIX wants for
                            # background jobs; a user's Ctrl-C reaches a foreground process.
                            preexec_fn=_default_sigint)  # noqa: PLW1509 (one syscall)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        if out.exists() and out.stat().st_size > 60_000:
            break
        time.sleep(0.2)
    os.kill(proc.pid, sig)
    proc.wait(timeout=60)
    return proc.returncode


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGKILL],
                         ids=["INT", "TERM", "HUP", "KILL"])
def test_a_recording_stopped_by_a_signal_still_plays(tmp_path, sig):
    """Ctrl-C, SIGTERM, SIGHUP (a closed ssh session) close the file; even SIGKILL leaves a
    fragmented mp4 that decodes up to its last fragment (a plain mp4 left 48 unplayable
    bytes)."""
    out = tmp_path / "clip.mp4"
    code = _record_then(sig, out)
    assert code != 0
    assert _decoded_frames(out) > 0


def test_existing_outputs_are_not_overwritten_without_the_flag(tmp_path):
    """record and render refuse an existing file, naming --overwrite; with it they replace."""
    out = tmp_path / "shot.png"
    out.write_bytes(b"precious")
    result = _pointmass("render", "projectile", "-o", str(out))
    assert result.returncode == 2 and "pass --overwrite" in result.stderr
    assert out.read_bytes() == b"precious"
    video = tmp_path / "clip.mp4"
    video.write_bytes(b"precious")
    result = _pointmass("record", "projectile", "-o", str(video), "--seconds", "0.2")
    assert result.returncode == 2 and "pass --overwrite" in result.stderr
    assert video.read_bytes() == b"precious"
    folder = tmp_path / "x.mp4"
    folder.mkdir()
    result = _pointmass("record", "projectile", "-o", str(folder), "--seconds", "0.2")
    assert result.returncode == 2 and "is a folder" in result.stderr
    result = _pointmass("record", "projectile", "-o", str(video), "--seconds", "0.2",
                        "--size", "160x90", "--overwrite", "--quiet")
    assert result.returncode == 0, result.stderr
    assert _decoded_frames(video) == 6


def test_a_demo_that_fails_mid_recording_costs_one_line_not_the_file(tmp_path):
    """A blow-up at t = 0.5 s: exit status 1, one line naming the error, and the frames
    recorded so far play."""
    demo = tmp_path / "blows_up.py"
    demo.write_text(BLOW_UP_DEMO)
    out = tmp_path / "clip.mp4"
    result = _pointmass("record", str(demo), "-o", str(out), "--seconds", "2", "--size",
                        "160x90", "--quiet")
    assert result.returncode == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "UnstableStepError" in lines[0] and str(out) in lines[0]
    assert 10 <= _decoded_frames(out) <= 20


@pytest.mark.parametrize(("args", "message"), [
    (["record", "projectile", "-o", "x.mp4", "--seconds", "inf"], "--seconds must be in (0, 3600]"),
    (["record", "projectile", "-o", "x.mp4", "--seconds", "1e9"], "--seconds must be in (0, 3600]"),
    (["record", "projectile", "-o", "x.mp4", "--fps", "100000"], "--fps must be in [1, 240]"),
    (["render", "projectile", "-o", "x.png", "--time", "inf"], "--time must be in [0, 3600]"),
    (["render", "projectile", "-o", "x.png", "--time", "-1"], "--time must be in [0, 3600]"),
    (["render", "./no_such_demo.py", "-o", "x.png"], "no such file: ./no_such_demo.py"),
])
def test_every_cli_value_is_checked_in_one_line(tmp_path, args, message):
    result = _pointmass(*args, cwd=tmp_path)
    assert result.returncode == 2
    assert message in result.stderr and "Traceback" not in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1


def test_a_demo_file_missing_its_contract_says_what_is_missing(tmp_path):
    demo = tmp_path / "half.py"
    demo.write_text('"""No title, no build."""\n')
    result = _pointmass("render", str(demo), "-o", str(tmp_path / "x.png"))
    assert result.returncode == 2
    assert "is missing TITLE and build" in result.stderr and "Traceback" not in result.stderr


def test_version():
    import pointmass

    result = _pointmass("--version")
    assert result.returncode == 0 and result.stdout.strip() == f"pointmass {pointmass.__version__}"


def test_progress_prints_sparse_lines_when_not_on_a_terminal():
    """In a log (not a tty) the bar writes a plain line every 10 %, never a carriage return."""
    import io

    from pointmass.render.progress import ProgressBar

    stream = io.StringIO()
    bar = ProgressBar(200, stream=stream, rate=1e9)
    for done in range(1, 201):
        bar.update(done)
    bar.close()
    text = stream.getvalue()
    assert "\r" not in text
    assert 10 <= len(text.splitlines()) <= 11


def test_a_gif_stopped_by_sigterm_keeps_its_frames(tmp_path):
    """A GIF is written when its file closes: SIGTERM closes it like Ctrl-C, so the frames so
    far are kept (it was 0 bytes). SIGKILL still leaves nothing for a GIF: use mp4."""
    from PIL import Image

    out = tmp_path / "clip.gif"
    proc = subprocess.Popen([sys.executable, "-m", "pointmass", "record", "projectile", "-o",
                             str(out), "--seconds", "600", "--size", "80x46", "--quiet"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    time.sleep(15)  # start-up (imports, cached kernels) takes a few seconds; then frames
    os.kill(proc.pid, signal.SIGTERM)
    proc.wait(timeout=60)
    assert proc.returncode == 143
    assert Image.open(out).n_frames > 10
