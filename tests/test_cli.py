"""The ``pointmass`` command line: list, render, record, run without a display, bad input."""

from __future__ import annotations

import subprocess
import sys

import pytest

from pointmass.cli import main, parse_size


@pytest.fixture
def egl():
    """Skip without EGL, unless POINTMASS_REQUIRE_GL=1 (then fail)."""
    import os

    try:
        from pointmass.render import create_headless_context

        create_headless_context().release()
    except Exception as exc:
        if os.environ.get("POINTMASS_REQUIRE_GL", "") not in ("", "0"):
            pytest.fail(f"POINTMASS_REQUIRE_GL=1 but no EGL context: {exc}")
        pytest.skip(f"no EGL OpenGL context: {exc}")


def test_list_names_the_side_library_demo(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "side_library" in out and "Side library" in out


def test_python_dash_m_runs(tmp_path):
    done = subprocess.run([sys.executable, "-m", "pointmass", "list"], capture_output=True,
                          text=True, check=False)
    assert done.returncode == 0 and "side_library" in done.stdout


def test_parse_size():
    assert parse_size("1280x720") == (1280, 720)
    for bad in ("12", "0x10", "abcx10", "100000x10"):
        with pytest.raises(Exception, match="--size"):
            parse_size(bad)


@pytest.mark.parametrize("argv, needle", [
    (["render", "no_such_demo", "-o", "{tmp}/x.png"], "unknown demo"),
    (["render", "side_library", "-o", "{tmp}/x.png", "--set", "spin"], "name=value"),
    (["render", "side_library", "-o", "{tmp}/x.png", "--set", "spin=9999"], "spin"),
    (["render", "side_library", "-o", "{tmp}/x.png", "--set", "nope=1"], "unknown parameter"),
    (["render", "side_library", "-o", "{tmp}/x.png", "--set", "spin=90", "--set", " spin=80"],
     "--set spin is given twice ('spin=90' and ' spin=80')"),
    (["render", "side_library", "-o", "{tmp}/x.png", "--size", "big"], "--size"),
    (["render", "side_library", "-o", "{tmp}/x.txt"], "image file"),
    (["render", "side_library", "-o", "{tmp}/missing/x.png"], "does not exist"),
    (["record", "side_library", "-o", "{tmp}/missing/x.mp4"], "does not exist"),
    (["record", "side_library", "-o", "{tmp}/x.avi"], ".mp4"),
    (["record", "side_library", "-o", "{tmp}/x.mp4", "--fps", "0"], "--fps"),
    (["record", "side_library", "-o", "{tmp}/x.mp4", "--seconds", "-1"], "--seconds"),
    (["run", "no_such_demo"], "unknown demo"),
    (["bogus"], "invalid choice"),
])
def test_bad_input_is_one_line_and_exit_2(tmp_path, capsys, argv, needle):
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    try:
        code = main(argv)
    except SystemExit as exc:      # argparse's own errors
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2
    assert needle in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_run_without_display_says_what_to_do(monkeypatch, capsys):
    """No DISPLAY on Linux: exit 2 naming `pointmass record` and xvfb-run; pyglet not loaded."""
    monkeypatch.setattr(sys, "platform", "linux")
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    loaded_before = "pyglet" in sys.modules
    assert main(["run", "side_library"]) == 2
    err = capsys.readouterr().err
    assert "pointmass record" in err and "xvfb-run" in err
    assert loaded_before or "pyglet" not in sys.modules, "the check ran after importing pyglet"


def test_run_with_an_unreachable_display_is_one_line(monkeypatch, capsys):
    """A DISPLAY that cannot be opened: one line naming xvfb-run, exit 2, no traceback."""
    import types

    from pointmass.app.errors import NoDisplayError

    def refuse(sim, paused):
        raise NoDisplayError("cannot open display :42; try xvfb-run -a pointmass run DEMO")

    fake = types.ModuleType("pointmass.app")
    fake.run_demo = refuse
    monkeypatch.setitem(sys.modules, "pointmass.app", fake)
    monkeypatch.setenv("DISPLAY", ":42")
    assert main(["run", "side_library"]) == 2
    err = capsys.readouterr().err
    assert "xvfb-run" in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_run_dispatches_to_the_app(monkeypatch):
    """With a display, ``run`` builds the demo once and hands that Simulation to
    pointmass.app.run_demo."""
    import types

    calls = []
    fake = types.ModuleType("pointmass.app")
    fake.run_demo = lambda sim, paused: calls.append((sim, paused))
    monkeypatch.setitem(sys.modules, "pointmass.app", fake)
    monkeypatch.setenv("DISPLAY", ":99")
    assert main(["run", "side_library", "--set", "spin=10", "--paused"]) == 0
    [(sim, paused)] = calls
    assert sim.demo.name == "side_library" and sim.params.spin == 10 and paused


def test_run_without_the_viewer_extra_says_how_to_get_it(monkeypatch, capsys):
    """pyglet missing: one line naming pointmass[viewer], exit 1."""
    monkeypatch.setitem(sys.modules, "pyglet", None)    # makes the import fail
    monkeypatch.setenv("DISPLAY", ":99")
    assert main(["run", "side_library"]) == 1
    assert "pointmass[viewer]" in capsys.readouterr().err


@pytest.mark.gl
def test_render_writes_a_png(egl, tmp_path, capsys):
    from PIL import Image

    out = tmp_path / "shot.png"
    assert main(["render", "side_library", "-o", str(out), "--size", "80x60",
                 "--time", "0.5", "--set", "spin=90"]) == 0
    assert Image.open(out).size == (80, 60)
    assert "wrote" in capsys.readouterr().out


@pytest.mark.gl
def test_record_writes_an_mp4(egl, tmp_path, capsys):
    av = pytest.importorskip("av")

    out = tmp_path / "clip.mp4"
    assert main(["record", "side_library", "-o", str(out), "--size", "64x48", "--seconds",
                 "0.2", "--fps", "20", "--quiet"]) == 0
    with av.open(str(out)) as c:
        assert sum(1 for _ in c.decode(video=0)) == 4


BLOW_UP_DEMO = '''"""Falls, then a user force throws the particle (a blow-up) after 0.5 s."""
import pointmass as pm

TITLE = "Blows up"


def build(params):
    world = pm.World()
    world.add_particle((0, 5, 0), radius=0.3)
    world.add(pm.CustomForce(lambda q: (0, 1e12 if world.time > 0.5 else 0, 0)))
    return pm.Scene(world)
'''


def test_render_of_a_demo_that_fails_while_stepping_is_one_line(tmp_path, capsys):
    """As ``record`` reports it: exit 1, one line naming the error and the time, no
    traceback and no picture (it printed a traceback before)."""
    pytest.importorskip("moderngl")
    demo = tmp_path / "blows_up.py"
    demo.write_text(BLOW_UP_DEMO)
    out = tmp_path / "shot.png"
    assert main(["render", str(demo), "-o", str(out), "--size", "80x60", "--time", "2"]) == 1
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert "rendering stopped by UnstableStepError at t = 0.5" in err
    assert "no picture was written" in err and not out.exists()


@pytest.mark.parametrize("signum, status", [("SIGINT", 130), ("SIGTERM", 143)])
def test_an_error_after_a_signal_exits_as_the_signal(capsys, signum, status):
    """A Ctrl-C that lands in a C callback (llvmlite's, while numba compiles a kernel) is
    printed and dropped there, and numba then fails on the compile it cut short: the command
    exits with the signal's status, not as a crash (CI saw exit 1 for a window's Ctrl-C)."""
    import argparse
    import signal

    from pointmass import cli

    def compile_cut_short(args):
        cli._received.append(getattr(signal, signum))  # what the handler notes first
        raise RuntimeError("no compiled object yet for <Library 'kernel'>")

    cli._handle_termination()
    try:
        args = argparse.Namespace(command="list", func=compile_cut_short)
        assert cli._dispatch(args) == status
        assert "interrupted (RuntimeError after the signal" in capsys.readouterr().err
        cli._received.clear()
        def fails(args):
            raise RuntimeError("a fault of its own")

        with pytest.raises(RuntimeError):  # with no signal, an error is an error
            cli._dispatch(argparse.Namespace(command="list", func=fails))
    finally:
        cli._received.clear()
