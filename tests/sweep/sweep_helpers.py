"""Shared by the sweep tests: a spring-pair demo written to a folder, and mp4 frame counts."""

from __future__ import annotations

from pathlib import Path

SPRING_DEMO = '''
"""Two 1 kg particles on a spring, stretched and let go (no gravity): the sweep tests' demo."""
import os
import signal
from dataclasses import dataclass
from pathlib import Path

from pointmass import CameraHint, Scene, Spring, World, tweak

TITLE = "Spring for sweeps"


@dataclass
class Params:
    stiffness: float = tweak(50.0, 1.0, 1e9, "Spring constant k [N/m]")
    stretch: float = tweak(0.2, 0.0, 1.0, "Initial stretch [m]")
    seed: int = tweak(0, 0, 1000, "Which run (kills its worker once when die_on_seed)")
    die_on_seed: int = tweak(-1, -1, 1000, "Seed whose first attempt kills its own worker")


def build(p):
    marker = Path(__file__).parent / f"killed-{p.seed}"
    if p.seed == p.die_on_seed and not marker.exists():
        marker.write_text(str(os.getpid()))
        os.kill(os.getpid(), signal.SIGKILL)   # the worker dies mid-run, as if OOM-killed
    world = World(gravity=(0.0, 0.0, 0.0))
    a = world.add_particle((-0.5 - p.stretch / 2, 1.0, 0.0), mass=1.0, radius=0.1)
    b = world.add_particle((0.5 + p.stretch / 2, 1.0, 0.0), mass=1.0, radius=0.1)
    world.add(Spring(a, b, p.stiffness, 1.0))
    return Scene(world, camera=CameraHint(target=(0, 1, 0), distance=4.0), dt=1 / 120)
'''


def write_spring_demo(folder: Path) -> Path:
    path = folder / "spring_sweep.py"
    path.write_text(SPRING_DEMO)
    return path


def mp4_frames(path: Path) -> tuple[int, tuple[int, int]]:
    """(decoded frame count, (width, height)) of an mp4, decoding every frame with PyAV."""
    import av

    with av.open(str(path)) as container:
        frames = list(container.decode(video=0))
    return len(frames), (frames[0].width, frames[0].height)
