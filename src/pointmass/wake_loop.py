"""The wake loop: which sleeping islands of particles and bodies a step must wake, and which
fall asleep at its end (``particle_sleep.py``, ``rigid/sleep.py``, ``rigid/islands.py``).

These are the parts of ``World``'s step that decide who moves; they read and write the
world's stores and its sleep state (``_longest_still``, ``_plinks``, ``_wakes_seen``), and
``World.step`` calls them at its stages."""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import TYPE_CHECKING

import numpy as np

from . import particle_sleep as psleep
from .rigid import sleep as sleeping
from .rigid.collide import generate as generate_body_contacts
from .rigid.particle_body import add_particle_contacts

if TYPE_CHECKING:
    from .world import World


def wake_disturbed(world: World, dt: float) -> bool:
    """Before the integration of a substep of ``dt``: wake the islands of sleeping
    particles that a force or the user disturbed (``particle_sleep.py``) and keep the
    force of those that may fall asleep after this step; returns whether any still sleep.
    """
    p = world.particles
    # Still for this long, a particle may fall asleep at the end of this step (a margin of
    # a step for the sums of the still-time's floats).
    candidate = psleep.TIME_TO_SLEEP - 2.0 * dt * world._substeps
    if p.awake.all():
        if world._longest_still < candidate:
            return False  # none can fall asleep after this step: no rest force to keep
        psleep.disturbed(p.force, p.rest_force, p.velocity, p.position, p.still_position,
                         p.inv_mass, p.rest_inv_mass, p.awake, p.sleep_time, candidate,
                         psleep.NUDGE,
                         np.zeros(0, np.bool_))
        return False
    out = np.zeros(p.count, np.bool_)
    if psleep.disturbed(p.force, p.rest_force, p.velocity, p.position, p.still_position,
                        p.inv_mass, p.rest_inv_mass, p.awake, p.sleep_time, candidate,
                         psleep.NUDGE, out):
        wake_particles(world, out)
    return not p.awake.all()


def wake_touched(world: World, live: np.ndarray, g: np.ndarray, dt: float) -> None:
    """After finding contacts with particles asleep: wake the islands that a row or a link
    joins to an active particle (those woken get this substep's kick: their rows are
    solved), until none; then leave out the rows that still reach a sleeper."""
    p = world.particles
    c = world.contacts
    if not live.any():  # nothing moves: no rows were found, no link can wake
        p.force[~p.awake] = 0.0
        return
    links = particle_links(world)
    while True:
        out = np.zeros(p.count, np.bool_)
        psleep.touched(c.a, c.b, c.normal, c.penetration, p.velocity, p.awake, live,
                       float(dt), out)
        if links.shape[0]:
            psleep.wake_linked(p, links, live, out)
        if not out.any():
            break
        woken = wake_particles(world, out)
        psleep.kick(p.velocity, p.acceleration, p.force, p.inv_mass, p.damping, woken, g,
                    float(dt))
        psleep.drift(p.position, p.velocity, woken, float(dt), c.a, c.b, c.normal,
                     c.penetration, c.count)
        live = psleep.active(p)
    asleep = ~p.awake
    p.force[asleep] = 0.0  # the accumulator is consumed, as by the integration
    if c.count:
        psleep.leave_out_sleepers(c, p.awake)


def particle_links(world: World) -> np.ndarray:
    """This step's particle pairs that share an island (``psleep.link_pairs``), made once
    a step when first asked for."""
    if world._plinks is None:
        world._plinks = psleep.link_pairs(world.forces, world.contact_generators)
    return world._plinks


def wake_particles(world: World, marked: np.ndarray) -> np.ndarray:
    """Wake the islands of the sleeping particles of mask ``marked`` (and the bodies of
    those islands); returns the mask of the particles woken."""
    p = world.particles
    labels = np.unique(p.island[marked & ~p.awake])
    woken = p.wake_islands(labels)
    b = world.bodies
    if b.count and (labels < b.count).any() and not b.awake.all():
        b.wake_islands(labels)  # an island of both: its bodies get the body stage's kick
    return woken


