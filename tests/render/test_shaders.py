"""Shader files: found from a checkout, split into stages, and every one compiles under EGL."""

from __future__ import annotations

import pytest

pytest.importorskip("moderngl")

from pointmass.render.shaders import (
    load_program,
    program_names,
    shader_dir,
    stage_sources,
)


def test_shader_dir_found_and_explicit_dir_missing_names_it(tmp_path):
    assert (shader_dir() / "spheres.glsl").is_file()
    with pytest.raises(FileNotFoundError, match=str(tmp_path)):
        shader_dir(tmp_path)


def test_stage_sources_define_each_stage_after_version():
    text = ("#version 330 core\n#if defined VERTEX_SHADER\nv\n"
            "#elif defined FRAGMENT_SHADER\nf\n#endif\n")
    src = stage_sources(text)
    assert set(src) == {"VERTEX_SHADER", "FRAGMENT_SHADER"}
    assert src["VERTEX_SHADER"].startswith("#version 330 core\n#define VERTEX_SHADER\n")
    with pytest.raises(ValueError):
        stage_sources("void main() {}")


@pytest.mark.gl
@pytest.mark.parametrize("name", program_names())
def test_every_shader_compiles(ctx, name):
    """Each .glsl in shaders/ compiles and links under EGL (llvmpipe)."""
    prog = load_program(ctx, name)
    prog.release()
