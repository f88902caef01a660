"""Force and torque generators for rigid bodies (Cyclone's ``fgen.cpp``, with its bugs fixed).

A generator is added with ``world.add(...)`` like a particle force generator; every substep it
adds forces and torques to ``bodies.force`` / ``bodies.torque`` just before the bodies' kick
(the world puts the user's own accumulated forces back afterwards, so those still act for one
whole step). The soft step (``World()``'s body stage) finds them again before each of its
substeps, where the bodies then are, and gives h of them (``solver/body_soft.step``'s
``forces``), so forces that balance gravity hold a body still every substep.
World gravity already acts on every body: there is no ``BodyGravity``.

What differs from Cyclone (rigid-notes §1.2, bugs R3 and R4):

* ``BodySpring`` pushes **both** bodies, equal and opposite at the two attachment points, so
  linear and angular momentum are kept (Cyclone's ``Spring`` pushes one end only).
* ``Aero`` works on the velocity of the surface point through the air, v + ω × r − wind
  (Cyclone uses the centre's velocity, so a spinning wing feels nothing and never damps the
  spin; it also *adds* the wind, a sign error if the wind is the air's velocity).
* ``AeroControl`` (a control surface) is ``Aero`` with its tensor blended min → base → max by
  a control in [−1, 1], as Cyclone's; its demos then apply the control (the sailboat's never is).
* ``BodyBuoyancy`` lifts by the submerged fraction ρ·V·g (Cyclone's has the wrong fraction,
  precedence, and no g).
* ``Explosion`` exists (Cyclone's ``updateForce`` is empty): an outward push falling off with
  distance, delivering a fixed impulse over its duration whatever the step.

Kernels are plain numba loops on scalars, ``nogil=True``, in the style of ``pointmass.forces``.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numba import njit

from .. import _validate as check
from .bodies import Bodies, Body, body_index
from .scalar import qrot, qrot_inv
from .shapes import BOX, SPHERE


class BodyForceGenerator:
    """Adds forces and torques to ``bodies.force`` / ``bodies.torque`` once per (sub)step."""

    def apply(self, bodies: Bodies, dt: float) -> None:
        raise NotImplementedError

    def validate(self, bodies: Bodies) -> None:
        """Check body indices when added to a world (raise naming the bad parameter)."""

    def check_handles(self, bodies: Bodies) -> None:
        """Refuse a ``Body`` handle given to the constructor that is not of ``bodies`` (another
        world's, or stale): its index would act on whatever body has it here."""
        for name, handles in getattr(self, "_handles", {}).items():
            for handle in handles if isinstance(handles, list) else [handles]:
                if isinstance(handle, Body):
                    handle.checked(bodies, name)

    def potential_energy(self, bodies: Bodies) -> float:
        """Potential energy stored by this generator [J] (0 when it has none)."""
        return 0.0



# -- springs -------------------------------------------------------------------------------------
@njit(cache=True, nogil=True)
def _spring_kernel(pos, quat, vel, ang, force, torque, a, b, la, lb, anchor, k, rest, c):
    """Hooke's spring with a damper along its line, between body ``a``'s point ``la`` and body
    ``b``'s point ``lb`` (body space), or the fixed world point ``anchor`` when ``b`` < 0.
    Equal and opposite forces at the two attachment points. Returns the stored energy [J]."""
    qa = quat[a]
    rax, ray, raz = qrot(qa[0], qa[1], qa[2], qa[3], la[0], la[1], la[2])
    pax, pay, paz = pos[a, 0] + rax, pos[a, 1] + ray, pos[a, 2] + raz
    # velocity of the attachment point: v + ω × r
    vax = vel[a, 0] + ang[a, 1] * raz - ang[a, 2] * ray
    vay = vel[a, 1] + ang[a, 2] * rax - ang[a, 0] * raz
    vaz = vel[a, 2] + ang[a, 0] * ray - ang[a, 1] * rax
    if b >= 0:
        qb = quat[b]
        rbx, rby, rbz = qrot(qb[0], qb[1], qb[2], qb[3], lb[0], lb[1], lb[2])
        pbx, pby, pbz = pos[b, 0] + rbx, pos[b, 1] + rby, pos[b, 2] + rbz
        vbx = vel[b, 0] + ang[b, 1] * rbz - ang[b, 2] * rby
        vby = vel[b, 1] + ang[b, 2] * rbx - ang[b, 0] * rbz
        vbz = vel[b, 2] + ang[b, 0] * rby - ang[b, 1] * rbx
    else:
        rbx = rby = rbz = 0.0
        pbx, pby, pbz = anchor[0], anchor[1], anchor[2]
        vbx = vby = vbz = 0.0
    dx, dy, dz = pbx - pax, pby - pay, pbz - paz
    length = math.sqrt(dx * dx + dy * dy + dz * dz)
    stretch = length - rest
    if length < 1e-12:
        return 0.5 * k * stretch * stretch  # no direction to push along
    nx, ny, nz = dx / length, dy / length, dz / length
    closing = (vbx - vax) * nx + (vby - vay) * ny + (vbz - vaz) * nz
    f = k * stretch + c * closing  # > 0 pulls a towards b
    fx, fy, fz = f * nx, f * ny, f * nz
    force[a, 0] += fx
    force[a, 1] += fy
    force[a, 2] += fz
    torque[a, 0] += ray * fz - raz * fy
    torque[a, 1] += raz * fx - rax * fz
    torque[a, 2] += rax * fy - ray * fx
    if b >= 0:
        force[b, 0] -= fx
        force[b, 1] -= fy
        force[b, 2] -= fz
        torque[b, 0] -= rby * fz - rbz * fy
        torque[b, 1] -= rbz * fx - rbx * fz
        torque[b, 2] -= rbx * fy - rby * fx
    return 0.5 * k * stretch * stretch


class BodySpring(BodyForceGenerator):
    """A spring (with a damper along it) between points of two bodies, pushing **both**.

    F = (k·(L − rest) + damping·dL/dt) along the line joining the attachment points, on body
    ``body_a`` at its point and the opposite force on ``body_b`` at its point: momentum and
    angular momentum are kept (Cyclone's ``Spring`` pushes one body only, R4).

    Args:
        body_a, body_b: The two bodies (``Body`` handles or indices), different.
        local_a, local_b: Attachment points in each body's own coordinates [m].
        k: Stiffness [N/m], ≥ 0.
        rest: Rest length [m], ≥ 0.
        damping: Damping along the spring [N·s/m], ≥ 0.
    """

    def __init__(self, body_a, local_a, body_b, local_b, k: float, rest: float,
                 damping: float = 0.0) -> None:
        self.a = body_index(body_a, "body_a")
        self.b = body_index(body_b, "body_b")
        self._handles = {"body_a": body_a, "body_b": body_b}
        if self.a == self.b:
            raise ValueError(f"body_a and body_b must be different bodies, both are {self.a}")
        self.local_a = check.vec3(local_a, "local_a")
        self.local_b = check.vec3(local_b, "local_b")
        self.k = k
        self.rest = rest
        self.damping = damping

    @property
    def k(self) -> float:
        """Stiffness [N/m], ≥ 0."""
        return self._k

    @k.setter
    def k(self, value: float) -> None:
        self._k = check.scalar(value, "k", low=0.0)

    @property
    def rest(self) -> float:
        """Rest length [m], ≥ 0."""
        return self._rest

    @rest.setter
    def rest(self, value: float) -> None:
        self._rest = check.scalar(value, "rest", low=0.0)

    @property
    def damping(self) -> float:
        """Damping [N·s/m], ≥ 0."""
        return self._c

    @damping.setter
    def damping(self, value: float) -> None:
        self._c = check.scalar(value, "damping", low=0.0)

    def validate(self, bodies: Bodies) -> None:
        bodies.check_index(self.a, "body_a")
        bodies.check_index(self.b, "body_b")

    def _run(self, bodies: Bodies, force, torque) -> float:
        return _spring_kernel(bodies.position, bodies.orientation, bodies.velocity,
                              bodies.angular_velocity, force, torque, self.a, self.b,
                              self.local_a, self.local_b, self.local_b, self._k, self._rest,
                              self._c)

    def apply(self, bodies: Bodies, dt: float) -> None:
        self._run(bodies, bodies.force, bodies.torque)

    def potential_energy(self, bodies: Bodies) -> float:
        n = bodies.count
        return self._run(bodies, np.zeros((n, 3)), np.zeros((n, 3)))

    def ends(self, bodies: Bodies) -> tuple[np.ndarray, np.ndarray]:
        """World positions of the two attachment points [m] (to draw the spring)."""
        return Body(bodies, self.a).to_world(self.local_a), \
            Body(bodies, self.b).to_world(self.local_b)


class AnchoredBodySpring(BodySpring):
    """A spring from a point of one body to a fixed world point ``anchor`` [m].

    Args:
        body: The body (``Body`` or index).
        local: Attachment point in the body's coordinates [m].
        anchor: The fixed end, in world coordinates [m].
        k, rest, damping: As ``BodySpring``.
    """

    def __init__(self, body, local, anchor, k: float, rest: float,
                 damping: float = 0.0) -> None:
        self.a = body_index(body, "body")
        self.b = -1
        self._handles = {"body": body}
        self.local_a = check.vec3(local, "local")
        self.anchor = anchor
        self.k = k
        self.rest = rest
        self.damping = damping

    @property
    def anchor(self) -> np.ndarray:
        """The fixed end [m]."""
        return self._anchor

    @anchor.setter
    def anchor(self, value) -> None:
        self._anchor = check.vec3(value, "anchor")

    def validate(self, bodies: Bodies) -> None:
        bodies.check_index(self.a, "body")

    def _run(self, bodies: Bodies, force, torque) -> float:
        return _spring_kernel(bodies.position, bodies.orientation, bodies.velocity,
                              bodies.angular_velocity, force, torque, self.a, -1,
                              self.local_a, self._anchor, self._anchor, self._k, self._rest,
                              self._c)

    def ends(self, bodies: Bodies) -> tuple[np.ndarray, np.ndarray]:
        return Body(bodies, self.a).to_world(self.local_a), self._anchor.copy()


# -- aerodynamics --------------------------------------------------------------------------------
@njit(cache=True, nogil=True)
def _aero_kernel(pos, quat, vel, ang, force, torque, i, tensor, local, wind):
    """Force R·T·Rᵀ·(v + ω×r − wind) at the body point ``local``, with its torque."""
    q = quat[i]
    rx, ry, rz = qrot(q[0], q[1], q[2], q[3], local[0], local[1], local[2])
    # the surface point's velocity through the air
    ux = vel[i, 0] + ang[i, 1] * rz - ang[i, 2] * ry - wind[0]
    uy = vel[i, 1] + ang[i, 2] * rx - ang[i, 0] * rz - wind[1]
    uz = vel[i, 2] + ang[i, 0] * ry - ang[i, 1] * rx - wind[2]
    bx, by, bz = qrot_inv(q[0], q[1], q[2], q[3], ux, uy, uz)
    gx = tensor[0, 0] * bx + tensor[0, 1] * by + tensor[0, 2] * bz
    gy = tensor[1, 0] * bx + tensor[1, 1] * by + tensor[1, 2] * bz
    gz = tensor[2, 0] * bx + tensor[2, 1] * by + tensor[2, 2] * bz
    fx, fy, fz = qrot(q[0], q[1], q[2], q[3], gx, gy, gz)
    force[i, 0] += fx
    force[i, 1] += fy
    force[i, 2] += fz
    torque[i, 0] += ry * fz - rz * fy
    torque[i, 1] += rz * fx - rx * fz
    torque[i, 2] += rx * fy - ry * fx


def aero_tensor(value, name: str) -> np.ndarray:
    """``value`` as a finite (3, 3) tensor [N·s/m] (3 entries make a diagonal), or an error
    naming ``name``."""
    check.numeric(value, name, "a (3, 3) matrix or 3 diagonal entries")
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a (3, 3) matrix or 3 diagonal entries [N·s/m], "
                         f"got {value!r}") from None
    if arr.shape == (3,):
        arr = np.diag(arr)
    if arr.shape != (3, 3) or not np.isfinite(arr).all():
        raise ValueError(f"{name} must be a finite (3, 3) matrix or 3 diagonal entries "
                         f"[N·s/m], got {arr.tolist()}")
    return np.ascontiguousarray(arr)


