"""Small fixed scenes for the golden images and renderer tests (no GL here)."""

from __future__ import annotations

import numpy as np

import pointmass as pm


def spheres_scene() -> pm.Scene:
    """Five lit spheres of different sizes and heights over the ground (shadows)."""
    world = pm.World()
    for x, y, z, r in [(-1.6, 0.5, 0.0, 0.5), (0.0, 0.35, 0.6, 0.35), (1.5, 1.4, -0.3, 0.45),
                       (0.4, 2.3, -1.4, 0.3), (-0.6, 0.2, 1.6, 0.2)]:
        world.add_particle((x, y, z), radius=r)
    return pm.Scene(world, camera=pm.CameraHint(target=(0, 0.6, 0), distance=6, yaw=25,
                                                pitch=22))


def lines_scene() -> pm.Scene:
    """Each kind of link: a stretched, a resting and a compressed spring, a slack and a taut
    cable, a rod, a bungee, and an anchored spring (anchor marker)."""
    world = pm.World()
    p = [world.add_particle(pos, radius=0.12) for pos in [
        (-2.0, 0.5, 0.0), (-1.0, 0.5, 0.0), (0.0, 0.5, 0.0), (1.0, 0.5, 0.0), (2.0, 0.5, 0.0),
        (-2.0, 1.5, -1.0), (0.0, 1.5, -1.0), (2.0, 1.5, -1.0), (0.0, 1.2, 1.0)]]
    world.add(pm.Spring([p[0], p[1], p[2]], [p[1], p[2], p[3]], 10.0, [0.7, 1.0, 1.3]))
    world.add(pm.Rod(p[3], p[4], 1.0))
    world.add(pm.Cable([p[5], p[6]], [p[6], p[7]], [3.0, 2.0]))
    world.add(pm.Bungee(p[4], p[7], 5.0, 1.0))
    world.add(pm.AnchoredSpring(p[8], (0.0, 2.6, 1.0), 10.0, 1.0))
    return pm.Scene(world, camera=pm.CameraHint(target=(0, 1.0, 0), distance=6.5, yaw=15,
                                                pitch=20), point_radius=0.12)


def grid_scene() -> pm.Scene:
    """Nothing but the ground grid and the sky."""
    return pm.Scene(pm.World(), camera=pm.CameraHint(target=(0, 0, 0), distance=8, yaw=30,
                                                     pitch=30))


def cube_scene() -> pm.Scene:
    """A rotated cube, a wireframe box, a translucent plane and a sphere."""
    world = pm.World()
    world.add_particle((1.2, 0.4, 0.8), radius=0.4)
    c, s = np.cos(0.6), np.sin(0.6)
    rot = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]) @ np.array(
        [[1, 0, 0], [0, np.cos(0.5), -np.sin(0.5)], [0, np.sin(0.5), np.cos(0.5)]])
    scene = pm.Scene(world, camera=pm.CameraHint(target=(0, 0.8, 0), distance=6, yaw=30,
                                                 pitch=20))
    scene.boxes.append(pm.BoxVisual(center=(-0.5, 1.0, -0.3), half_size=(0.6, 0.6, 0.6),
                                    rotation=rot, color=(0.9, 0.55, 0.2)))
    scene.boxes.append(pm.BoxVisual(center=(1.6, 0.5, -1.2), half_size=(0.5, 0.5, 0.3),
                                    color=(0.5, 0.9, 0.6), wireframe=True))
    scene.planes.append(pm.PlaneVisual(center=(0.0, 0.3, 1.8), half_size=(1.5, 0.6),
                                       color=(0.2, 0.45, 0.9, 0.5)))
    return scene


def night_scene() -> pm.Scene:
    """A frozen firework burst at night: twelve glowing sparks flying out of a centre, each with
    a short trail (recorded in ``handles["trails"]``), and a rising rocket; two colors overlap
    where the sparks cross."""
    from pointmass.trails import Trails

    world = pm.World(gravity=(0.0, 0.0, 0.0))
    angles = np.linspace(0.0, 2.0 * np.pi, 12, endpoint=False)
    out = np.c_[np.cos(angles), np.sin(angles), 0.3 * np.sin(3 * angles)]
    centre = np.array([0.0, 2.5, 0.0])
    world.add_particles(np.r_[centre + 1.4 * out, [(1.5, 0.8, 0.5)]])
    colors = np.r_[np.tile([(1.0, 0.35, 0.2), (0.3, 0.6, 1.0)], (6, 1)), [(1.0, 0.85, 0.4)]]
    scene = pm.Scene(world, colors=colors, point_radius=0.05, sky="night", glow=True,
                     trails=list(range(13)), trail_length=6,
                     camera=pm.CameraHint(target=(0, 1.8, 0), distance=6, yaw=20, pitch=5))
    pos = world.particles.position
    end = pos.copy()
    trails = scene.handles["trails"] = Trails()
    for k in range(5):                       # the paths that led here, oldest first
        t = (k + 1) / 6
        pos[:12] = centre + 1.4 * t * out
        pos[12] = end[12] - (1 - t) * np.array([0.0, 0.8, 0.0])
        trails.record(scene)
    pos[:] = end                             # now: the trails end at the particles
    return scene
