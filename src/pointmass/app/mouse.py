"""Mouse gestures on the 3D view (pure logic: no pyglet, testable without a window).

Coordinates come in framebuffer pixels with the origin top-left (the window converts pyglet's
bottom-left window points). A left drag orbits, a right or Shift+left drag pans, the wheel zooms,
a double-click focuses on the particle or body under the cursor, a Ctrl+left drag grabs the
nearest particle or rigid body under it (a body by the point clicked), and a left press
released without moving is a click (the demo's "CLICK" key, if it binds one).
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..render import Hit, pick
from .body_spring import grab_body
from .grab import Grab, grab_particle

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
            self.mode = None
            self.grab = self.start_grab(self.pick(x, y))
            if self.grab is not None:
                self.grab.move(*self.camera.ray(x, y, self.size()))
                self.mode = "grab"
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
            self.camera.keep_in_view = False  # the camera is yours now
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
            hit = self.pick(x, y)
            if hit is not None:
                self.camera.focus(self.centre(hit))
                self.camera.keep_in_view = False
            return
        self._last_click = (now, x, y)
        self.sim.press("CLICK")

    def scroll(self, clicks: float) -> None:
        self.camera.zoom(0.9 ** clicks)
        self.camera.keep_in_view = False

    def pick(self, x: float, y: float) -> Hit | None:
        """The nearest particle or body under the pixel (x, y), or None."""
        origin, direction = self.camera.ray(x, y, self.size())
        return pick(self.sim.scene, origin, direction)

    def start_grab(self, hit: Hit | None) -> Grab | None:
        """A grab of what was hit, or None, saying why (nothing there, or it is fixed)."""
        world = self.sim.scene.world
        if hit is None:
            self.say("nothing to grab there: Ctrl+drag starts on a particle or a body")
            return None
        store = world.particles if hit.kind == "particle" else world.bodies
        if store.inv_mass[hit.index] <= 0:
            self.say(f"{hit.kind} {hit.index} is fixed in place: it cannot be grabbed")
            return None
        if hit.kind == "particle":
            return grab_particle(world, hit.index, self.camera.forward)
        return grab_body(world, hit.index, hit.point, self.camera.forward)

    def centre(self, hit: Hit) -> np.ndarray:
        """Where a double-click on ``hit`` focuses: the particle's or the body's centre."""
        world = self.sim.scene.world
        store = world.particles if hit.kind == "particle" else world.bodies
        return store.position[hit.index].copy()

    def end_grab(self) -> None:
        """Take the spring out of the world (release, reset, close)."""
        if self.grab is not None:
            self.grab.release()
            self.grab = None

    def extra_lines(self) -> list:
        return [self.grab.line()] if self.grab is not None else []
