"""``pm.render(scene_or_sim, path, time=, size=)``: one picture offscreen from Python."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

import pointmass as pm

pytestmark = pytest.mark.gl


def _scene():
    world = pm.World()
    world.add(pm.Ground())
    world.add_particle((0.0, 2.0, 0.0), radius=0.3)
    world.add_body(pm.Box((0.4, 0.4, 0.4)), (1.0, 2.0, 0.0))
    return pm.Scene(world)


def test_render_writes_a_png_of_the_scene_at_the_time_asked(gl_session, tmp_path):
    """A Scene rendered 1 s on: the file is a PNG of the size asked, not blank, and the world
    has moved on by whole steps to 1 s (the ball has fallen and bounced)."""
    scene = _scene()
    out = pm.render(scene, tmp_path / "shot.png", time=1.0, size=(320, 200))
    rgb = np.asarray(Image.open(out).convert("RGB"))
    assert Image.open(out).format == "PNG"
    assert rgb.shape == (200, 320, 3) and rgb.std() > 5
    assert scene.world.time == pytest.approx(1.0)
    assert scene.world.particles.position[0, 1] < 1.0


def test_render_takes_a_demo_name_and_a_simulation(gl_session, tmp_path):
    """A demo by name (with --set style overrides) and a running Simulation (drawn where it
    is, then moved on) both give pictures."""
    pm.render("projectile", tmp_path / "a.png", time=0.5, size=(160, 90),
              overrides=["vx=20"])
    sim = pm.Simulation(_scene())
    sim.advance(0.25)
    pm.render(sim, tmp_path / "b.png", size=(160, 90))
    assert sim.time == pytest.approx(0.25)
    for name in ("a.png", "b.png"):
        assert np.asarray(Image.open(tmp_path / name)).shape[:2] == (90, 160)


def test_render_is_still_callable_after_importing_the_render_package(gl_session, tmp_path):
    """``import pointmass.render`` sets ``pm.render`` to the package: it is callable too."""
    import pointmass.render

    assert pm.render is pointmass.render
    pm.render(_scene(), tmp_path / "c.png", size=(64, 64))
    assert (tmp_path / "c.png").stat().st_size > 0


@pytest.mark.parametrize(("options", "match"), [
    ({"size": (0, 100)}, "size"), ({"size": (100,)}, "size"), ({"size": (1.5, 2)}, "size"),
    ({"time": -1.0}, "time"), ({"time": float("nan")}, "time"),
])
def test_bad_settings_are_refused_by_name(tmp_path, options, match):
    with pytest.raises(ValueError, match=match):
        pm.render(_scene(), tmp_path / "bad.png", **options)


def test_a_non_image_path_or_a_kept_file_is_refused(tmp_path):
    with pytest.raises(ValueError, match="image file"):
        pm.render(_scene(), tmp_path / "shot.txt")
    (tmp_path / "kept.png").write_bytes(b"x")
    with pytest.raises(FileExistsError, match="overwrite"):
        pm.render(_scene(), tmp_path / "kept.png", overwrite=False)
    assert (tmp_path / "kept.png").read_bytes() == b"x"
