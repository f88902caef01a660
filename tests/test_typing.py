"""The public API type-checks: mypy over the modules ``[tool.mypy]`` lists in pyproject.toml
(the core a script imports and the renderer's public modules), and over the README's python
blocks as a user's script, with the checkout's ``py.typed`` package on the path.

mypy is in the ``test`` extra; without it this skips (CI installs it)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _mypy(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    pytest.importorskip("mypy")
    env = {**os.environ, "MYPYPATH": str(ROOT / "src")}  # this checkout's pointmass first
    return subprocess.run([sys.executable, "-m", "mypy", "--no-error-summary", *args],
                          capture_output=True, text=True, cwd=cwd, check=False, timeout=600,
                          env=env)


@pytest.mark.slow
def test_the_public_modules_type_check():
    """``mypy`` with pyproject.toml's settings reports nothing."""
    out = _mypy("--cache-dir", str(ROOT / ".mypy_cache"), cwd=ROOT)
    assert out.returncode == 0, out.stdout + out.stderr


@pytest.mark.slow
def test_the_readme_snippets_type_check_as_user_code(tmp_path):
    """The README's blocks, as one script that imports pointmass, type-check: the names a user
    reaches (pm.World, pm.Box, world.particles.position, ...) have usable types."""
    sys.path.insert(0, str(ROOT / "tests" / "docs"))
    try:
        from test_readme import BLOCKS
    finally:
        sys.path.pop(0)
    script = tmp_path / "readme_snippets.py"
    script.write_text("\n".join(code for _, code in BLOCKS), encoding="utf-8")
    assert (ROOT / "src" / "pointmass" / "py.typed").exists()
    out = _mypy("--ignore-missing-imports", "--follow-imports=silent", "--allow-redefinition",
                "--cache-dir", str(tmp_path / "cache"), str(script), cwd=tmp_path)
    assert out.returncode == 0, out.stdout + out.stderr
