"""pointmass: the cookbook's mass-aggregate physics engine (particles, force generators, hard
constraints, an iterative contact resolver), with an OpenGL viewer in ``pointmass.render`` and
``pointmass.app``.

The core imports only numpy and numba; rendering and windows load only when asked for.

    >>> import pointmass as pm
    >>> world = pm.World(gravity=(0, -9.81, 0))
    >>> a = world.add_particle(position=(0, 2, 0), velocity=(0, 10, 30), mass=1.0, radius=0.5)
    >>> b = world.add_particle(position=(2, 2, 2), mass=20.0, radius=0.5)
    >>> _ = world.add(pm.Spring(a, b, spring_constant=100.0, rest_length=2.0))
    >>> _ = world.add(pm.Drag(k1=0.1, k2=0.1))
    >>> _ = world.add(pm.Ground(height=0.0, restitution=0.5))
    >>> _ = world.add(pm.SphereCollisions(restitution=0.5))
    >>> stats = world.step(1 / 60)
"""

import os as _os

# numba's parallel kernels (50 000 particles and up) run on OpenMP, whose idle threads spin by
# default. On a machine with other work on its cores, spinning threads steal the cores their
# siblings need: 100 000 free particles took 24.8 ms a step instead of 1.75 ms with passive
# waiting (2 cores, load average 4.3, same run). A user's own setting is kept.
_os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

# First, before numba loads: importing numba_cache points numba's cache at a per-user folder,
# so kernels compile once (see numba_cache).
from . import numba_cache as _numba_cache  # noqa: F401  (imported for that effect)
from . import probes, stability
from .collide import BoxContainer, Ground, Plane, SphereCollisions
from .compiling import install as _watch_compiles
from .contacts import ContactBuffer, ContactGenerator
from .forces import Buoyancy, CustomForce, Drag, ForceGenerator, Gravity
from .links import AnchoredCable, AnchoredRod, Cable, Rod
from .params import choice, tweak
from .particles import Particle, Particles
from .probes import Probe
from .rigid.bodies import Bodies, Body
from .rigid.forces import (
    Aero,
    AeroControl,
    AnchoredBodySpring,
    BodyBuoyancy,
    BodyForce,
    BodyForceGenerator,
    BodySpring,
    Explosion,
)
from .rigid.joints import BallJoint, HingeJoint, Joint
from .rigid.shapes import Box, Sphere
from .scene import BoxVisual, CameraHint, PlaneVisual, Scene
from .simulation import Simulation
from .solver.settings import SolverSettings
from .springs import AnchoredBungee, AnchoredSpring, Bungee, FakeSpring, Spring
from .stability import UnstableStepError
from .world import StepStats, World

# Count numba compiles from the start: a notebook prints a line when one begins, and the
# window, `record` and `render` say "compiling physics kernels (first run only)" while it lasts.
_watch_compiles()

__version__ = "0.1.0"


def render(scene, path, *, time: float = 0.0, size=(1280, 720), overrides=(),
           overwrite: bool = True):
    """Write a picture (PNG, or JPEG by the suffix) of ``scene`` offscreen (EGL; no display
    needed) after ``time`` more simulated seconds [s].

    ``scene`` is a Scene, a Simulation, a demo name or a demo's ``.py`` path; a Scene or a
    Simulation goes on from where it is, in its fixed steps, and is left there (a demo starts
    at 0, so ``time`` is its clock). ``size`` is (width, height) in pixels; ``overrides`` are a
    demo's ``"name=value"`` settings. An existing file is replaced unless ``overwrite=False``.
    Returns the path written. Imports the renderer (moderngl) only when called.

        >>> pm.render("projectile", "shot.png", time=2.0, size=(640, 360))  # doctest: +SKIP
    """
    from .extras import require

    require("render", "pointmass.render (a PNG)")
    from .render.snapshot import render_png

    return render_png(scene, path, time=time, size=size, overrides=overrides,
                      overwrite=overwrite)


def show(scene, **options):
    """Open a window on ``scene`` (a Scene, a demo name or a Simulation): see
    ``pointmass.app.show``.

    Imports the viewer (pyglet, imgui-bundle) only when called, so ``import pointmass`` stays
    light and works with no display.
    """
    from .extras import require

    require("viewer", "pointmass.show (a window)")
    from .app import show as _show

    return _show(scene, **options)


__all__ = [
    "Aero", "AeroControl", "AnchoredBodySpring", "AnchoredBungee", "AnchoredCable", "AnchoredRod",
    "AnchoredSpring", "BallJoint", "Bodies", "Body", "BodyBuoyancy", "BodyForce",
    "BodyForceGenerator", "BodySpring", "Box", "BoxContainer", "BoxVisual", "Bungee", "Buoyancy",
    "Cable", "CameraHint", "ContactBuffer", "ContactGenerator", "CustomForce", "Drag",
    "Explosion", "FakeSpring", "ForceGenerator", "Gravity", "Ground", "HingeJoint", "Joint",
    "Particle", "Particles", "Plane", "PlaneVisual", "Probe", "Rod", "Scene", "Simulation",
    "SolverSettings", "Sphere", "SphereCollisions", "Spring", "StepStats", "UnstableStepError",
    "World", "choice", "probes", "render", "show", "stability", "tweak",
]
