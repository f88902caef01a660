"""Import layering: the core stays light, and the renderer never pulls in the window toolkit."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest


def _loaded_after(statement: str, modules: list[str]) -> list[str]:
    code = (f"import sys, json\n{statement}\n"
            f"print(json.dumps([m for m in {modules!r} if m in sys.modules]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, env={"PATH": "/usr/bin:/bin"})
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_import_pointmass_loads_no_graphics():
    """``import pointmass`` loads none of moderngl, pyglet, pyrr, imgui_bundle, av."""
    heavy = ["moderngl", "pyglet", "pyrr", "imgui_bundle", "av", "PIL"]
    assert _loaded_after("import pointmass", heavy) == []


def test_import_cli_loads_no_graphics():
    """The command line module alone (``pointmass list``) loads no GL or window code."""
    heavy = ["moderngl", "pyglet", "pyrr", "imgui_bundle", "av"]
    assert _loaded_after("import pointmass.cli", heavy) == []


def test_import_render_loads_no_pyglet():
    """``pointmass.render`` (and its recorder) never import pyglet or imgui."""
    pytest.importorskip("moderngl")
    pytest.importorskip("pyrr")
    stmt = ("import pointmass.render, pointmass.render.recording, pointmass.render.video, "
            "pointmass.render.snapshot, pointmass.render.notebook")
    assert _loaded_after(stmt, ["pyglet", "imgui_bundle"]) == []


def test_importing_pointmass_makes_openmp_wait_passively_unless_told_otherwise():
    """Spinning OpenMP threads made the parallel kernels 14× slower on a loaded machine; the
    default is passive waiting, and a user's own OMP_WAIT_POLICY is kept."""
    import os

    code = "import os, pointmass; print(os.environ['OMP_WAIT_POLICY'])"
    env = {k: v for k, v in os.environ.items() if k != "OMP_WAIT_POLICY"}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "PASSIVE"
    out = subprocess.run([sys.executable, "-c", code], env={**env, "OMP_WAIT_POLICY": "ACTIVE"},
                         capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "ACTIVE"


def _imports(path) -> set[str]:
    """The absolute module names ``path`` (a module of the ``pointmass`` package) imports."""
    import ast

    package = "pointmass." + ".".join(path.relative_to(PACKAGE).with_suffix("").parts[:-1])
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = package.rstrip(".").split(".")
            base = base[:len(base) - node.level + 1] if node.level else []
            module = ".".join(base + ([node.module] if node.module else []))
            names.add(module)
            names.update(f"{module}.{a.name}" for a in node.names)
    return names


PACKAGE = __import__("pathlib").Path(__file__).resolve().parents[1] / "src" / "pointmass"


@pytest.mark.parametrize(("lower", "upper"), [("rigid", "solver"), ("solver", "render"),
                                              ("rigid", "render"), ("render", "app")])
def test_one_direction_between_packages(lower, upper):
    """``pointmass.solver`` builds on ``pointmass.rigid`` (bodies, shapes, joints' rows), never
    the reverse (issue 26); the physics never imports the renderer; the renderer never the app
    (the window)."""
    offenders = sorted(str(p.relative_to(PACKAGE)) for p in (PACKAGE / lower).rglob("*.py")
                       if any(n == f"pointmass.{upper}" or n.startswith(f"pointmass.{upper}.")
                              for n in _imports(p)))
    assert offenders == []
