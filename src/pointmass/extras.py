"""Which optional extras are installed, and a one-line error naming the command that fixes it.

``pip install pointmass`` gives the physics core (numpy, numba). Pictures and videos need the
``render`` extra (moderngl, pyrr, PyAV, Pillow); windows need ``viewer`` (render + pyglet,
imgui-bundle). Without them a command fails with one line naming the pip command, never with a
``ModuleNotFoundError`` traceback from deep inside.
"""

from __future__ import annotations

import importlib.util

#: The modules each extra provides (import names).
EXTRAS: dict[str, tuple[str, ...]] = {
    "render": ("moderngl", "pyrr", "av", "PIL"),
    "viewer": ("moderngl", "pyrr", "av", "PIL", "pyglet", "imgui_bundle"),
}


class MissingExtra(ImportError):
    """An optional extra is not installed; the message names the pip command."""


def missing(extra: str) -> list[str]:
    """The modules of ``extra`` that cannot be imported here."""
    absent = []
    for name in EXTRAS[extra]:
        try:
            found = importlib.util.find_spec(name) is not None
        except (ImportError, ValueError):
            found = False
        if not found:
            absent.append(name)
    return absent


def has(extra: str) -> bool:
    return not missing(extra)


def require(extra: str, what: str) -> None:
    """Raise ``MissingExtra`` if ``extra`` is not installed: ``what`` needs it."""
    absent = missing(extra)
    if absent:
        raise MissingExtra(f"{what} needs the {extra} extra ({', '.join(absent)} not "
                           f"installed): pip install \"pointmass[{extra}]\"")
