"""Every fenced ``python`` block of README.md runs as written.

The blocks run in order in one namespace, as a reader pastes them into one session (the probe
snippet goes on from the first world). Windows are swapped for offscreen pictures:
``pm.show(x)`` renders ``x`` to a PNG with ``pm.render`` (EGL, no display), so a snippet that
opens a window is still run to the end. Files a snippet writes land in a temporary folder.
A block that defines a demo (``Params`` and ``build``) is also built and stepped.

New README sections are picked up by themselves: the blocks are read from the file.
"""

from __future__ import annotations

import os
import re
import sys
import types
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"

_FENCE = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)


def python_blocks(text: str) -> list[tuple[int, str]]:
    """(first line number, code) of every ```python block of ``text``."""
    return [(text.count("\n", 0, m.start()) + 2, m.group(1)) for m in _FENCE.finditer(text)]


BLOCKS = python_blocks(README.read_text(encoding="utf-8"))


def test_the_readme_has_python_blocks_to_run():
    """The extraction finds the README's snippets (a changed fence style would skip them)."""
    assert len(BLOCKS) >= 3
    assert all(code.strip() for _, code in BLOCKS)


class _Session:
    """One namespace the blocks share, run up to the block asked for."""

    def __init__(self, folder: Path, shots: list[Path]) -> None:
        # a real module, so a dataclass in a snippet finds its module as in a script
        self.module = types.ModuleType("readme_snippets")
        sys.modules[self.module.__name__] = self.module
        self.namespace: dict = self.module.__dict__
        self.done = 0
        self.folder = folder
        self.shots = shots

    def run_through(self, index: int) -> None:
        while self.done <= index:
            line, code = BLOCKS[self.done]
            self.done += 1
            exec(compile(code, f"README.md:{line}", "exec"), self.namespace)
            if "class Params" in code and "def build" in code:
                _exercise_demo(self.namespace)


def _exercise_demo(namespace: dict) -> None:
    """A demo block: build its scene from its defaults, apply them, step it a little."""
    params = namespace["Params"]()
    scene = namespace["build"](params)
    if "apply" in namespace:
        namespace["apply"](scene, params)
    for _ in range(10):
        scene.world.step(scene.dt)


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    """The shared namespace; ``pm.show`` renders offscreen, the working folder is temporary,
    matplotlib draws without a display."""
    try:
        from pointmass.render import create_headless_context

        create_headless_context().release()
    except Exception as exc:  # no moderngl, or no EGL
        if os.environ.get("POINTMASS_REQUIRE_GL", "") not in ("", "0"):
            pytest.fail(f"POINTMASS_REQUIRE_GL=1 but no EGL context for the README: {exc}")
        pytest.skip(f"the README's snippets draw offscreen and need EGL: {exc}")
    import matplotlib

    matplotlib.use("Agg")
    import pointmass as pm

    folder = tmp_path_factory.mktemp("readme")
    shots: list[Path] = []

    def show(scene, **options):
        path = folder / f"show{len(shots)}.png"
        shots.append(pm.render(scene, path, size=(320, 180)))

    saved_show, saved_cwd = pm.show, os.getcwd()
    pm.show = show
    os.chdir(folder)
    try:
        yield _Session(folder, shots)
    finally:
        sys.modules.pop("readme_snippets", None)
        pm.show = saved_show
        os.chdir(saved_cwd)


@pytest.mark.parametrize("index", range(len(BLOCKS)), ids=[f"line{n}" for n, _ in BLOCKS])
def test_readme_block_runs_as_written(session, index):
    """Run the README's python block (and any before it not run yet)."""
    session.run_through(index)


def test_the_readme_windows_became_pictures(session):
    """Every ``pm.show`` in the README drew something: its PNG exists and is not blank."""
    import numpy as np
    from PIL import Image

    session.run_through(len(BLOCKS) - 1)
    assert session.shots, "no README snippet calls pm.show"
    for path in session.shots:
        rgb = np.asarray(Image.open(path).convert("RGB"))
        assert rgb.shape == (180, 320, 3) and rgb.std() > 5, path
