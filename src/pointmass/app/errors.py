"""Why a window could not open, in words a user can act on."""

from __future__ import annotations

import os
import sys


class NoDisplayError(RuntimeError):
    """There is no display to open a window on. The message names the alternatives
    (``pointmass record`` offscreen, or a virtual display through ``xvfb-run``); the CLI prints
    it as one line instead of a traceback."""


def no_display_message(name: str | None = None, detail: str = "") -> str:
    """The no-display message for the demo ``name``, or for a script (``show``) when None."""
    why = f" ({detail})" if detail else ""
    if name is None:
        return (f"no display to open a window on{why}: render offscreen instead "
                "(pointmass.render.recording.record, or `pointmass record DEMO -o clip.mp4` "
                "for a demo), or run the script under a virtual display: "
                "`xvfb-run -a python your_script.py`")
    return (f"no display to open a window on{why}: record a video instead with "
            f"`pointmass record {name} -o clip.mp4`, or run under a virtual display: "
            f"`xvfb-run -a pointmass run {name}`")


def has_display() -> bool:
    """False on Linux without DISPLAY or WAYLAND_DISPLAY (checked before pyglet is imported,
    because importing ``pyglet.window`` with no display raises)."""
    if not sys.platform.startswith("linux"):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
