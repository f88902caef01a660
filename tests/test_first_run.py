"""The first run: numba's cache in a per-user folder, a visible notice while kernels compile,
and Ctrl-C / SIGTERM that end the process at once even then (real signals, real processes).

The signal tests start ``pointmass record`` and ``pointmass run`` with an empty numba cache, wait
for the compile notice on stderr, send the signal and time the exit: each process compiles
only for the few seconds before the signal.
"""

from __future__ import annotations

import io
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest

from pointmass import compiling, worker
from pointmass.numba_cache import default_cache_dir, source_digest

SRC = Path(__file__).resolve().parents[1] / "src"
#: Seconds a signalled process may take to be gone (the issue asks for 1; slack for a loaded
#: CI machine, whose figure the test prints).
EXIT_WITHIN = 2.0


def _env(**extra) -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(SRC) + os.pathsep + env.get("PYTHONPATH", "")
    env.update(extra)
    return env


def _probe(env: dict) -> str:
    code = "import pointmass, numba; print(numba.config.CACHE_DIR)"
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                          check=True, timeout=120).stdout.strip()


def test_the_cache_goes_to_the_per_user_folder(tmp_path):
    env = _env(XDG_CACHE_HOME=str(tmp_path / "xdg"))
    env.pop("NUMBA_CACHE_DIR", None)
    env.pop("POINTMASS_CACHE_DIR", None)
    assert _probe(env) == str(tmp_path / "xdg" / "pointmass" / "numba" / source_digest())


def test_each_version_of_the_sources_has_its_own_cache_folder(tmp_path):
    """numba checks only a kernel's own file: a kernel whose callee in another file changed
    would load stale from the cache. The folder is named by a digest of every source file."""
    package = tmp_path / "pkg"
    (package / "sub").mkdir(parents=True)
    (package / "a.py").write_text("def f(): return 1\n")
    (package / "sub" / "b.py").write_text("def g(): return 2\n")
    before = source_digest(package)
    assert source_digest(package) == before                  # stable
    (package / "sub" / "b.py").write_text("def g(): return 3\n")
    assert source_digest(package) != before                  # a callee's file changed


def test_a_users_own_numba_cache_dir_is_kept(tmp_path):
    env = _env(NUMBA_CACHE_DIR=str(tmp_path / "mine"), XDG_CACHE_HOME=str(tmp_path / "xdg"))
    assert _probe(env) == str(tmp_path / "mine")
    assert not (tmp_path / "xdg").exists()


def test_pointmass_cache_dir_overrides_the_folder(tmp_path, monkeypatch):
    monkeypatch.setenv("POINTMASS_CACHE_DIR", str(tmp_path / "pm"))
    assert default_cache_dir() == tmp_path / "pm" / "numba"


def _fresh_kernel():
    """A kernel numba has never compiled (no cache): its first call compiles."""
    from numba import njit

    @njit
    def kernel(n):
        total = 0.0
        for i in range(n):
            total += (i % 7) * 0.5
        return total

    return kernel


def test_the_watch_sees_a_compile_and_its_end():
    watch = compiling.install()
    before = watch.kernels
    kernel = _fresh_kernel()
    seen = []
    done = threading.Event()

    def poll():
        while not done.is_set():
            seen.append(compiling.elapsed())
            time.sleep(0.005)

    poller = threading.Thread(target=poll)
    poller.start()
    kernel(10)
    done.set()
    poller.join()
    assert watch.kernels > before
    assert any(s is not None for s in seen), "no compile seen while it ran"
    time.sleep(compiling.QUIET_SECONDS + 0.2)
    assert compiling.elapsed() is None
    kernel(20)                                 # compiled now: no new burst
    assert compiling.elapsed() is None


def test_a_cached_call_is_not_a_compile():
    kernel = _fresh_kernel()
    kernel(3)
    watch = compiling.install()
    before = watch.kernels
    kernel(4)
    assert watch.kernels == before


def test_the_terminal_notice_prints_the_burst():
    stream = io.StringIO()                     # not a terminal: one line each end
    with compiling.TerminalNotice(stream, period=0.02) as notice:
        _fresh_kernel()(5)
        time.sleep(compiling.QUIET_SECONDS + 0.2)
    text = stream.getvalue()
    assert notice.bursts >= 1
    assert f"pointmass: {compiling.NOTICE} …" in text
    assert "pointmass: compiled physics kernels in" in text


def test_the_worker_hands_back_results_and_errors():
    assert worker.call(lambda a, b: a + b, 2, b=3) == 5
    with pytest.raises(ZeroDivisionError):
        worker.call(lambda: 1 / 0)
    assert not worker.busy()


