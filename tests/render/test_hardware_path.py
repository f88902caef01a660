"""The renderer's hardware path (particles in GPU buffers, shadows drawn by the GPU), forced
under llvmpipe: it draws what the software path draws; its look goes up only when it changes;
the path is chosen by the GL renderer's name unless forced; pixel-buffer reads come back in
order."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm

pytestmark = pytest.mark.gl

SIZE = (640, 360)


def _crowd(count: int = 10_000, seed: int = 0) -> pm.Scene:
    """``count`` balls (r = 0.12 m) over a 24 m square up to 3 m high, some resting on the
    ground, 500 springs among the first 1000 (benchmarks/bench_render.py's scene)."""
    rng = np.random.default_rng(seed)
    world = pm.World()
    pos = np.c_[rng.uniform(-12, 12, count), rng.uniform(0.12, 3.0, count),
                rng.uniform(-12, 12, count)]
    pos[: count // 10, 1] = 0.12
    springs = np.arange(0, min(count, 1000) - 1, 2)
    pos[springs + 1] = pos[springs] + rng.normal(0.0, 0.3, (len(springs), 3))
    pos[:, 1] = np.abs(pos[:, 1] - 0.12) + 0.12
    world.add_particles(pos, radii=0.12)
    world.add(pm.Spring(springs, springs + 1, 10.0, 0.5))
    return pm.Scene(world, camera=pm.CameraHint(target=(0, 0.5, 0), distance=26, yaw=30,
                                                pitch=28))


def _draw(ctx, scene, path, **options):
    from pointmass.render import OrbitCamera, Renderer

    r = Renderer(ctx, SIZE, path=path)
    try:
        assert r.path == path
        r.render(scene, OrbitCamera.from_hint(scene.camera), **options)
        return r.read_rgb()
    finally:
        r.release()


def _compare(a: np.ndarray, b: np.ndarray) -> tuple[float, float]:
    """(mean absolute difference per channel [0-255], fraction of pixels off by > 16)."""
    d = np.abs(a.astype(np.int16) - b.astype(np.int16))
    return float(d.mean()), float((d.max(axis=2) > 16).mean())


def test_hardware_path_draws_10k_spheres_as_the_software_path_does(ctx):
    """10 000 spheres with springs and shadows: the hardware path's shaders (run by llvmpipe)
    give the software path's picture, but for single pixels on silhouettes (measured: mean
    difference 0.52 of 255, 0.2 % of pixels off by more than 16)."""
    scene = _crowd()
    soft = _draw(ctx, scene, "software")
    hard = _draw(ctx, scene, "hardware")
    mean, off = _compare(soft, hard)
    assert mean < 1.0 and off < 0.005, (mean, off)
    # Not two blank images: the crowd covers much of the frame, shadows included.
    assert soft.std() > 30


def test_hardware_shadows_darken_the_ground_as_the_splatted_ones(ctx):
    """Looking down on 2000 spheres: on the ground around them (sphere pixels left out), the
    GPU's blob discs take away as much light as the CPU-splatted map does."""
    import dataclasses

    scene = _crowd(2000, seed=3)
    scene.camera = pm.CameraHint(target=(0, 0, 0), distance=30, yaw=0, pitch=89)
    soft = _draw(ctx, scene, "software").astype(float)
    hard = _draw(ctx, scene, "hardware").astype(float)
    ground = _draw(ctx, pm.Scene(pm.World(), camera=scene.camera), "software").astype(float)
    # Where the spheres are: pixels that differ from the sky with the ground left out.
    floating = _draw(ctx, dataclasses.replace(scene, show_ground=False), "software")
    sky = _draw(ctx, pm.Scene(pm.World(), camera=scene.camera, show_ground=False), "software")
    open_ground = ~(floating != sky).any(axis=2)
    dark_soft = (ground - soft)[open_ground].mean()
    dark_hard = (ground - hard)[open_ground].mean()
    assert dark_soft > 0.5, dark_soft
    assert dark_hard == pytest.approx(dark_soft, rel=0.15)


def test_glow_rigid_bodies_and_links_match(ctx):
    """Glowing particles (their own program), rigid bodies (spheres with spin markers, boxes,
    their blob shadows) and links drawn from the GPU's positions (the cloth's springs colored
    by strain; the bridge's rods, and cables dashed when slack) on the hardware path."""
    from pointmass.demo import Simulation, load_demo

    for name, seconds in (("fireworks", 3.0), ("big_ballistic", 2.0), ("cloth", 2.0),
                          ("bridge", 2.0)):
        sim = Simulation(load_demo(name))
        for _ in range(round(seconds * 30)):
            sim.advance(1 / 30)
        soft = _draw(ctx, sim.scene, "software", trails=sim.trails)
        hard = _draw(ctx, sim.scene, "hardware", trails=sim.trails)
        mean, off = _compare(soft, hard)
        assert mean < 0.5 and off < 0.002, (name, mean, off)


def test_look_goes_up_only_when_it_changes(ctx, monkeypatch):
    """No new look while nothing changes; an in-place color edit is seen (compared) in a small
    scene; above COMPARE_MAX only ``scene.look_changed()`` or a new array says so; and the
    picture follows."""
    from pointmass.render import OrbitCamera, Renderer, look

    world = pm.World()
    world.add_particles([(0.0, 1.0, 0.0), (1.5, 1.0, 0.0)], radii=0.6)
    scene = pm.Scene(world, colors=np.array([(1.0, 0.0, 0.0), (0.0, 0.0, 1.0)]),
                     camera=pm.CameraHint(target=(0.75, 1, 0), distance=6, yaw=0, pitch=0))
    r = Renderer(ctx, (160, 120), path="hardware")
    cam = OrbitCamera.from_hint(scene.camera)
    try:
        first = r.capture(scene)
        assert first.look is not None and first.positions.dtype == np.float32
        r.draw(first, cam)
        assert r.capture(scene).look is None                 # unchanged: nothing to send
        scene.colors[0] = (0.0, 1.0, 0.0)                    # in place, small scene: compared
        frame = r.capture(scene)
        assert frame.look is not None
        r.draw(frame, cam)
        centre = r.read_rgb()[60, 50]
        assert centre[1] > 2 * centre[0], centre             # the left ball turned green

        monkeypatch.setattr(look, "COMPARE_MAX", 1)          # as for a million particles
        r.draw(r.capture(scene), cam)
        scene.colors[0] = (1.0, 0.0, 0.0)
        assert r.capture(scene).look is None                 # in place, unannounced: unseen
        scene.look_changed()
        assert r.capture(scene).look is not None
        scene.colors = scene.colors.copy()                   # a new array is seen too
        assert r.capture(scene).look is not None
        world.add_particle((0.0, 3.0, 0.0), radius=0.2)      # a new count comes with a look
        assert len(r.capture(scene).look.rows) == 3
    finally:
        r.release()


def test_a_captured_frame_that_is_never_drawn_does_not_lose_the_look(ctx):
    """The look counts as sent only once drawn: a change captured in a dropped frame is sent
    again with the next frame."""
    from pointmass.render import Renderer

    scene = _crowd(100)
    r = Renderer(ctx, (64, 48), path="hardware")
    try:
        assert r.capture(scene).look is not None             # captured, never drawn
        assert r.capture(scene).look is not None
    finally:
        r.release()


def test_path_is_chosen_by_the_renderer_name_or_forced(ctx, monkeypatch):
    from pointmass.render import Renderer
    from pointmass.render.path import ENV, choose_path, is_software

    assert is_software("llvmpipe (LLVM 15.0.6, 256 bits)")
    assert is_software("softpipe") and is_software("Mesa swrast")
    assert not is_software("NVIDIA H100 80GB HBM3/PCIe/SSE2")
    assert not is_software("AMD Radeon RX 7900 XTX (radeonsi, navi31)")
    monkeypatch.delenv(ENV, raising=False)
    assert choose_path(ctx) == "software"                    # this machine: llvmpipe
    monkeypatch.setenv(ENV, "hardware")
    assert choose_path(ctx) == "hardware"
    assert choose_path(ctx, "auto") == "software"            # the argument wins
    monkeypatch.setenv(ENV, "gpu")
    with pytest.raises(ValueError, match=ENV):
        Renderer(ctx, (8, 8))
    with pytest.raises(ValueError, match="path"):
        choose_path(ctx, "fast")


def test_pixel_buffer_reads_come_back_in_order(ctx):
    """read_rgb_later returns each frame one call late, the last through read_pending, each
    equal to what read_rgb gave at once."""
    from pointmass.render import OrbitCamera, Renderer

    scene = _crowd(50)
    r = Renderer(ctx, (96, 64), path="hardware")
    cam = OrbitCamera.from_hint(scene.camera)
    try:
        direct, late = [], []
        for k in range(4):
            cam.yaw += 40.0 * k
            r.render(scene, cam)
            direct.append(r.read_rgb())
            got = r.read_rgb_later()
            if k < 2:
                assert got is None                           # two frames in flight
            else:
                late.append(got)
        late += r.read_pending()
        assert r.read_pending() == []
        assert len(late) == 4
        for a, b in zip(direct, late):
            np.testing.assert_array_equal(a, b)
        assert not np.array_equal(direct[0], direct[1])
    finally:
        r.release()


def test_pair_links_are_drawn_from_the_gpu_and_anchored_ones_stay_rows(ctx):
    """Springs and rods between particles go to the links buffer (re-sent when a link is
    added), an anchored spring stays a CPU line row; the software path keeps all as rows."""
    from pointmass.render import OrbitCamera, Renderer

    world = pm.World()
    world.add_particles([(0.0, 1.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 1.0)], radii=0.1)
    world.add(pm.Spring(0, 1, 10.0, 0.8))
    world.add(pm.Rod(0, 2, 1.0))
    world.add(pm.AnchoredSpring(1, (1.0, 2.0, 0.0), 10.0, 1.0))
    scene = pm.Scene(world)
    cam = OrbitCamera.from_hint(scene.camera)
    r = Renderer(ctx, (64, 48), path="hardware")
    soft = Renderer(ctx, (64, 48), path="software")
    try:
        frame = r.capture(scene)
        assert len(frame.gpu_links) == 2 and len(frame.lines) == 1
        r.draw(frame, cam)
        assert r._links.count == 2
        world.add(pm.Spring(1, 2, 10.0, 1.0))
        r.draw(r.capture(scene), cam)
        assert r._links.count == 3
        assert len(soft.capture(scene).lines) == 4 and soft.capture(scene).gpu_links == ()
    finally:
        r.release()
        soft.release()


def test_body_rows_from_the_arrays_equal_the_software_rows():
    """bodies.body_arrays (numpy over the bodies' arrays) gives exactly the box instances,
    edges, shadow casters, balls and spin markers the software path builds body by body."""
    from pointmass.render import bodies as bv
    from pointmass.render import geometry
    from pointmass.render.shadows import ShadowMap
    from pointmass.rigid.shapes import Box, Sphere

    rng = np.random.default_rng(5)
    world = pm.World()
    for k in range(6):
        q = rng.normal(size=4)
        shape = Sphere(0.2 + 0.05 * k) if k % 2 else Box((0.2, 0.3 + 0.1 * k, 0.4))
        world.add_body(shape, (k, 1.0 + k, -k), orientation=tuple(q / np.linalg.norm(q)),
                       mass=np.inf if k == 4 else 1.0)
    bodies = world.bodies
    fast = bv.body_arrays(bodies, 8)
    visuals = bv.box_visuals(bodies)
    np.testing.assert_array_equal(fast["boxes"], geometry.box_instances(visuals))
    start, end = geometry.box_edge_lines(visuals)
    np.testing.assert_array_equal(fast["edge_start"], start)
    np.testing.assert_array_equal(fast["edge_end"], end)

    class Boxes:
        boxes = visuals

    np.testing.assert_array_equal(fast["casters"], ShadowMap.box_rows(Boxes))
    balls, markers = bv.sphere_rows(bodies, 8)
    assert len(balls) == 3
    np.testing.assert_array_equal(fast["balls"], balls)
    np.testing.assert_array_equal(fast["markers"], markers)
