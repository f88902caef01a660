"""Particles against rigid bodies: a particle with a radius is a sphere body with no inertia.

Every particle with radius > 0 meets every body with a shape, automatically, once the world
has bodies. The contacts are rows of the body stage (``solver/body_soft.py``): the solver
works on a packed view — the bodies first, at their own indices (so body–body rows, keys and
arithmetic are exactly those of a world without particles), then the touching particles as
extra bodies with their inverse mass, zero inverse inertia and the identity orientation. The
body feels each impulse at the contact point with its angular terms; the particle feels it
through its centre.

The particle stage has already moved the particles (x += v·dt) when the body stage runs, so
a particle is narrow-phased at the point it drifted from, x − v·dt (where the bodies are, at
the start of their drift), and after the velocity rows it drifts again with its new velocity:
x += (v_new − v)·dt (adds exactly 0 to a particle the rows left alone). The position rows
then follow it like a body.

Broadphase: the bodies' AABBs (``broadphase.bounds``, grown by the margin and their travel)
sorted by low x; each particle's AABB (radius + margin + its own travel) finds its candidate
bodies by binary search in that order, bounded by the widest body: O(P log N + pairs).
Narrow phase: ``sphere_box`` and ``sphere_sphere`` with the particle as sphere A (normal from
the body to the particle).

Materials: the particles' surface is the world's ``particle_friction`` and
``particle_restitution``; a contact uses √(μp·μb) and max(ep, eb), the bodies' rule.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..keys import PARTICLE_KEY_LIMIT, particle_body_key
from .broadphase import bounds
from .contacts import BodyContacts
from .manifold import MAX_POINTS
from .narrow_sphere import sphere_box, sphere_sphere
from .shapes import BOX, SPHERE

#: Gap [m] below which a particle–body pair reports a speculative point, besides what the two
#: can travel in the step (Box3D's speculative distance; body–body pairs use 5 mm,
#: ``collide.SPECULATIVE_MARGIN``, a choice measured on box piles only).
PARTICLE_MARGIN = 0.02


@njit(cache=True, nogil=True)
def particle_body_pairs(ppos, pvel, radius, pinv, dt, margin, low, high, reach, order,
                        low_x, widest, bpos, quat, shape, size, binv, friction, restitution,
                        mu_p, e_p, out_p, out_b, out_n, out_pt, out_d, out_mu, out_e, out_key):
    """Contact points of every particle with radius > 0 against the bodies (AABBs ``low``,
    ``high``, travel ``reach``, taken in ``order`` whose low x are ``low_x``, sorted; the
    widest AABB along x is ``widest``). A particle is tested at ppos − pvel·dt. Writes the
    particle, the body, the normal (body to particle), the world point, the depth, μ, e and
    the key; returns the count, or −(count needed) when the outputs are too short."""
    normal = np.zeros(3)
    points = np.zeros((MAX_POINTS, 3))
    depth = np.zeros(MAX_POINTS)
    ids = np.zeros(MAX_POINTS, np.int64)
    c = np.zeros(3)
    cap = out_p.shape[0]
    count = 0
    n = order.shape[0]
    for i in range(ppos.shape[0]):
        r = radius[i]
        if r <= 0.0:
            continue
        vx, vy, vz = pvel[i, 0], pvel[i, 1], pvel[i, 2]
        c[0] = ppos[i, 0] - vx * dt
        c[1] = ppos[i, 1] - vy * dt
        c[2] = ppos[i, 2] - vz * dt
        travel = math.sqrt(vx * vx + vy * vy + vz * vz) * dt
        grow = r + margin + travel
        # first body whose low x could reach this particle: low x ≥ its low − the widest box
        lo = 0
        hi = n
        key = c[0] - grow - widest
        while lo < hi:
            mid = (lo + hi) // 2
            if low_x[mid] < key:
                lo = mid + 1
            else:
                hi = mid
        for u in range(lo, n):
            if low_x[u] > c[0] + grow:
                break
            j = order[u]
            if low[j, 0] > high[j, 0]:
                continue  # no shape
            if (high[j, 0] < c[0] - grow or low[j, 1] > c[1] + grow or high[j, 1] < c[1] - grow
                    or low[j, 2] > c[2] + grow or high[j, 2] < c[2] - grow):
                continue
            if pinv[i] == 0.0 and binv[j] == 0.0:
                continue
            m = margin + travel + reach[j]
            if shape[j] == BOX:
                got = sphere_box(c, r, bpos[j], quat[j], size[j], m, normal, points, depth, ids)
            elif shape[j] == SPHERE:
                got = sphere_sphere(c, r, bpos[j], size[j, 0], m, normal, points, depth, ids)
            else:
                got = 0
            if got == 0:
                continue
            if count < cap:
                out_p[count] = i
                out_b[count] = j
                for k in range(3):
                    out_n[count, k] = normal[k]
                    out_pt[count, k] = points[0, k]
                out_d[count] = depth[0]
                out_mu[count] = math.sqrt(mu_p * friction[j])
                out_e[count] = max(e_p, restitution[j])
                out_key[count] = particle_body_key(i, j, ids[0])
            count += 1
    return count if count <= cap else -count


class Packed:
    """The solver's view of bodies and touching particles (module docstring): bodies first,
    then the particles ``selected``, as the body stage's kernels read a ``Bodies``."""

    def __init__(self, bodies, particles, selected: np.ndarray, origin: np.ndarray) -> None:
        b = bodies
        k = selected.shape[0]
        self.count = b.count + k
        self.selected = selected
        self.inv_mass = np.concatenate([b.inv_mass, particles.inv_mass[selected]])
        self.inv_inertia = np.concatenate([b.inv_inertia, np.zeros((k, 3))])
        self.inv_inertia_world = np.concatenate([b.inv_inertia_world, np.zeros((k, 3, 3))])
        identity = np.zeros((k, 4))
        identity[:, 0] = 1.0
        self.orientation = np.concatenate([b.orientation, identity])
        self.position = np.concatenate([b.position, origin])
        self.velocity = np.concatenate([b.velocity, particles.velocity[selected]])
        self.angular_velocity = np.concatenate([b.angular_velocity, np.zeros((k, 3))])
        self.awake = np.concatenate([b.awake, np.ones(k, bool)])  # joints skip sleeping rows
        # a particle is a sphere of its radius (the soft step's round rows: its point lies
        # along the normal as it now lies, and on a sphere body along the two centres)
        self.shape = np.concatenate([b.shape, np.full(k, SPHERE, b.shape.dtype)])
        self.size = np.concatenate([b.size, np.repeat(particles.radius[selected, None], 3,
                                                      axis=1)])
        #: Sleeping bodies that particles rest on, immovable in this view (``freeze``).
        self.frozen: np.ndarray | None = None

    def freeze(self, frozen: np.ndarray) -> None:
        """Make the bodies of mask ``frozen`` (N,) immovable in this view (sleeping bodies a
        particle rests on: it pushes against them as against scenery, ``islands.py``)."""
        self.frozen = frozen
        self.inv_mass[: frozen.shape[0]][frozen] = 0.0
        self.inv_inertia_world[: frozen.shape[0]][frozen] = 0.0

    def take_positions(self, bodies, particles) -> None:
        """After the soft step: positions, the bodies' turns and spins back."""
        n = bodies.count
        bodies.position[:] = self.position[:n]
        bodies.orientation[:] = self.orientation[:n]
        bodies.angular_velocity[:] = self.angular_velocity[:n]
        live = slice(None) if self.frozen is None else ~self.frozen
        bodies.inv_inertia_world[live] = self.inv_inertia_world[:n][live]
        particles.position[self.selected] = self.position[n:]




