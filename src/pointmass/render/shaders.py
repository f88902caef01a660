"""Finding and compiling the programs in ``shaders/`` (one ``.glsl`` per program).

Each file starts with ``#version 330 core`` and holds its stages in ``#if defined VERTEX_SHADER``
/ ``#elif defined FRAGMENT_SHADER`` blocks; the loader inserts the ``#define`` after the version
line, as moderngl-window does. A line ``#include <frame>`` becomes the camera and light's
uniform block (``frame_block.FRAME_BLOCK``), shared by every program.
"""

from __future__ import annotations

import importlib.resources
from pathlib import Path

import moderngl

from .frame_block import FRAME_BLOCK

STAGES = ("VERTEX_SHADER", "GEOMETRY_SHADER", "FRAGMENT_SHADER")


def shader_dir(explicit: str | Path | None = None) -> Path:
    """The shaders folder: ``explicit`` if given, else the wheel's ``pointmass/shaders``, else the
    checkout's top-level ``shaders/``. Fails with every path it tried."""
    candidates: list[Path] = []
    if explicit is not None:
        candidates.append(Path(explicit))
    else:
        try:
            candidates.append(Path(str(importlib.resources.files("pointmass") / "shaders")))
        except (ModuleNotFoundError, TypeError):
            pass
        candidates.append(Path(__file__).resolve().parents[3] / "shaders")
    for path in candidates:
        if (path / "spheres.glsl").is_file():
            return path
    tried = ", ".join(str(p) for p in candidates)
    raise FileNotFoundError(f"pointmass shaders not found; looked in {tried}")


def stage_sources(text: str, defines: tuple[str, ...] = ()) -> dict[str, str]:
    """The source of every stage a single-file program defines, keyed by stage name, each with
    ``#define NAME`` for its stage and for every name in ``defines`` (a variant)."""
    first, _, rest = text.partition("\n")
    if not first.startswith("#version"):
        raise ValueError("a shader file must start with its #version line")
    extra = "".join(f"#define {name}\n" for name in defines)
    rest = rest.replace("#include <frame>\n", FRAME_BLOCK)
    return {stage: f"{first}\n#define {stage}\n{extra}{rest}" for stage in STAGES
            if f"defined {stage}" in rest}


def load_program(ctx: moderngl.Context, name: str, directory: str | Path | None = None, *,
                 defines: tuple[str, ...] = ()) -> moderngl.Program:
    """Compile ``<shader_dir>/<name>.glsl``, with ``defines`` (names) set before its code."""
    path = shader_dir(directory) / f"{name}.glsl"
    src = stage_sources(path.read_text(), defines)
    return ctx.program(vertex_shader=src["VERTEX_SHADER"],
                       geometry_shader=src.get("GEOMETRY_SHADER"),
                       fragment_shader=src["FRAGMENT_SHADER"])


def program_names(directory: str | Path | None = None) -> list[str]:
    """The names of every program in the shaders folder."""
    return sorted(p.stem for p in shader_dir(directory).glob("*.glsl"))
