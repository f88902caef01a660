"""The pure-Python baseline: the Physics Cook Book's engine, written the way the cookbook writes it.

One object per particle, a ``Vector3`` class, a force registry of callables on each particle,
sphere collisions found by checking every pair (O(N²)), and Millington's contact resolver
(worst contact first, velocity then interpenetration) in plain Python. No numpy, no numba:
this is what ``benchmarks/bench_physics.py`` compares pointmass against.

Deviations from the cookbook text, each to make it run correctly: the spring force is signed
(the cookbook's abs(extension) is Cyclone bug #1), ``euclidean_distance`` takes ``self``, the
resolver clears the stored movement on every early return (Cyclone bug #6).
"""

from __future__ import annotations


class Vector3:
    def __init__(self, x=0.0, y=0.0, z=0.0):
        self.x, self.y, self.z = x, y, z

    # Get how long the vector is
    def magnitude(self):
        return (self.x**2 + self.y**2 + self.z**2) ** 0.5

    # Make the length = 1 without changing the direction
    def normalize(self):
        if (self.x, self.y, self.z) == (0, 0, 0):
            return Vector3()
        return self.scalar_multiply(1 / self.magnitude())

    def invert(self):
        return Vector3(-self.x, -self.y, -self.z)

    def scalar_multiply(self, scalar):
        return Vector3(self.x * scalar, self.y * scalar, self.z * scalar)

    def euclidean_distance(self, other):
        return ((self.x - other.x) ** 2 + (self.y - other.y) ** 2
                + (self.z - other.z) ** 2) ** 0.5

    def __add__(self, vect):
        return Vector3(self.x + vect.x, self.y + vect.y, self.z + vect.z)

    def __sub__(self, vect):
        return self + vect.invert()

    # The scalar (dot) product with a vector, else scaling by a number
    def __mul__(self, other):
        if type(other) is Vector3:
            return self.x * other.x + self.y * other.y + self.z * other.z
        return self.scalar_multiply(other)


class Particle:
    def __init__(self, v=None, p=None, mass=1.0, radius=0.0):
        self.velocity = v if v is not None else Vector3()
        self.position = p if p is not None else Vector3()
        self.inverse_mass = 0.0 if mass == float("inf") else 1.0 / mass
        self.radius = radius
        self.force_registry = []  # callables: particle -> force
        self.acceleration = Vector3()

    def register_force(self, force_generator):
        self.force_registry.append(force_generator)

    def tick(self, delta_t):
        f_net = Vector3()
        for force_generator in self.force_registry:
            f_net += force_generator(self)
        if self.inverse_mass == 0:
            return
        self.acceleration = f_net * self.inverse_mass
        self.velocity += self.acceleration * delta_t
        self.position += self.velocity * delta_t


class GravityGenerator:
    def __init__(self, strength):
        self.force = Vector3(0, -strength, 0)

    def __call__(self, particle):
        if particle.inverse_mass == 0:
            return Vector3()
        return self.force * (1.0 / particle.inverse_mass)


class DragGenerator:
    def __init__(self, linear_coefficient, quadratic_coefficient):
        self.l, self.q = linear_coefficient, quadratic_coefficient

    def __call__(self, particle):
        speed = particle.velocity.magnitude()
        drag_coefficient = self.l * speed + self.q * speed**2
        return particle.velocity.normalize() * -drag_coefficient


class SpringGenerator:
    def __init__(self, other_particle, spring_constant, resting_length):
        self.other_particle = other_particle
        self.spring_constant, self.resting_length = spring_constant, resting_length

    def __call__(self, particle):
        delta_p = particle.position - self.other_particle.position
        length = delta_p.magnitude()
        force_magnitude = (length - self.resting_length) * self.spring_constant
        return delta_p.normalize() * -force_magnitude


def connect(p1, p2, spring_constant, resting_length):
    """A spring between two particles: each needs its own generator, as in the cookbook."""
    p1.register_force(SpringGenerator(p2, spring_constant, resting_length))
    p2.register_force(SpringGenerator(p1, spring_constant, resting_length))


