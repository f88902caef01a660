"""Keyboard: which key does what, and the help overlay's table (pure logic, no pyglet).

Keys are named as pyglet spells their symbols, normalised (``key_name``): "SPACE", "P", "1",
"RIGHT", "BACKSPACE", "MINUS", "EQUAL", "TAB", "F1". A demo's own binding (``KEYS`` in the demo
file: ammo on 1-4, fire on SPACE, a load on WASD) wins over a global one on the same key; every
global action keeps a key the demo cannot take away (P pauses, Backspace resets), and the help
overlay says which keys the demo took.
"""

from __future__ import annotations

from dataclasses import dataclass

#: Global actions and the keys that trigger them (the first is the one the help shows first).
GLOBAL_KEYS: dict[str, tuple[str, ...]] = {
    "pause": ("SPACE", "P"),
    "step": ("RIGHT",),
    "reset": ("BACKSPACE", "R"),
    "slower": ("MINUS", "NUM_SUBTRACT"),
    "faster": ("EQUAL", "NUM_ADD"),
    "record": ("V",),
    "panel": ("TAB",),
    "contacts": ("C",),
    "frame": ("F",),
    "help": ("F1", "H"),
    "close": ("ESCAPE",),
}

#: With Ctrl held only these apply (Ctrl+P: screenshot, as in MuJoCo).
CTRL_KEYS: dict[str, str] = {"P": "screenshot"}

DESCRIPTIONS = {
    "pause": "pause / resume",
    "step": "single step (pauses)",
    "reset": "reset (rebuild the scene)",
    "slower": "slower (time scale down)",
    "faster": "faster (time scale up)",
    "screenshot": "screenshot (PNG of the 3D view)",
    "record": "start / stop recording an mp4",
    "panel": "hide / show the panel",
    "contacts": "show / hide contacts",
    "frame": "frame all particles",
    "help": "this help",
    "close": "close the window",
}

_KEY_LABELS = {"SPACE": "Space", "RIGHT": "Right", "BACKSPACE": "Backspace", "MINUS": "-",
               "EQUAL": "=", "NUM_SUBTRACT": "keypad -", "NUM_ADD": "keypad +", "TAB": "Tab",
               "ESCAPE": "Esc", "ENTER": "Enter", "CLICK": "click"}

_ALIASES = {"RETURN": "ENTER", "NUM_ENTER": "ENTER"}


def key_name(symbol_string: str) -> str:
    """A pyglet ``key.symbol_string`` as demos name keys: "_1" -> "1", "RETURN" -> "ENTER"."""
    name = symbol_string.upper()
    if len(name) == 2 and name[0] == "_" and name[1].isdigit():
        return name[1]
    if name.startswith("NUM_") and name[4:].isdigit():
        return name[4:]
    return _ALIASES.get(name, name)


def label(name: str) -> str:
    """How a key is written in the help overlay."""
    return _KEY_LABELS.get(name, name)


@dataclass(frozen=True)
class KeyAction:
    """What a key press means: ``kind`` "demo" (``name`` is the demo's key), "action" (``name``
    is a global action) or "none"."""

    kind: str
    name: str = ""


class KeyMap:
    """Resolves key presses against a demo's bindings and the global actions."""

    def __init__(self, demo_keys: dict[str, tuple[str, object]] | None = None) -> None:
        self.demo_keys = dict(demo_keys or {})
        self._global = {k: action for action, keys in GLOBAL_KEYS.items() for k in keys}

    def resolve(self, name: str, *, ctrl: bool = False) -> KeyAction:
        if ctrl:
            action = CTRL_KEYS.get(name)
            return KeyAction("action", action) if action else KeyAction("none")
        if name in self.demo_keys:
            return KeyAction("demo", name)
        action = self._global.get(name)
        return KeyAction("action", action) if action else KeyAction("none")

    def keys_for(self, action: str) -> list[str]:
        """The keys that still trigger a global action (those a demo took are left out)."""
        if action in CTRL_KEYS.values():
            return ["Ctrl+" + k for k, a in CTRL_KEYS.items() if a == action]
        return [k for k in GLOBAL_KEYS[action] if k not in self.demo_keys]

    def help_rows(self) -> list[tuple[str, str]]:
        """(keys, what they do) for the help overlay: global actions, then the demo's keys."""
        rows = []
        for action in (*GLOBAL_KEYS, *CTRL_KEYS.values()):
            keys = self.keys_for(action)
            taken = [k for k in GLOBAL_KEYS.get(action, ()) if k in self.demo_keys]
            text = DESCRIPTIONS[action]
            if taken:
                text += f"  ({', '.join(label(k) for k in taken)}: the demo's)"
            rows.append((" / ".join(label(k) for k in keys) or "-", text))
        for key, (text, _fn) in self.demo_keys.items():
            rows.append((label(key), f"{text}  [demo]"))
        return rows


#: The mouse, for the help overlay.
MOUSE_HELP = (
    ("left drag", "orbit"),
    ("right / Shift+left drag", "pan"),
    ("wheel", "zoom"),
    ("double-click", "focus on a particle or body"),
    ("Ctrl+left drag", "grab a particle or body (spring)"),
)
