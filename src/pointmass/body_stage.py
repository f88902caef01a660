"""The rigid bodies' stage of a world's substep: the forces, the leapfrog's opening kick, the
rows (``wake_loop.find_body_rows``), the soft step (``solver/body_soft.py``) and its continuous
collision (``solver/body_continuous.py``), and the shortcut of a world all asleep.

Functions of the ``World`` they step (``World._substep`` calls ``step``; ``wake_loop`` calls
``kick`` for the bodies it wakes): the world keeps the state, this module runs the stage.
"""

from __future__ import annotations

from functools import partial
from typing import TYPE_CHECKING

import numpy as np

from . import wake_loop as wake
from .collide import Plane
from .rigid import sleep as sleeping
from .rigid.collide import plane_table
from .rigid.step import force_acceleration, integrate_velocities, spin_error
from .solver import body_soft
from .solver.body_continuous import sweep_back

if TYPE_CHECKING:
    from .world import World


def step(world: World, dt: float) -> body_soft.SoftRows:
    """The rigid bodies' substep: the first kick (gravity, forces, torques over
    dt / ``settings.soft_substeps``), contacts once, then the soft step's substeps
    (``solver/body_soft.py``: kick, warm start, soft solve, drift, relax; restitution),
    then its continuous collision (``solver/body_continuous.py``: a fast body back to
    where its step first meets what the collision pass did not foresee).
    Particles with a radius that touch a body join the stage as bodies without inertia
    (``rigid/particle_body.py``); with none touching, the stage sees the bodies alone, as
    in a world without particles. Sleeping bodies are skipped throughout
    (``rigid/sleep.py``)."""
    b = world.bodies
    st = world.solver.settings
    h = dt / st.soft_substeps
    kept, acc = _apply_body_forces(world, h)  # for the first substep (and found again)
    p = world.particles
    if world._sleep and not (p.count and p.awake.any()) and not sleeping.any_active(b):
        # everything asleep (but still scenery: a static body stays awake) and no force
        # woke it: no body and no particle can move or touch anything this step, so there
        # is no row to find and nothing to solve
        if kept is not None:
            b.force[:], b.torque[:] = kept
        return _stay_asleep(world)
    x_start, q_start = b.position.copy(), b.orientation.copy()  # the sweep's start
    # the particles the integration moved (and kicked by dt); none: no packed view
    integrated = p.awake.copy() if p.count else None
    planes = world_planes(world)  # found once a step, and their table (collision, sweep)
    table = plane_table(planes)
    try:  # the first kicks (here, and of woken bodies); ``body_soft`` gives the others
        # the leapfrog (``body_soft``): a body goes on from the half-step velocity its
        # last step drifted with, kicked by h; one whose velocity that step did not leave
        # (just added, set by hand, woken) starts from it with a half kick
        _open_leapfrog(world, h)
        packed, acc = wake.find_body_rows(world, dt, acc, planes,
                                          partial(kick, world, h / 2, drift=h), table=table)
        world._packed = packed  # the islands read its particles (``_fall_asleep``)
        view = b
        if packed is not None:
            view = packed
            assert integrated is not None  # a packed view holds particles
            _first_particle_kick(world, packed, integrated, h, dt, acc)
        forces = None
        if world.body_forces:  # found again every substep, where the bodies then are
            forces = partial(_refind_body_forces, world, view, kept, h)
        rows = body_soft.step(view, b, world.body_contacts, acc, world.body_impulses, dt,
                              world.solver.restitution_threshold, world._gravity,
                              world.joints if world.joints else None, forces=forces,
                              settings=st)
    finally:
        if kept is not None:
            b.force[:], b.torque[:] = kept
    if packed is not None:
        packed.take_positions(b, p)
        b.velocity[:] = packed.velocity[:b.count]
        p.velocity[packed.selected] = packed.velocity[b.count:]
    # what the step's one collision pass did not foresee: a fast body is put back where
    # it first meets a static body or a plane (``solver/body_continuous.py``); only an
    # awake body can be fast
    if b.awake.any():
        exclude = world.joints.pair_keys(b.count) if world.joints else None
        anchored = [j.a for j in world.joints.items if j.b < 0] if world.joints else None
        # the sweep reads the velocities the step drifted with (the leapfrog's half-step
        # ones); the step's synchronised ones wait in ``left_velocity`` meanwhile
        sweep_back(b, planes, exclude, x_start, q_start, dt, anchored, st, table,
                   leapfrog=True)
    else:
        body_soft.leave_step(b.awake, b.velocity, b.angular_velocity, b.left_velocity,
                             b.left_spin)  # what this step left (``_open_leapfrog``)
    world._body_rows = rows
    return rows