class Aero(BodyForceGenerator):
    """Cyclone's aerodynamic surface: a body-space tensor applied to the air velocity.

    The force, in body coordinates, is ``tensor`` · (the velocity of the surface point through
    the air, in body coordinates), applied at ``local_position``. The point's velocity is
    v + ω × r − wind: a spinning wing feels the air, so surfaces damp rotation (Cyclone uses the
    centre's velocity, R3). Drag takes negative entries (Cyclone's tensors work unchanged in
    still air), e.g. a flat plate of normal y: ``diag(-0.1, -5, -0.1)``.

    Args:
        body: The body (``Body`` or index).
        tensor: (3, 3) matrix [N·s/m] in body coordinates, or its 3 diagonal entries; finite.
        local_position: Where the force acts, in body coordinates [m].
        wind: The air's velocity [m/s] (may be changed between steps).
    """

    def __init__(self, body, tensor, local_position=(0.0, 0.0, 0.0),
                 wind=(0.0, 0.0, 0.0)) -> None:
        self.index = body_index(body, "body")
        self._handles = {"body": body}
        self.tensor = tensor
        self.local_position = check.vec3(local_position, "local_position")
        self.wind = wind

    @property
    def tensor(self) -> np.ndarray:
        """Body-space aerodynamic tensor [N·s/m], (3, 3)."""
        return self._tensor

    @tensor.setter
    def tensor(self, value) -> None:
        self._tensor = aero_tensor(value, "tensor")

    @property
    def wind(self) -> np.ndarray:
        """The air's velocity [m/s]."""
        return self._wind

    @wind.setter
    def wind(self, value) -> None:
        self._wind = check.vec3(value, "wind")

    def validate(self, bodies: Bodies) -> None:
        bodies.check_index(self.index, "body")

    def apply(self, bodies: Bodies, dt: float) -> None:
        _aero_kernel(bodies.position, bodies.orientation, bodies.velocity,
                     bodies.angular_velocity, bodies.force, bodies.torque, self.index,
                     self._tensor, self.local_position, self._wind)