def test_progress_leaves_compile_time_out_of_the_rate():
    from pointmass.render.progress import ProgressBar

    stream = io.StringIO()
    bar = ProgressBar(10, stream=stream)
    _fresh_kernel()(5)                         # a compile while the bar runs
    compiled = compiling.install().seconds - bar._compiled_before
    assert compiled > 0
    bar.start -= 100.0                         # as if 100 s had passed besides the compile
    bar.update(10, force=True)
    assert "0.1 fps" in stream.getvalue()      # 10 frames / 100 s, the compile left out


# -- real signals --------------------------------------------------------------------------------
def _start(args: list[str], tmp_path: Path, extra_env: dict | None = None) -> subprocess.Popen:
    env = _env(NUMBA_CACHE_DIR=str(tmp_path / "cold-cache"), PYTHONUNBUFFERED="1",
               **(extra_env or {}))
    return subprocess.Popen([sys.executable, "-m", "pointmass", *args], env=env,
                            cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)


def _wait_for_notice(proc: subprocess.Popen, timeout: float = 120.0) -> str:
    """Read stderr until the compile notice; returns what was read."""
    seen = []
    deadline = time.monotonic() + timeout

    def read():
        for line in proc.stderr:
            seen.append(line)
            if compiling.NOTICE in line:
                return

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    reader.join(max(0.0, deadline - time.monotonic()))
    text = "".join(seen)
    assert compiling.NOTICE in text, f"no compile notice on stderr: {text!r}"
    return text


def _signal_and_time(proc: subprocess.Popen, signum: int) -> float:
    sent = time.monotonic()
    proc.send_signal(signum)
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
        pytest.fail(f"still running 10 s after {signal.Signals(signum).name}")
    return time.monotonic() - sent


@pytest.mark.parametrize("signum, status", [(signal.SIGINT, 130), (signal.SIGTERM, 143)],
                         ids=["SIGINT", "SIGTERM"])
def test_record_ends_at_once_when_signalled_while_compiling(tmp_path, signum, status):
    pytest.importorskip("av")
    proc = _start(["record", "box_tower", "-o", "clip.mp4", "--seconds", "2"], tmp_path)
    _wait_for_notice(proc)
    time.sleep(0.5)                            # well inside the compile
    took = _signal_and_time(proc, signum)
    print(f"record exited {took:.2f} s after {signal.Signals(signum).name}")
    assert proc.returncode == status, proc.stderr.read()
    assert took < EXIT_WITHIN


def _wait_for_a_window(proc: subprocess.Popen, timeout: float = 120.0) -> None:
    """Until something is drawn on the (virtual) screen: the window is up."""
    from PIL import ImageGrab

    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and proc.poll() is None:
        if ImageGrab.grab().getbbox() is not None:
            return
        time.sleep(0.2)
    pytest.fail("no window appeared")


@pytest.mark.parametrize("signum, status", [(signal.SIGINT, 130), (signal.SIGTERM, 143)],
                         ids=["SIGINT", "SIGTERM"])
def test_the_window_ends_at_once_when_signalled_while_compiling(tmp_path, signum, status):
    from pointmass.app.errors import has_display

    if not has_display():
        if os.environ.get("POINTMASS_REQUIRE_GL", "") not in ("", "0"):
            pytest.fail("POINTMASS_REQUIRE_GL=1 but no display (run under xvfb-run -a)")
        pytest.skip("no display (run the window tests under xvfb-run -a)")
    proc = _start(["run", "box_tower"], tmp_path)
    _wait_for_notice(proc)
    _wait_for_a_window(proc)
    time.sleep(1.0)                            # its notice drawn, the worker compiling on
    assert proc.poll() is None
    took = _signal_and_time(proc, signum)
    print(f"window exited {took:.2f} s after {signal.Signals(signum).name}")
    assert proc.returncode == status, proc.stderr.read()
    assert took < EXIT_WITHIN


def test_the_notebook_line(tmp_path):
    """Inside a Jupyter kernel a compile prints one line (where the cell's output goes)."""
    code = textwrap.dedent("""
        import sys, types
        sys.modules["ipykernel"] = types.ModuleType("ipykernel")   # as in a notebook
        import pointmass
        from numba import njit
        njit(lambda n: n + 1)(1)
    """)
    out = subprocess.run([sys.executable, "-c", code], env=_env(), capture_output=True,
                         text=True, timeout=120, check=True).stdout
    assert f"pointmass: {compiling.NOTICE}" in out


def test_warmup_steps_the_named_demos_and_says_where_the_cache_is(capsys):
    from pointmass.cli import main

    assert main(["warmup", "projectile", "box_tower"]) == 0
    err = capsys.readouterr().err
    assert "warmup [1/2] projectile:" in err and "warmup [2/2] box_tower:" in err
    assert "cached in" in err


def test_warmup_of_an_unknown_demo_is_a_usage_error(capsys):
    from pointmass.cli import main

    assert main(["warmup", "bal_pit"]) == 2
    assert "did you mean 'ball_pit'" in capsys.readouterr().err
