"""Make the README's demo gallery: a thumbnail per demo, made with `pointmass render`/`record`.

    .venv/bin/python scripts/make_gallery.py [--only NAME ...] [--table-only]

Writes docs/gallery/NAME.png (or .gif for demos listed in ANIMATED) and rewrites the table
between the gallery markers in README.md. Runs headless (EGL).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

from pointmass.demo import list_demos

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "gallery"
START, END = "<!-- gallery:start -->", "<!-- gallery:end -->"
#: Demos whose point is motion get a short GIF; the others a still at a telling moment.
ANIMATED = {"ballistic": 3.0, "fireworks": 3.0, "newtons_cradle": 3.0, "ball_pit": 4.0,
            "side_library": 3.0, "bridge": 3.0, "fracture": 3.0, "tennis_racket": 3.0,
            "ragdoll": 3.0, "spinning_top": 3.0}
STILL_TIME = {"projectile": 1.6, "terminal_velocity": 5.0, "spring_pair": 1.0, "cloth": 3.0,
              "ball_pit": 6.0, "buoyancy": 4.0, "fireworks": 1.5, "sailboat": 3.0,
              "particle_storm": 6.0}
CLI = [sys.executable, "-m", "pointmass"]


def make_thumbnail(name: str) -> Path:
    if name in ANIMATED:
        path = OUT / f"{name}.gif"
        cmd = [*CLI, "record", name, "-o", str(path), "--seconds", str(ANIMATED[name]),
               "--fps", "10", "--size", "320x180", "--overwrite"]
    else:
        path = OUT / f"{name}.png"
        cmd = [*CLI, "render", name, "-o", str(path), "--time", str(STILL_TIME.get(name, 2.0)),
               "--size", "320x180", "--overwrite"]
    subprocess.run(cmd, check=True, cwd=ROOT)
    return path


def gallery_table(thumbs: dict[str, Path]) -> str:
    rows = ["| Demo | | What it shows | Run it |", "|---|---|---|---|"]
    for demo in list_demos():
        thumb = thumbs.get(demo.name)
        if thumb is None:
            existing = [p for p in (OUT / f"{demo.name}.gif", OUT / f"{demo.name}.png")
                        if p.exists()]
            thumb = existing[0] if existing else None
        image = f"![{demo.title}]({thumb.relative_to(ROOT).as_posix()})" if thumb else ""
        rows.append(f"| **{demo.title}** | {image} | {demo.description} | "
                    f"`pointmass run {demo.name}` |")
    return "\n".join(rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="*", help="demo names to redo (default: all)")
    parser.add_argument("--table-only", action="store_true",
                        help="rewrite the README table (titles, descriptions) with the "
                             "thumbnails already made, rendering nothing")
    args = parser.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    names = [] if args.table_only else args.only or [d.name for d in list_demos()]
    thumbs = {name: make_thumbnail(name) for name in names}
    readme = ROOT / "README.md"
    text = readme.read_text()
    head, _, rest = text.partition(START)
    _, _, tail = rest.partition(END)
    readme.write_text(f"{head}{START}\n{gallery_table(thumbs)}\n{END}{tail}")
    print(f"wrote {len(thumbs)} thumbnails to {OUT} and the table in README.md")


if __name__ == "__main__":
    main()