class AeroControl(Aero):
    """An ``Aero`` surface with a control (an aileron, an elevator, a rudder): Cyclone's
    ``AeroControl``.

    The tensor in use is interpolated by ``control`` in [−1, 1]: ``minimum`` at −1, ``base`` at
    0, ``maximum`` at 1, linearly in between (−1..0 blends minimum → base, 0..1 base → maximum).
    Set ``control`` between steps (from keys); a value outside [−1, 1] is refused.

    Args:
        body: The body (``Body`` or index).
        base, minimum, maximum: Tensors [N·s/m] at control 0, −1 and 1: (3, 3) matrices or 3
            diagonal entries each, finite.
        local_position: Where the force acts, in body coordinates [m].
        wind: The air's velocity [m/s].
        control: The starting control, in [−1, 1].
    """

    def __init__(self, body, base, minimum, maximum, local_position=(0.0, 0.0, 0.0),
                 wind=(0.0, 0.0, 0.0), control: float = 0.0) -> None:
        self.base = aero_tensor(base, "base")
        super().__init__(body, self.base, local_position, wind)
        self.minimum = aero_tensor(minimum, "minimum")
        self.maximum = aero_tensor(maximum, "maximum")
        self.control = control

    @property
    def control(self) -> float:
        """The control setting in [−1, 1] (−1: ``minimum``, 0: ``base``, 1: ``maximum``)."""
        return self._control

    @control.setter
    def control(self, value) -> None:
        self._control = check.scalar(value, "control", low=-1.0, high=1.0)
        self.tensor = control_tensor(self.base, self.minimum, self.maximum, self._control)


