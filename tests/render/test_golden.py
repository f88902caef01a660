"""Golden images: small fixed scenes rendered under llvmpipe at 256×256, compared with a
tolerance with tests/golden/*.png (regenerate: POINTMASS_UPDATE_GOLDENS=1)."""

from __future__ import annotations

import pytest
import render_scenes as scenes

SIZE = (256, 256)

pytestmark = pytest.mark.gl


@pytest.fixture
def renderer(ctx):
    from pointmass.render import Renderer

    r = Renderer(ctx, SIZE)
    yield r
    r.release()


def _shot(renderer, scene, **options):
    from pointmass.render import OrbitCamera

    renderer.render(scene, OrbitCamera.from_hint(scene.camera), **options)
    return renderer.read_rgb()


@pytest.mark.parametrize("name", ["spheres", "lines", "grid", "cube", "night"])
def test_golden_scene(renderer, golden, name):
    """Render each reference scene and compare it with its golden PNG."""
    scene = getattr(scenes, f"{name}_scene")()
    golden(name, _shot(renderer, scene, trails=scene.handles.get("trails")))


def test_golden_side_library_demo(renderer, golden):
    """The side-library demo (rotating cube, translating sphere) after 1.5 simulated seconds."""
    from pointmass.demo import Simulation, load_demo

    sim = Simulation(load_demo("side_library"))
    sim.advance(1.5)
    golden("side_library__t1.5", _shot(renderer, sim.scene))
