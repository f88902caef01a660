"""pyglet events to ImGui input (imports pyglet: only loaded once a window exists).

Our own small mapping: imgui-bundle's ``pyglet_backend`` imports PyOpenGL at module level (its
renderer), and its ``process_inputs`` treats ``pyglet.clock.tick()``'s return value as a time.
Events are *forwarded* here by the window, which then asks ``io.want_capture_mouse`` /
``want_capture_keyboard`` whether the scene should also see them.
"""

from __future__ import annotations

import time

from imgui_bundle import imgui
from pyglet.window import key, mouse

_NAMED = {
    key.TAB: imgui.Key.tab, key.BACKSPACE: imgui.Key.backspace, key.RETURN: imgui.Key.enter,
    key.ENTER: imgui.Key.enter, key.NUM_ENTER: imgui.Key.keypad_enter,
    key.ESCAPE: imgui.Key.escape, key.DELETE: imgui.Key.delete, key.SPACE: imgui.Key.space,
    key.LEFT: imgui.Key.left_arrow, key.RIGHT: imgui.Key.right_arrow,
    key.UP: imgui.Key.up_arrow, key.DOWN: imgui.Key.down_arrow, key.HOME: imgui.Key.home,
    key.END: imgui.Key.end, key.MINUS: imgui.Key.minus, key.EQUAL: imgui.Key.equal,
    key.PERIOD: imgui.Key.period, key.COMMA: imgui.Key.comma,
    key.LCTRL: imgui.Key.left_ctrl, key.RCTRL: imgui.Key.right_ctrl,
    key.LSHIFT: imgui.Key.left_shift, key.RSHIFT: imgui.Key.right_shift,
    key.LALT: imgui.Key.left_alt, key.RALT: imgui.Key.right_alt,
}
_MODS = {imgui.Key.left_ctrl: imgui.Key.mod_ctrl, imgui.Key.right_ctrl: imgui.Key.mod_ctrl,
         imgui.Key.left_shift: imgui.Key.mod_shift, imgui.Key.right_shift: imgui.Key.mod_shift,
         imgui.Key.left_alt: imgui.Key.mod_alt, imgui.Key.right_alt: imgui.Key.mod_alt}
_BUTTON = {mouse.LEFT: 0, mouse.RIGHT: 1, mouse.MIDDLE: 2}
_CURSORS = {
    imgui.MouseCursor_.arrow: None,
    imgui.MouseCursor_.text_input: "text",
    imgui.MouseCursor_.resize_ew: "size_left_right",
    imgui.MouseCursor_.resize_ns: "size_up_down",
    imgui.MouseCursor_.hand: "hand",
}


def imgui_key(symbol: int):
    """The ImGui key for a pyglet symbol, or None."""
    if symbol in _NAMED:
        return _NAMED[symbol]
    name = key.symbol_string(symbol)
    if len(name) == 1 and name.isalpha():
        return getattr(imgui.Key, name.lower())
    if len(name) == 2 and name[0] == "_" and name[1].isdigit():
        return getattr(imgui.Key, name)
    return None


class PygletImguiInput:
    """Feeds one pyglet window's events to the current ImGui context."""

    def __init__(self, window) -> None:
        self.window = window
        self.io = imgui.get_io()
        self._t: float | None = None
        self._cursor = None
        self.sync_size()

    def sync_size(self) -> None:
        """Display size in window points; the framebuffer scale covers HiDPI screens."""
        w, h = self.window.get_size()
        fw, fh = self.window.get_framebuffer_size()
        self.io.display_size = imgui.ImVec2(w, h)
        self.io.display_framebuffer_scale = imgui.ImVec2(fw / max(w, 1), fh / max(h, 1))

    def mouse_move(self, x: float, y: float) -> None:
        self.io.add_mouse_pos_event(x, self.io.display_size.y - y)

    def mouse_button(self, x: float, y: float, button: int, down: bool) -> None:
        self.mouse_move(x, y)        # ImGui needs the position that goes with the press
        self.io.add_mouse_button_event(_BUTTON.get(button, 0), down)

    def scroll(self, dx: float, dy: float) -> None:
        self.io.add_mouse_wheel_event(dx, dy)

    def key_event(self, symbol: int, down: bool) -> None:
        k = imgui_key(symbol)
        if k is not None:
            self.io.add_key_event(k, down)
            if k in _MODS:
                self.io.add_key_event(_MODS[k], down)

    def text(self, text: str) -> None:
        for char in text:
            self.io.add_input_character(ord(char))

    def new_frame_time(self) -> None:
        now = time.perf_counter()
        self.io.delta_time = max(now - self._t, 1e-4) if self._t is not None else 1 / 60
        self._t = now

    def update_cursor(self) -> None:
        """Show the cursor ImGui asks for (a text bar over input fields...)."""
        cursor = imgui.get_mouse_cursor()
        if cursor != self._cursor:
            self._cursor = cursor
            name = _CURSORS.get(cursor)
            w = self.window
            w.set_mouse_cursor(w.get_system_mouse_cursor(name) if name else None)
