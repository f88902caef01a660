"""The wheel carries the shaders and the ``py.typed`` marker (PEP 561: type checkers read
pointmass's annotations), and an installed wheel finds its shaders (not the checkout's)."""

from __future__ import annotations

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_wheel_contains_shaders_and_installed_copy_finds_them(tmp_path):
    pytest.importorskip("hatchling")
    built = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps",
                            "--no-build-isolation", "-q", "-w", str(tmp_path), str(ROOT)],
                           capture_output=True, text=True, check=False)
    if built.returncode != 0:
        pytest.skip(f"could not build the wheel here: {built.stderr[-300:]}")
    wheel = next(tmp_path.glob("pointmass-*.whl"))
    names = set(zipfile.ZipFile(wheel).namelist())
    for glsl in sorted((ROOT / "shaders").glob("*.glsl")):
        assert f"pointmass/shaders/{glsl.name}" in names
    assert "pointmass/py.typed" in names

    site = tmp_path / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "-q", "--target",
                    str(site), str(wheel)], check=True, capture_output=True)
    code = (f"import sys; sys.path.insert(0, {str(site)!r}); "
            "from pointmass.render.shaders import shader_dir; print(shader_dir())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=tmp_path)
    assert Path(out.stdout.strip()) == site / "pointmass" / "shaders"