def add_particle_contacts(bodies, particles, dt: float, contacts: BodyContacts,
                          friction: float, restitution: float,
                          margin: float = PARTICLE_MARGIN) -> Packed | None:
    """Append the particle–body points of this substep to ``contacts`` (after the body rows)
    and return the packed view they index into, or None (``contacts`` untouched) when no
    particle is near a body."""
    p = particles
    b = bodies
    if p.count == 0 or b.count == 0 or not (p.radius > 0.0).any():
        return None
    if p.count > PARTICLE_KEY_LIMIT:
        raise ValueError(f"at most {PARTICLE_KEY_LIMIT} particles meet bodies (contact keys "
                         f"have 35 bits for a particle), got {p.count}")
    n = b.count
    low = np.empty((n, 3))
    high = np.empty((n, 3))
    reach = np.empty(n)
    bounds(b.position, b.orientation, b.velocity, b.angular_velocity, b.shape, b.size, margin,
           dt, low, high, reach)
    order = np.argsort(low[:, 0], kind="stable")
    low_x = low[order, 0]
    width = high[:, 0] - low[:, 0]
    widest = float(width.max()) if n else 0.0
    cap = 64
    while True:
        out_p = np.empty(cap, np.int64)
        out_b = np.empty(cap, np.int64)
        out_n = np.empty((cap, 3))
        out_pt = np.empty((cap, 3))
        out_d = np.empty(cap)
        out_mu = np.empty(cap)
        out_e = np.empty(cap)
        out_key = np.empty(cap, np.int64)
        got = particle_body_pairs(p.position, p.velocity, p.radius, p.inv_mass, dt, margin,
                                  low, high, reach, order, low_x, widest, b.position,
                                  b.orientation, b.shape, b.size, b.inv_mass, b.friction,
                                  b.restitution, friction, restitution, out_p, out_b, out_n,
                                  out_pt, out_d, out_mu, out_e, out_key)
        if got >= 0:
            break
        cap = -got
    if got == 0:
        return None
    rows = slice(0, got)
    who = out_p[rows]
    selected, slot = np.unique(who, return_inverse=True)
    origin = p.position[selected] - p.velocity[selected] * dt
    packed = Packed(b, p, selected, origin)
    point = out_pt[rows]
    body = out_b[rows]
    extra = {
        "a": n + slot.reshape(-1).astype(np.int64),
        "b": body,
        "normal": out_n[rows],
        "r_a": point - origin[slot.reshape(-1)],
        "r_b": point - b.position[body],
        "depth": out_d[rows],
        "friction": out_mu[rows],
        "restitution": out_e[rows],
        "key": out_key[rows],
        "impulse": np.zeros(got),
    }
    total = contacts.count + got
    for name in BodyContacts.FIELDS:
        setattr(contacts, name, np.concatenate([getattr(contacts, name), extra[name]]))
    contacts.count = total
    return packed
