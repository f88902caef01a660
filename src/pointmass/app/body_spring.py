"""The mouse spring on a rigid body: ``rigid.pull.BodyPull`` (the particle grab's law, at the
body-local point that was clicked, so it pulls and turns the body) as a ``Grab`` target."""

from __future__ import annotations

import numpy as np

from ..rigid.bodies import world_rotation
from ..rigid.pull import BodyPull
from .grab import Grab


class BodyMouseSpring(BodyPull):
    """A ``BodyPull`` the viewer's ``Grab`` holds: see ``rigid/pull.py`` for the law."""

    grabs = "body"

    def point(self, world) -> np.ndarray:
        """Where the grabbed point is now [m], (3,)."""
        return self.point_of(world.bodies)


def grab_body(world, index: int, point, normal) -> Grab:
    """Grab body ``index`` at the world ``point`` [m] (where the pick ray met it): the spring
    holds that point of the body, its target moving in the plane through it with ``normal``."""
    b = world.bodies
    local = world_rotation(b.orientation[index]).T @ (np.asarray(point, float) - b.position[index])
    return Grab(world, BodyMouseSpring(index, local, point), normal)