def control_tensor(base: np.ndarray, minimum: np.ndarray, maximum: np.ndarray,
                   control: float) -> np.ndarray:
    """The tensor at ``control`` in [−1, 1]: minimum → base over [−1, 0], base → maximum over
    [0, 1] (linear), shape (3, 3)."""
    if control < 0.0:
        return minimum + (control + 1.0) * (base - minimum)
    return base + control * (maximum - base)


# -- buoyancy ------------------------------------------------------------------------------------
@njit(cache=True, nogil=True)
def _buoyancy_kernel(pos, quat, force, torque, i, local, max_depth, volume, water, rho, g):
    q = quat[i]
    rx, ry, rz = qrot(q[0], q[1], q[2], q[3], local[0], local[1], local[2])
    y = pos[i, 1] + ry
    if y >= water + max_depth:
        return  # out of the water
    fraction = 1.0 if y <= water - max_depth else (water + max_depth - y) / (2.0 * max_depth)
    lift = rho * volume * g * fraction
    force[i, 1] += lift
    # torque r × (0, lift, 0)
    torque[i, 0] -= rz * lift
    torque[i, 2] += rx * lift


class BodyBuoyancy(BodyForceGenerator):
    """Archimedes' lift at a point of a body near a horizontal water surface.

    The point (the centre of buoyancy, in body coordinates) stands for a part of the body of
    ``volume`` whose half height is ``max_depth``: out of the water when the point is above
    ``water_height + max_depth``, fully under (lift ρ·V·g) below ``water_height − max_depth``,
    and the linear fraction in between. The lift acts at the point, so several points on one
    body right it (a hull). Cyclone's version has the fraction wrong and forgets g.

    Args:
        body: The body (``Body`` or index).
        local_point: The centre of buoyancy in body coordinates [m].
        max_depth: Half the height of the part [m], > 0.
        volume: Its volume [m³], > 0.
        water_height: Height of the water surface [m].
        liquid_density: ρ [kg/m³], ≥ 0 (water 1000).
        gravity: Magnitude of gravity g [m/s²], ≥ 0 (match the world's).
    """

    def __init__(self, body, local_point, max_depth: float, volume: float,
                 water_height: float = 0.0, liquid_density: float = 1000.0,
                 gravity: float = 9.81) -> None:
        self.index = body_index(body, "body")
        self._handles = {"body": body}
        self.local_point = check.vec3(local_point, "local_point")
        self.max_depth = check.scalar(max_depth, "max_depth", low=0.0, low_open=True)
        self.volume = check.scalar(volume, "volume", low=0.0, low_open=True)
        self.water_height = water_height
        self.liquid_density = liquid_density
        self.gravity = check.scalar(gravity, "gravity", low=0.0)

    @property
    def water_height(self) -> float:
        """Water surface height [m]."""
        return self._water

    @water_height.setter
    def water_height(self, value: float) -> None:
        self._water = check.scalar(value, "water_height")

    @property
    def liquid_density(self) -> float:
        """Liquid density [kg/m³], ≥ 0."""
        return self._rho

    @liquid_density.setter
    def liquid_density(self, value: float) -> None:
        self._rho = check.scalar(value, "liquid_density", low=0.0)

    def validate(self, bodies: Bodies) -> None:
        bodies.check_index(self.index, "body")

    def apply(self, bodies: Bodies, dt: float) -> None:
        _buoyancy_kernel(bodies.position, bodies.orientation, bodies.force, bodies.torque,
                         self.index, self.local_point, self.max_depth, self.volume,
                         self._water, self._rho, self.gravity)