class Contact:
    """Particle ``a`` touches ``b`` (another particle, or None for a wall); normal from b to a."""

    def __init__(self, a, b, normal, penetration, restitution):
        self.a, self.b = a, b
        self.normal, self.penetration, self.restitution = normal, penetration, restitution
        self.movement = (Vector3(), Vector3())

    def separating_velocity(self):
        relative = self.a.velocity
        if self.b is not None:
            relative = relative - self.b.velocity
        return relative * self.normal

    def total_inverse_mass(self):
        return self.a.inverse_mass + (self.b.inverse_mass if self.b is not None else 0.0)

    def resolve_velocity(self, dt):
        separating = self.separating_velocity()
        if separating > 0:
            return
        new_separating = -separating * self.restitution
        # Resting contacts: do not bounce what this frame's acceleration alone built up.
        acc = self.a.acceleration
        if self.b is not None:
            acc = acc - self.b.acceleration
        from_acceleration = (acc * self.normal) * dt
        if from_acceleration < 0:
            new_separating = max(new_separating + self.restitution * from_acceleration, 0.0)
        total = self.total_inverse_mass()
        if total <= 0:
            return
        impulse_per_imass = self.normal * ((new_separating - separating) / total)
        self.a.velocity += impulse_per_imass * self.a.inverse_mass
        if self.b is not None:
            self.b.velocity += impulse_per_imass * -self.b.inverse_mass

    def resolve_interpenetration(self):
        total = self.total_inverse_mass()
        if self.penetration <= 0 or total <= 0:
            self.movement = (Vector3(), Vector3())  # Cyclone forgets this
            return
        per_imass = self.normal * (self.penetration / total)
        move_a = per_imass * self.a.inverse_mass
        move_b = per_imass * -(self.b.inverse_mass if self.b is not None else 0.0)
        self.a.position += move_a
        if self.b is not None:
            self.b.position += move_b
        self.movement = (move_a, move_b)


def resolve_contacts(contacts, iterations, dt):
    """Millington's resolver: resolve the most closing (or penetrating) contact, repeat."""
    for _ in range(iterations):
        worst, worst_speed = None, float("inf")
        for contact in contacts:
            speed = contact.separating_velocity()
            if speed < worst_speed and (speed < 0 or contact.penetration > 0):
                worst, worst_speed = contact, speed
        if worst is None:
            return
        worst.resolve_velocity(dt)
        worst.resolve_interpenetration()
        move_a, move_b = worst.movement
        for contact in contacts:  # patch the penetration of contacts sharing a particle
            for moved, move in ((worst.a, move_a), (worst.b, move_b)):
                if moved is None:
                    continue
                if contact.a is moved:
                    contact.penetration -= move * contact.normal
                elif contact.b is moved:
                    contact.penetration += move * contact.normal


class World:
    """Particles, their forces, spheres colliding pairwise and with axis-aligned walls."""

    def __init__(self, walls=(), restitution=0.5):
        self.particles = []
        self.walls = walls  # (normal Vector3, offset): keep n·p - radius >= offset
        self.restitution = restitution

    def contacts(self):
        found = []
        spheres = [p for p in self.particles if p.radius > 0]
        for i, a in enumerate(spheres):  # every pair: O(N²)
            for b in spheres[i + 1:]:
                distance = a.position.euclidean_distance(b.position)
                if distance < a.radius + b.radius:
                    normal = (a.position - b.position).normalize()
                    found.append(Contact(a, b, normal, a.radius + b.radius - distance,
                                         self.restitution))
            for normal, offset in self.walls:
                gap = a.position * normal - offset - a.radius
                if gap < 0:
                    found.append(Contact(a, None, normal, -gap, self.restitution))
        return found

    def step(self, dt):
        for particle in self.particles:
            particle.tick(dt)
        contacts = self.contacts()
        if contacts:
            resolve_contacts(contacts, 2 * len(contacts), dt)
        return len(contacts)
