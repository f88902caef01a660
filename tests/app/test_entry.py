"""Entry points without a window: light import, the no-display message, show() on a Scene."""

import subprocess
import sys

import numpy as np
import pytest

import pointmass.app as app
from pointmass import Scene, Simulation, World


def test_importing_the_app_opens_no_display_and_loads_no_pyglet():
    code = ("import sys, pointmass.app; "
            "assert 'pyglet' not in sys.modules, 'pyglet imported'; print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False,
                         env={"PATH": "/usr/bin:/bin"})
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"


def test_no_display_is_a_clear_error(monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    monkeypatch.setattr(sys, "platform", "linux")
    with pytest.raises(app.NoDisplayError) as info:
        app.run_demo("side_library")
    message = str(info.value)
    assert "pointmass record side_library" in message
    assert "xvfb-run -a pointmass run side_library" in message
    with pytest.raises(app.NoDisplayError, match="xvfb-run"):
        app.show(Scene(World()))


def test_show_refuses_other_things():
    with pytest.raises(TypeError, match="Scene, a demo name or a Simulation"):
        app.show(42)


def test_a_bare_scene_simulation_steps_and_resets():
    world = World()
    world.add_particle((0, 5, 0), (1, 0, 0), mass=2.0)
    sim = Simulation(Scene(world))
    for _ in range(60):
        sim.step()
    assert sim.time == pytest.approx(0.5) and world.time == sim.time
    assert world.particles.position[0, 1] < 5
    assert sim.press("SPACE") is False
    sim.rebuild()
    np.testing.assert_allclose(world.particles.position[0], (0, 5, 0))
    np.testing.assert_allclose(world.particles.velocity[0], (1, 0, 0))
    assert sim.time == 0.0
    with pytest.raises(ValueError, match="no parameters"):
        sim.set_param("x", 1)