# -- explosion -----------------------------------------------------------------------------------
@njit(cache=True, nogil=True)
def _explosion_kernel(pos, quat, inv_mass, shape, size, force, torque, centre, scale, radius):
    """Push every movable body within ``radius`` of ``centre`` away from it: force
    ``scale``·(1 − d/radius) along centre → body centre, d the distance from the centre to the
    body's nearest surface point, applied at that point (so boxes tumble). Returns how many
    bodies it pushed."""
    pushed = 0
    for i in range(pos.shape[0]):
        if inv_mass[i] <= 0.0:
            continue
        dx, dy, dz = pos[i, 0] - centre[0], pos[i, 1] - centre[1], pos[i, 2] - centre[2]
        dist = math.sqrt(dx * dx + dy * dy + dz * dz)
        # the nearest point of the body to the centre, relative to the body's centre
        rx = ry = rz = 0.0
        if shape[i] == SPHERE:
            if dist > size[i, 0]:
                s = -size[i, 0] / dist
                rx, ry, rz = s * dx, s * dy, s * dz
        elif shape[i] == BOX:
            q = quat[i]
            lx, ly, lz = qrot_inv(q[0], q[1], q[2], q[3], -dx, -dy, -dz)
            lx = min(max(lx, -size[i, 0]), size[i, 0])
            ly = min(max(ly, -size[i, 1]), size[i, 1])
            lz = min(max(lz, -size[i, 2]), size[i, 2])
            rx, ry, rz = qrot(q[0], q[1], q[2], q[3], lx, ly, lz)
        sx, sy, sz = dx + rx, dy + ry, dz + rz
        near = math.sqrt(sx * sx + sy * sy + sz * sz)
        if near >= radius:
            continue
        if dist > 1e-12:
            nx, ny, nz = dx / dist, dy / dist, dz / dist
        else:
            nx, ny, nz = 0.0, 1.0, 0.0  # a body right at the centre goes up
        f = scale * (1.0 - near / radius)
        fx, fy, fz = f * nx, f * ny, f * nz
        force[i, 0] += fx
        force[i, 1] += fy
        force[i, 2] += fz
        torque[i, 0] += ry * fz - rz * fy
        torque[i, 1] += rz * fx - rx * fz
        torque[i, 2] += rx * fy - ry * fx
        pushed += 1
    return pushed