def find_body_rows(world: World, dt: float, acc: np.ndarray, planes: list,
                   kick: Callable[[np.ndarray], None], table: np.ndarray | None = None):
    """This substep's body rows, then the particle–body rows; returns the packed view (or
    None) and ``acc`` extended to it. A sleeping island that a row wakes gets its first kick
    (``kick``, called with the mask of the bodies woken: the soft step's leapfrog half kick,
    ``body_stage.kick``) and the rows are made again, until no row touches a sleeping body
    that should wake. ``planes``: the
    world's ``Plane``s (``body_stage.world_planes``, found once a step); ``table``: their
    ``collide.plane_table`` when the caller has it."""
    b = world.bodies
    p = world.particles
    links = body_links(world) if world._sleep else None
    exclude = world.joints.pair_keys(b.count) if world.joints else None
    while True:
        if b.wakes != world._wakes_seen:  # islands woke (here, or by hand since)
            world._wakes_seen = b.wakes
            world.sleeping_impulses.give_back(world.body_impulses, b.awake)
        live = sleeping.active(b) if world._sleep and not b.awake.all() else None
        if live is not None and not live.any():  # all asleep or still: nothing to find
            world.body_contacts.resize(0)
        else:
            generate_body_contacts(b, planes, dt, world.body_contacts, active=live,
                                   exclude=exclude, table=table)
        packed = add_particle_contacts(b, p, dt, world.body_contacts, world._particle_friction,
                                       world._particle_restitution)
        full = acc if packed is None else np.concatenate(
            [acc, p.acceleration[packed.selected]])
        if packed is not None and world._sleep and not p.awake.all():
            # a moving body wakes the sleeping particles it touches; the rows that still
            # reach a sleeping particle are left out (``particle_sleep.py``)
            c = world.body_contacts
            out = np.zeros(p.count, np.bool_)
            movers = sleeping.active(b) if live is None else live
            if psleep.touched_by_bodies(b.count, c.a, c.b, c.normal, c.depth,
                                        packed.selected, p.velocity, b.velocity,
                                        b.angular_velocity, c.r_b, p.awake, movers,
                                        float(dt), out):
                was = b.awake.copy()
                wake_particles(world, out)
                if (b.awake & ~was).any():  # their first kick
                    kick(b.awake & ~was)
                continue  # again, with the woken
            slot = c.a >= b.count
            reach = np.zeros(c.a.shape[0], np.bool_)
            reach[slot] = ~p.awake[packed.selected[c.a[slot] - b.count]]
            if reach.any():
                c.keep(~reach)
        if live is None:
            return packed, full
        assert links is not None  # ``live`` is only set with sleeping on, as ``links``
        woken = sleeping.touched(b, world.body_contacts, packed, full, dt, links, live)
        if not woken.any():
            sleeping.leave_sleepers_out(b, world.body_contacts, packed)
            return packed, full
        kick(b.wake_islands(np.unique(b.island[woken])))


def body_links(world: World) -> np.ndarray:
    """The body pairs (K, 2) that share an island: ``island_links`` and every joint's."""
    links = sleeping.check_links(world.island_links, world.bodies.count)
    if not world.joints:
        return links
    return np.concatenate([links, world.joints.body_pairs()])


def fall_asleep(world: World, dt: float) -> None:
    """End of a step: islands of bodies and particles still for long enough fall asleep
    (``rigid/sleep.py``, ``particle_sleep.py``)."""
    b = world.bodies
    packed = world._packed if b.count else None
    slept, world._longest_still = psleep.fall_asleep(
        b, world.body_contacts, None if packed is None else packed.selected,
        partial(body_links, world) if b.count else partial(np.zeros, (0, 2), np.int64),
        world.particles,        world.contacts, partial(particle_links, world), dt)
    if slept is not None:
        world.sleeping_impulses.put_away(world.body_impulses, slept)

