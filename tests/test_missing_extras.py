"""With only the core installed, every command that needs an extra says so in one line, naming
the pip command, and the no-display advice fits what is installed. The missing modules are
simulated by an import blocker in a subprocess (nothing is uninstalled)."""

from __future__ import annotations

import subprocess
import sys

import pytest

RUNNER = """
import importlib.abc, sys
BLOCKED = set(sys.argv[1].split(","))
class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in BLOCKED:
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None
sys.meta_path.insert(0, Block())
if sys.argv[2] == "show":
    import pointmass as pm
    try:
        pm.show(pm.Scene(pm.World()))
    except ImportError as exc:
        print(exc, file=sys.stderr)
        sys.exit(1)
else:
    from pointmass.cli import main
    sys.exit(main(sys.argv[2:]))
"""


def _run(blocked: str, *args: str, env=None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", RUNNER, blocked, *args], capture_output=True,
                          text=True, timeout=120, check=False, env=env)


@pytest.mark.parametrize("command", [["render", "projectile", "-o", "x.png"],
                                     ["record", "projectile", "-o", "x.mp4"]])
def test_render_and_record_without_the_render_extra(command, tmp_path):
    result = _run("pyrr,moderngl", *command[:3], str(tmp_path / command[3]))
    assert result.returncode == 1
    assert result.stderr.strip().splitlines() == [
        f"pointmass: error: pointmass {command[0]} needs the render extra (moderngl, pyrr not "
        'installed): pip install "pointmass[render]"']


def test_run_and_show_without_the_viewer_extra(monkeypatch):
    import os

    env = dict(os.environ, DISPLAY=os.environ.get("DISPLAY", ":99"))
    result = _run("pyglet", "run", "projectile", env=env)
    assert result.returncode == 1
    assert 'pip install "pointmass[viewer]"' in result.stderr
    assert "Traceback" not in result.stderr and len(result.stderr.strip().splitlines()) == 1
    result = _run("imgui_bundle", "show", env=env)
    assert result.returncode == 1
    assert 'pointmass.show (a window) needs the viewer extra (imgui_bundle not installed)' \
        in result.stderr


def test_no_display_advice_fits_what_is_installed():
    """No display: suggest `record` when the render extra is there, else its install."""
    import os

    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    with_render = _run("nothing", "run", "projectile", env=env)
    assert with_render.returncode == 2
    assert "pointmass record projectile -o clip.mp4" in with_render.stderr
    without = _run("pyrr", "run", "projectile", env=env)
    assert without.returncode == 2
    assert 'pip install "pointmass[render]"' in without.stderr
    assert "pointmass record" not in without.stderr
