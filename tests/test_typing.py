"""The public API type-checks: one mypy run over the modules ``[tool.mypy]`` lists in
pyproject.toml (the core a script imports and the renderer's public modules) and over the
README's python blocks as a user's script, so the names a user reaches (``pm.World``,
``pm.Box``, ``world.particles.position``, ...) have usable types. ``py.typed`` (PEP 561) tells
type checkers to read them from an installed pointmass.

mypy is in the ``test`` extra; without it this skips (CI installs it)."""

from __future__ import annotations

import os
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
def test_the_public_modules_and_the_readme_snippets_type_check(tmp_path):
    pytest.importorskip("mypy")
    sys.path.insert(0, str(ROOT / "tests" / "docs"))
    try:
        from test_readme import BLOCKS
    finally:
        sys.path.pop(0)
    script = tmp_path / "readme_snippets.py"
    script.write_text("\n".join(code for _, code in BLOCKS), encoding="utf-8")
    assert (ROOT / "src" / "pointmass" / "py.typed").exists()
    files = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["mypy"]["files"]
    env = {**os.environ, "MYPYPATH": str(ROOT / "src")}  # this checkout's pointmass first
    out = subprocess.run([sys.executable, "-m", "mypy", "--no-error-summary", "--cache-dir",
                          str(ROOT / ".mypy_cache"), *files, str(script)],
                         capture_output=True, text=True, cwd=ROOT, check=False, timeout=600,
                         env=env)
    assert out.returncode == 0, out.stdout + out.stderr
