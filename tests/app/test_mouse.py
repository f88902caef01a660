"""Mouse gestures and the grab spring, without a window (camera math and physics only)."""

import numpy as np
import pytest

from pointmass import World
from pointmass.app.grab import MouseSpring, plane_point
from pointmass.app.mouse import MouseControls
from pointmass.render import OrbitCamera

SIZE = (800, 500)


class Clock:
    def __init__(self):
        self.t = 100.0

    def __call__(self):
        return self.t


@pytest.fixture
def controls(sim):
    camera = OrbitCamera.from_hint(sim.scene.camera)
    pressed = []
    sim.press = lambda key: pressed.append(key) or True
    mc = MouseControls(camera, sim, lambda: SIZE, clock=Clock())
    mc.pressed = pressed
    return mc


def screen_of(controls, index):
    pos = controls.sim.scene.world.particles.position[index]
    return controls.camera.project(pos[None], SIZE)[0]


@pytest.mark.parametrize("mass", [1.0, 10.0])
def test_spring_pulls_any_mass_to_the_target_without_overshoot(mass):
    world = World(gravity=(0, 0, 0))
    world.add_particle((0, 0, 0), mass=mass)
    world.add(MouseSpring(0, (1.0, 0, 0)))
    xs = []
    for _ in range(240):
        world.step(1 / 120)
        xs.append(world.particles.position[0, 0])
    assert xs[-1] == pytest.approx(1.0, abs=1e-3)          # settles in 2 s
    assert max(xs) < 1.0 + 1e-3                             # critically damped
    wt = 12 * 31 / 120                                      # after 31 steps: ω·t
    assert xs[30] == pytest.approx(1 - (1 + wt) * np.exp(-wt), abs=0.01)   # the analytic path


def test_plane_point():
    hit = plane_point((0, 0, 5), (0, 0, -1), (0, 0, 0), (0, 0, 1))
    np.testing.assert_allclose(hit, (0, 0, 0))
    assert plane_point((0, 0, 5), (1, 0, 0), (0, 0, 0), (0, 0, 1)) is None
    assert plane_point((0, 0, 5), (0, 0, 1), (0, 0, 0), (0, 0, 1)) is None


def test_ctrl_drag_grabs_and_release_removes_the_spring(controls):
    x, y = screen_of(controls, 1)
    controls.press(x, y, "left", ctrl=True)
    assert controls.mode == "grab" and controls.grab.index == 1
    world = controls.sim.scene.world
    assert controls.grab.spring in world.forces
    controls.drag(x + 100, y, 100, 0)
    target = controls.grab.spring.target
    assert controls.camera.project(target[None], SIZE)[0] == pytest.approx((x + 100, y), abs=0.5)
    line = controls.extra_lines()[0]
    np.testing.assert_allclose(line[1], target)
    controls.release(x + 100, y, "left")
    assert controls.grab is None and not any(isinstance(f, MouseSpring) for f in world.forces)
    assert controls.pressed == []                       # a grab is not a click


def test_ctrl_press_on_empty_space_does_nothing_and_says_so(controls):
    said = []
    controls.say = said.append
    yaw = controls.camera.yaw
    controls.press(5, 5, "left", ctrl=True)
    controls.drag(50, 5, 45, 0)
    assert controls.grab is None and controls.camera.yaw == yaw
    assert said and "nothing to grab" in said[0]


def _pull(sim, index: int, offset, seconds: float = 1.0) -> float:
    """Grab ``index``, hold the target ``offset`` [m] from where it was, run; returns how far
    the particle moved toward the target [fraction of the offset]."""
    from pointmass.app.grab import grab_particle

    world = sim.world
    start = world.particles.position[index].copy()
    grab = grab_particle(world, index, (0.0, 0.0, -1.0))
    grab.spring.target = start + np.asarray(offset, float)
    sim.advance(seconds)
    moved = world.particles.position[index] - start
    assert np.isfinite(world.particles.position).all()
    return float(moved @ offset / (np.asarray(offset) @ offset))


def test_the_grab_moves_a_stiff_cloth_visibly():
    """A cloth node is held by its springs: the grab is scaled to them, so a node pulled
    half a metre toward the viewer follows it (0.99 of the way; 0.39 with the particle's
    own mass alone)."""
    import pointmass as pm

    sim = pm.Simulation("cloth")
    sim.advance(1.0)                              # let it hang
    node = sim.world.particles.count // 2 + 5
    assert _pull(sim, node, (0.0, 0.0, 0.5)) > 0.5


def test_the_grab_moves_a_truss_tied_by_rods():
    """A platform corner weighs 1 kg but rods tie it to the whole truss: the grab pulls the
    truss's mass, so lifting a corner lifts it (0.96 of the way; 0.07 before)."""
    import pointmass as pm

    sim = pm.Simulation("platform")
    sim.advance(1.0)
    corner = 0
    assert _pull(sim, corner, (0.0, 0.6, 0.0), seconds=1.5) > 0.5


def test_left_drag_orbits_right_drag_pans_wheel_zooms(controls):
    cam = controls.camera
    yaw, target, distance = cam.yaw, cam.target.copy(), cam.distance
    controls.press(400, 250, "left")
    controls.drag(440, 250, 40, 0)
    controls.release(440, 250, "left")
    assert cam.yaw != yaw and controls.pressed == []
    controls.press(400, 250, "right")
    controls.drag(420, 250, 20, 0)
    controls.release(420, 250, "right")
    assert not np.allclose(cam.target, target)
    moved = cam.target.copy()
    controls.press(400, 250, "left", shift=True)
    controls.drag(400, 270, 0, 20)
    assert not np.allclose(cam.target, moved)
    controls.scroll(2)
    assert cam.distance == pytest.approx(distance * 0.81)


def test_click_presses_click_and_double_click_focuses(controls):
    x, y = screen_of(controls, 2)
    controls.press(x, y, "left")
    controls.release(x, y, "left")
    assert controls.pressed == ["CLICK"]
    controls.clock.t += 0.1
    controls.press(x, y, "left")
    controls.release(x, y, "left")
    np.testing.assert_allclose(controls.camera.target,
                               controls.sim.scene.world.particles.position[2])
    assert controls.pressed == ["CLICK"]                # the second click focused instead