def _stay_asleep(world: World) -> body_soft.SoftRows:
    """The soft body stage of a substep in which every body and particle sleeps (but still
    static bodies, which stay awake): what the whole stage leaves then (no rows, no
    impulses kept, each body's half-step velocity its own, none left for a sleeper),
    without its passes over empty work."""
    b = world.bodies
    if world.body_contacts.a.shape[0]:
        world.body_contacts.resize(0)
    world.body_impulses.clear()
    world._packed = None
    b.half_velocity[:] = b.velocity
    b.half_spin[:] = b.angular_velocity
    body_soft.leave_step(b.awake, b.velocity, b.angular_velocity, b.left_velocity,
                         b.left_spin)
    rows = body_soft.SoftRows(world.body_contacts)
    world._body_rows = rows
    return rows

def _open_leapfrog(world: World, h: float) -> None:
    """The soft step's leapfrog opening (``body_soft``, "Leapfrog") and its first kick:
    each awake body whose velocity and spin are still the ones the last step left goes on
    from the half-step velocity and spin that step drifted with, kicked by ``h``; the
    others start from their velocity with a half kick."""
    b = world.bodies
    spun, half = body_soft.open_and_kick(
        b.awake, b.velocity, b.angular_velocity, b.left_velocity, b.left_spin,
        b.half_velocity, b.half_spin, b.force, b.torque, b.inv_mass, b.inv_inertia,
        b.inv_inertia_world, b.linear_damping, b.angular_damping, world._gravity, h)
    if spun >= 0:
        raise spin_error(b, spun, h / 2 if half else h, world.time)

def world_planes(world: World) -> list[Plane]:
    """The world's ``Plane``s (and ``Ground``s) among its contact generators: what the
    body stages collide and sweep against, found once a step."""
    return [g for g in world.contact_generators if isinstance(g, Plane)]

def _first_particle_kick(world: World, packed, integrated: np.ndarray, h: float, dt: float,
                         acc: np.ndarray) -> None:
    """The soft step's particle rows start, as its bodies do, with one substep's kick of
    h: the integration gave those it moved the whole dt's (kept: one substep's); one
    that a body's row woke since (``find_body_rows``) was not integrated: it gets its h
    (at g + F/m: what the integration gives a particle at rest); a sleeper in the view
    (its rows left out) gets none and stays out of the substeps (not awake in the view:
    with the whole view kicked, a particle asleep on a box rose 1 mm in its first step
    asleep, which woke it again, for ever)."""
    n = world.bodies.count
    p = world.particles
    sel = packed.selected
    awake = p.awake[sel]
    packed.awake[n:] = awake
    moved = integrated[sel]
    packed.velocity[n:][moved] -= p.acceleration[sel[moved]] * (dt - h)
    woken = awake & ~moved
    if woken.any():
        i = sel[woken]
        a = world._folded[1] + p.force[i] * p.inv_mass[i, None]
        p.acceleration[i] = a
        acc[n:][woken] = a
        # at rest until now: v = a·h, then the particle's damping over h (as integrated)
        packed.velocity[n:][woken] = a * h * (p.damping[i] ** h)[:, None]

def _apply_body_forces(world: World, dt: float):
    """Let the body force generators add to the user's forces for this substep (of ``dt``:
    the soft step's first, whose others find them again), wake the
    bodies they push, and return (the user's own forces and torques to put back after the
    substep, or None; what the forces alone give each body [m/s²], for the resting-contact
    trick)."""
    b = world.bodies
    kept = None
    if world.body_forces:
        kept = b.force.copy(), b.torque.copy()
        try:
            for generator in world.body_forces:
                generator.apply(b, dt)
        except BaseException:
            b.force[:], b.torque[:] = kept
            raise
    if world._sleep:
        sleeping.wake_pushed(b)
    return kept, force_acceleration(b.inv_mass, b.force, world._gravity)

def _refind_body_forces(world: World, view, kept, h: float) -> np.ndarray:
    """The soft step's forces found again within its step (``body_soft.step``'s
    ``forces``): the user's own forces and torques, plus every body force generator at the
    bodies' current state (read from ``view``, the packed copy when particles take part);
    returns what the forces alone give each body [m/s²]."""
    b = world.bodies
    if view is not b:
        n = b.count
        b.position[:] = view.position[:n]
        b.orientation[:] = view.orientation[:n]
        b.velocity[:] = view.velocity[:n]
        b.angular_velocity[:] = view.angular_velocity[:n]
    b.force[:], b.torque[:] = kept
    for generator in world.body_forces:
        generator.apply(b, h)
    return force_acceleration(b.inv_mass, b.force, world._gravity)

def kick(world: World, dt: float, which: np.ndarray, drift: float = 0.0) -> None:
    """The velocity half of the bodies' integration over ``dt``, for the bodies of mask
    ``which``: gravity, forces, torques and damping (the soft step's first substep; its
    later substeps' kicks are ``body_soft.kick``, with the same forces). ``drift``: the
    drift that follows when it is not ``dt`` (a leapfrog's opening half kick), for the
    spin's cap (``integrate_velocities``)."""
    b = world.bodies
    spun = integrate_velocities(b.velocity, b.angular_velocity, b.force, b.torque,
                                b.inv_mass, b.inv_inertia, b.inv_inertia_world,
                                b.linear_damping, b.angular_damping, world._gravity, dt, which,
                                drift)
    if spun >= 0:
        raise spin_error(b, spun, dt, world.time)
