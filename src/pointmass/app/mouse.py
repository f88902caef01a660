"""Mouse gestures on the 3D view (pure logic: no pyglet, testable without a window).

Coordinates come in framebuffer pixels with the origin top-left (the window converts pyglet's
bottom-left window points). A left drag orbits, a right or Shift+left drag pans, the wheel zooms,
a double-click focuses on the particle under the cursor, a Ctrl+left drag grabs a particle, and
a left press released without moving is a click (the demo's "CLICK" key, if it binds one).
"""

from __future__ import annotations

import math
import time

from ..render import pick_particle
from .grab import Grab

#: Degrees of orbit per pixel of drag.
ORBIT_DEG_PER_PX = 0.35
#: A press that moves less than this many pixels before release is a click.
CLICK_SLOP_PX = 4.0
#: Two clicks closer in time than this [s] are a double-click.
DOUBLE_CLICK_S = 0.35


class MouseControls:
    """Turns presses, drags, releases and the wheel into camera moves, grabs and clicks.

    Args:
        camera: The OrbitCamera to move.
        simulation: The Simulation (for its scene and ``press("CLICK")``).
        size: A callable returning the framebuffer (width, height) [px].
        clock: Seconds for double-click timing (a parameter so tests can control it).
    """

    def __init__(self, camera, simulation, size, clock=time.perf_counter, say=None) -> None:
        self.camera = camera
        self.say = say or (lambda text: None)   # tells the user (the viewer's panel line)
        self.sim = simulation
        self.size = size
        self.clock = clock
        self.mode: str | None = None     # "orbit", "pan", "grab" while a button is down
        self.grab: Grab | None = None
        self._press_at = (0.0, 0.0)
        self._moved = 0.0
        self._last_click = (-1.0, 0.0, 0.0)

    def press(self, x: float, y: float, button: str, *, shift=False, ctrl=False) -> None:
        self._press_at, self._moved = (x, y), 0.0
        if button == "left" and ctrl:
            index = self.pick(x, y)
            if index is not None and self.sim.scene.world.particles.inv_mass[index] > 0:
                self.grab = Grab(self.sim.scene.world, index, self.camera.forward)
                self.grab.move(*self.camera.ray(x, y, self.size()))
                self.mode = "grab"
            else:
                self.mode = None
                self.say("nothing to grab there: Ctrl+drag starts on a particle" if index is None
                         else f"particle {index} is fixed in place: it cannot be grabbed")
        elif button == "right" or button == "middle" or (button == "left" and shift):
            self.mode = "pan"
        elif button == "left":
            self.mode = "orbit"

    def drag(self, x: float, y: float, dx: float, dy: float) -> None:
        """The cursor moved by (dx, dy) pixels (y down) to (x, y) with a button held."""
        self._moved += math.hypot(dx, dy)
        if self.mode == "orbit":
            self.camera.orbit(-dx * ORBIT_DEG_PER_PX, dy * ORBIT_DEG_PER_PX)
        elif self.mode == "pan":
            # Scaled so the point under the cursor at the target's depth follows the cursor.
            per_px = 2.0 * math.tan(math.radians(self.camera.fov) / 2.0) / self.size()[1]
            self.camera.pan(-dx * per_px, dy * per_px)
        elif self.mode == "grab" and self.grab is not None:
            self.grab.move(*self.camera.ray(x, y, self.size()))

    def release(self, x: float, y: float, button: str) -> None:
        mode, self.mode = self.mode, None
        self.end_grab()
        if mode == "orbit" and self._moved < CLICK_SLOP_PX:
            self.click(x, y)

    def click(self, x: float, y: float) -> None:
        """A click in the scene: the demo's CLICK key; a second one soon after focuses."""
        now = self.clock()
        t, px, py = self._last_click
        if now - t < DOUBLE_CLICK_S and math.hypot(x - px, y - py) < 2 * CLICK_SLOP_PX:
            self._last_click = (-1.0, 0.0, 0.0)
            index = self.pick(x, y)
            if index is not None:
                self.camera.focus(self.sim.scene.world.particles.position[index])
            return
        self._last_click = (now, x, y)
        self.sim.press("CLICK")

    def scroll(self, clicks: float) -> None:
        self.camera.zoom(0.9 ** clicks)

    def pick(self, x: float, y: float) -> int | None:
        origin, direction = self.camera.ray(x, y, self.size())
        return pick_particle(self.sim.scene, origin, direction)

    def end_grab(self) -> None:
        """Take the spring out of the world (release, reset, close)."""
        if self.grab is not None:
            self.grab.release()
            self.grab = None

    def extra_lines(self) -> list:
        return [self.grab.line()] if self.grab is not None else []
