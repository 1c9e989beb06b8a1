"""EGL frames as the cameras need them (sensors/render.py, sensors/egl_shadow_map.py): the
plugin's shadow-map pass is switched off, so EGL lights a scene as the TinyRenderer does, and a
frame bigger than the plugin's 1024 x 768 surface is rendered in tiles instead of repeating rows.
Real PyBullet, real EGL plugin (Mesa's llvmpipe here); no master."""
import pkgutil

import numpy as np
import pybullet as pb
import pytest

from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.sensors import egl_shadow_map
from racebot_sim_bridge.sensors import render as render_module
from racebot_sim_bridge.sensors.camera import PinholeCamera
from racebot_sim_bridge.sensors.render import EGL, TINY, load_renderer, render, tile_projection


def plugin_path():
    return pkgutil.get_loader('eglRenderer').get_filename()


def scene(renderer):
    """A world with a grey floor box and a green-yellow wall 3 m ahead, lit by PyBullet's light."""
    world = PhysicsWorld()
    kind, description = load_renderer(world, renderer)
    if renderer == EGL and kind != EGL:
        world.close()
        pytest.skip('no EGL driver on this machine: %s' % description)
    c = world.client
    floor = c.createVisualShape(pb.GEOM_BOX, halfExtents=[10, 10, 0.01], rgbaColor=[0.5, 0.5, 0.5, 1])
    c.createMultiBody(0, -1, floor, basePosition=[0, 0, -0.01])
    wall = c.createVisualShape(pb.GEOM_BOX, halfExtents=[0.05, 1.0, 0.5], rgbaColor=[0.5, 0.8, 0.3, 1])
    c.createMultiBody(0, -1, wall, basePosition=[3, 0, 0.5])
    return world, description


def frame(world, renderer, width, height):
    camera = PinholeCamera(width, height, 1.047, 0.05, 100.0)
    view = camera.view_matrix([0.0, 0.0, 0.5], np.eye(3))  # 0.5 m up, looking along +x
    rgb, buffer = render(world, width, height, view, camera.projection_matrix(), renderer)
    return rgb, camera.linear_depth(buffer)


def tiny_frame(width, height):
    """frame() of the same scene from the TinyRenderer, the reference EGL is compared with."""
    world, _ = scene(TINY)
    try:
        return frame(world, TINY, width, height)
    finally:
        world.close()


@pytest.fixture
def egl_world():
    world, description = scene(EGL)
    yield world, description
    world.close()


def test_egl_loads_with_its_shadow_map_pass_off(egl_world):
    _, description = egl_world
    assert 'shadow-map pass stays on' not in description
    assert not egl_shadow_map.is_on(plugin_path())


def test_the_switch_is_the_shadow_pass(egl_world):
    """The byte written is the plugin's shadow switch: with it back on, the shadow shader darkens
    the floor; off, a sunlit face has the TinyRenderer's colour."""
    world, _ = egl_world
    tiny, _ = tiny_frame(160, 120)
    off, _ = frame(world, EGL, 160, 120)
    flag = egl_shadow_map.flag_of(plugin_path())
    flag.value = True
    try:
        on, _ = frame(world, EGL, 160, 120)
    finally:
        flag.value = False
    floor, wall = (slice(100, 120), slice(None)), (slice(55, 65), slice(70, 90))

    def median(img, part):
        return np.median(img[part].reshape(-1, 3), axis=0)
    assert (median(off, floor) - median(on, floor)).min() >= 5, (median(off, floor), median(on, floor))
    assert np.abs(median(off, wall) - median(tiny, wall)).max() <= 3, (median(off, wall), median(tiny, wall))


def test_egl_still_renders_when_the_switch_cannot_be_found(monkeypatch):
    """A PyBullet build without the symbol: EGL is used all the same (slower), and the renderer's
    description, which the simulator logs once, says why."""
    def cannot(path):
        raise egl_shadow_map.ShadowMapError('%s has no symbol useShadowMap (a stripped build)' % path)
    monkeypatch.setattr(egl_shadow_map, 'switch_off', cannot)
    world, description = scene(EGL)
    try:
        assert 'shadow-map pass stays on' in description and 'no symbol useShadowMap' in description
        _, depth = frame(world, EGL, 64, 48)
        assert abs(float(np.median(depth[20:28, 28:36])) - 2.95) < 0.02  # the wall, 3 m ahead
    finally:
        world.close()


def test_a_library_without_the_flag_is_left_alone():
    with pytest.raises(egl_shadow_map.ShadowMapError, match='no symbol'):
        egl_shadow_map.switch_off(pb.__file__)  # pybullet itself: no useShadowMap, no PyInit_eglRenderer
    with pytest.raises(egl_shadow_map.ShadowMapError, match='cannot read'):
        egl_shadow_map.switch_off('/nonexistent/eglRenderer.so')


def clip_to_pixel(projection, point, width, height):
    """Pixel (column, row from the top) of a camera-space point under a column-major projection."""
    clip = np.asarray(projection).reshape(4, 4).T @ np.append(point, 1.0)
    ndc = clip[:3] / clip[3]
    return (ndc[0] + 1.0) / 2.0 * width, (1.0 - ndc[1]) / 2.0 * height, ndc[2]


@pytest.mark.parametrize('tile', [(0, 400, 0, 400), (400, 800, 0, 400), (0, 800, 400, 800), (123, 456, 78, 654)])
def test_a_tile_projection_sees_its_part_of_the_image(tile):
    x0, x1, y0, y1 = tile
    camera = PinholeCamera(800, 800, 1.047, 0.05, 100.0)
    full = camera.projection_matrix()
    part = tile_projection(full, 800, 800, x0, x1, y0, y1)
    rng = np.random.default_rng(7)
    for _ in range(50):
        point = np.array([rng.uniform(-2, 2), rng.uniform(-2, 2), -rng.uniform(0.5, 20)])  # OpenGL eye space
        u, v, depth = clip_to_pixel(full, point, 800, 800)
        tu, tv, tile_depth = clip_to_pixel(part, point, x1 - x0, y1 - y0)
        assert tu == pytest.approx(u - x0, abs=1e-6) and tv == pytest.approx(v - y0, abs=1e-6)
        assert tile_depth == pytest.approx(depth, abs=1e-12)


def test_a_frame_taller_than_the_plugin_surface_has_all_its_rows(egl_world, monkeypatch):
    """800 rows (the racebot's camera) from a 768-row surface: without tiles every 24th row came twice."""
    world, _ = egl_world
    _, depth = frame(world, EGL, 800, 800)
    near_floor = depth[650:]  # 0.5 m below the camera: each row is a little nearer than the one above
    assert (np.diff(near_floor, axis=0) < 0).all(axis=1).all(), 'repeated rows in the near floor'

    _, tiny_depth = tiny_frame(800, 800)
    wall = np.abs(tiny_depth - 2.95) < 0.02  # its face; rows ~283-517, across the tiles' seam at row 400
    wall[500:] = False  # where the floor meets it
    assert wall[399].any() and wall[400].any()
    assert np.percentile(np.abs(depth - tiny_depth)[wall], 99) < 0.01

    # The untiled frame (what the plugin gives on its own) repeats rows: the check above can fail.
    monkeypatch.setattr(render_module, 'EGL_SURFACE', (4096, 4096))
    _, untiled = frame(world, EGL, 800, 800)
    assert not (np.diff(untiled[650:], axis=0) < 0).all(axis=1).all()
