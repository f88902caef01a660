"""The demo contract, loading demo files, and running one (shared by the viewer and the recorder).

A demo is a Python file in ``demos/`` (import-safe: no side effects at import) with:

- ``TITLE``: a short title (required);
- ``build(params) -> Scene`` (required);
- ``Params``: a dataclass of ``tweak``/``choice`` fields (optional);
- ``apply(scene, params)``: push live parameter changes into the running scene (optional);
- ``on_step(scene, dt)``: called before every physics step (optional). It runs per *step*, not per
  drawn frame, so a demo behaves the same in a window, a recording and a test; the time is
  ``scene.world.time`` (the only clock);
- ``on_keys_held(scene, keys, dt)``: called before every step while keys are held (optional;
  ``keys`` is a frozenset of names such as "W"), for controls that act as long as a key is down;
- ``check(scene)``: an oracle the tests run after a few simulated seconds (optional);
- ``KEYS``: ``{"1": ("Pistol", fn(scene, params)), ...}`` key bindings (optional). Key names
  are pyglet-style symbol names ("1", "W", "SPACE", "ENTER") or "CLICK" for a click in the scene.
- ``HINT``: one short line the window shows over the scene until the first demo key or click,
  saying what to do ("Click or press SPACE to fire"); a demo that waits for input needs one
  (optional otherwise).
"""

from __future__ import annotations

import difflib
import importlib.util
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

from .scene import Scene
from .simulation import Simulation

__all__ = ["Demo", "Simulation", "demo_dir", "demo_name", "demo_paths", "list_demos",
           "load_demo"]

_ORDER_PREFIX = re.compile(r"^\d+_")


def demo_dir() -> Path:
    """The demos folder: the checkout's ``demos/`` or the copy packaged in the wheel."""
    here = Path(__file__).resolve()
    candidates = [here.parents[2] / "demos", here.parent / "demos"]
    for path in candidates:
        if path.is_dir():
            return path
    tried = ", ".join(str(p) for p in candidates)
    raise FileNotFoundError(f"pointmass demos folder not found; looked in {tried}")


def demo_name(path: Path) -> str:
    """``demos/03_terminal_velocity.py`` -> ``terminal_velocity``."""
    return _ORDER_PREFIX.sub("", path.stem)


def demo_paths() -> list[Path]:
    """Every demo file, in gallery order (their numeric prefixes)."""
    return sorted(p for p in demo_dir().glob("*.py") if not p.name.startswith("_"))


@dataclass
class Demo:
    """A loaded demo file."""

    name: str
    path: Path
    module: ModuleType

    @property
    def title(self) -> str:
        return self.module.TITLE

    @property
    def description(self) -> str:
        """The first paragraph of the demo's docstring, as one line of plain text (wrapped
        lines joined, reStructuredText ````code```` marks dropped), for ``pointmass list``, the
        panel and the README gallery."""
        return summary(self.module.__doc__) or self.title

    @property
    def params_class(self) -> type | None:
        return getattr(self.module, "Params", None)

    def default_params(self) -> Any:
        cls = self.params_class
        return cls() if cls is not None else None

    def build(self, params: Any) -> Scene:
        scene = self.module.build(params) if self.params_class else self.module.build(None)
        if not isinstance(scene, Scene):
            raise TypeError(f"demo {self.name!r}: build() must return a Scene, got {scene!r}")
        return scene

    @property
    def hint(self) -> str | None:
        """The demo's ``HINT``: what to do, shown over the scene until the first key or click."""
        return getattr(self.module, "HINT", None)

    @property
    def keys(self) -> dict[str, tuple[str, Callable]]:
        return dict(getattr(self.module, "KEYS", {}))

    def hook(self, name: str) -> Callable | None:
        return getattr(self.module, name, None)


def summary(doc: str | None) -> str:
    """A docstring's first paragraph on one line, without ````literal```` marks."""
    first = (doc or "").strip().split("\n\n")[0]
    return re.sub(r"``([^`]+)``", r"\1", " ".join(first.split()))


def unknown_demo_message(wanted: str) -> str:
    """``unknown demo 'bal_pit'; did you mean 'ball_pit'?`` (difflib's close matches), then
    the known names."""
    names = [demo_name(p) for p in demo_paths()]
    close = difflib.get_close_matches(wanted, names, n=3, cutoff=0.6)
    hint = ""
    if close:
        hint = " did you mean " + " or ".join(repr(c) for c in close) + "?"
    return f"unknown demo {wanted!r};{hint} known demos: {', '.join(names)}"


def load_demo(name_or_path: str | Path) -> Demo:
    """Load a demo by name (``bridge``, ``09_bridge``) or by the path of any ``.py`` file."""
    path = Path(name_or_path)
    if path.suffix != ".py" or not path.is_file():
        wanted = str(name_or_path)
        matches = [p for p in demo_paths() if p.stem == wanted or demo_name(p) == wanted]
        if not matches:
            if path.suffix == ".py" or "/" in wanted or "\\" in wanted:
                raise ValueError(f"no such file: {wanted}")
            raise ValueError(unknown_demo_message(wanted))
        path = matches[0]
    module_name = f"pointmass_demo_{demo_name(path)}"
    spec = importlib.util.spec_from_file_location(module_name, path)
    if spec is None or spec.loader is None:
        raise ValueError(f"cannot load {path} as a Python module")
    module = importlib.util.module_from_spec(spec)
    sys.modules[module_name] = module  # dataclasses look their module up while being built
    spec.loader.exec_module(module)
    missing = [name for name in ("TITLE", "build") if not hasattr(module, name)]
    if missing:
        raise ValueError(f"demo file {path} is missing {' and '.join(missing)}: a demo needs "
                         "TITLE = \"...\" and def build(params) -> Scene (see README, Writing "
                         "a demo)")
    return Demo(demo_name(path), path, module)


def list_demos() -> list[Demo]:
    return [load_demo(p) for p in demo_paths()]