class Explosion(BodyForceGenerator):
    """A blast that throws bodies outward (Cyclone's ``Explosion::updateForce`` is empty).

    For ``duration`` seconds after it is added (or ``detonate``-d again), every movable body
    whose nearest point lies within ``radius`` of ``centre`` is pushed away from the centre by
    a force of ``strength``·(1 − d/radius)/``duration``, d that distance, applied at that
    nearest point (boxes tumble, spheres do not spin). Over the blast a body receives the
    impulse ``strength``·(1 − d/radius) [N·s] whatever the step (the last substep is cut to
    the time left); afterwards it does nothing.

    Args:
        centre: Where it goes off [m].
        strength: Impulse at zero distance [N·s], ≥ 0.
        radius: Reach [m], > 0.
        duration: How long it pushes [s], > 0 (short: an impulse; ~0.05 s reads well).
    """

    def __init__(self, centre, strength: float, radius: float,
                 duration: float = 0.05) -> None:
        self.centre = centre
        self.strength = check.scalar(strength, "strength", low=0.0)
        self.radius = check.scalar(radius, "radius", low=0.0, low_open=True)
        self.duration = check.scalar(duration, "duration", low=0.0, low_open=True)
        #: Seconds since it went off.
        self.age = 0.0

    @property
    def centre(self) -> np.ndarray:
        """Where it goes off [m]."""
        return self._centre

    @centre.setter
    def centre(self, value) -> None:
        self._centre = check.vec3(value, "centre")

    @property
    def done(self) -> bool:
        """True once the blast is over."""
        return self.age >= self.duration

    def detonate(self, centre=None) -> None:
        """Go off again (at ``centre`` if given)."""
        if centre is not None:
            self.centre = centre
        self.age = 0.0

    def apply(self, bodies: Bodies, dt: float) -> None:
        left = self.duration - self.age
        self.age += dt
        if left <= 0.0:
            return
        share = min(dt, left) / dt  # the part of this substep inside the blast
        _explosion_kernel(bodies.position, bodies.orientation, bodies.inv_mass, bodies.shape,
                          bodies.size, bodies.force, bodies.torque, self._centre,
                          share * self.strength / self.duration, self.radius)


# -- user callables ------------------------------------------------------------------------------
class BodyForce(BodyForceGenerator):
    """A user callable: ``fn(bodies, index, dt)`` returns a force [N] through the centre of
    mass, or a pair (force [N], torque [N m]).

    The slow path (a Python call per body per substep), fine for a handful of bodies.

    Args:
        fn: The callable; what it returns must be finite 3-vectors.
        bodies: Bodies (handles or indices) to act on, or None for all (also later ones).
    """

    def __init__(self, fn: Callable, bodies=None) -> None:
        if not callable(fn):
            raise TypeError(f"fn must be callable (bodies, index, dt) -> force or "
                            f"(force, torque), got {fn!r}")
        self.fn = fn
        self.indices = None if bodies is None else [body_index(b, "bodies") for b in bodies]
        self._handles = {"bodies": [] if bodies is None else list(bodies)}

    def validate(self, bodies: Bodies) -> None:
        for i in self.indices or ():
            bodies.check_index(i, "bodies")

    def apply(self, bodies: Bodies, dt: float) -> None:
        chosen = range(bodies.count) if self.indices is None else self.indices
        force, torque = bodies.force, bodies.torque
        for i in chosen:
            out = self.fn(bodies, i, dt)
            if isinstance(out, tuple) and len(out) == 2:
                f = np.asarray(out[0], dtype=np.float64)
                t = np.asarray(out[1], dtype=np.float64)
            else:
                f = np.asarray(out, dtype=np.float64)
                t = np.zeros(3)
            if f.shape != (3,) or t.shape != (3,) or not (np.isfinite(f).all()
                                                         and np.isfinite(t).all()):
                raise ValueError(f"BodyForce {self.fn!r} returned {out!r} for body {i}; it "
                                 "must return a finite 3-vector force or (force, torque)")
            force[i] += f
            torque[i] += t
