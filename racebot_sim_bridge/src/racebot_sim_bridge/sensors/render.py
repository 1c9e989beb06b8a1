"""Camera frames from a PyBullet client: which renderer, and one camera's frame from a pose.

No rospy here. Two renderers:
- 'egl': PyBullet's EGL plugin, hardware OpenGL without a window (a GPU, or Mesa's llvmpipe on
  the CPU: ~20 ms for an 800 x 800 frame here with its shadow-map pass off (egl_shadow_map), a
  quarter of the TinyRenderer's time; a GPU is expected to take a few ms, not measured here). The
  plugin must be loaded into a DIRECT client before its bodies are created. It draws into a fixed
  1024 x 768 surface, so render() renders a bigger frame in tiles (EGL_SURFACE).
- 'tiny': PyBullet's TinyRenderer, on the CPU, always there.
`load_renderer(client, 'auto')` loads EGL when it loads and draws a correct test image
(`renderer_draws_correctly`), the TinyRenderer otherwise.
"""
import os
import pkgutil
import tempfile
import threading

import numpy as np
import pybullet as pb

from racebot_sim_bridge.sensors import egl_shadow_map
from racebot_sim_bridge.sensors.camera import PinholeCamera
from racebot_sim_bridge.sensors.noise import ImageNoise

TINY = 'tiny'
EGL = 'egl'
RENDERER_CHOICES = ('auto', EGL, TINY)
RENDERER_FLAGS = {TINY: pb.ER_TINY_RENDERER, EGL: pb.ER_BULLET_HARDWARE_OPENGL}
RENDERER_NAMES = {TINY: 'TinyRenderer (CPU)', EGL: 'EGL (OpenGL)'}


class RendererError(RuntimeError):
    """A renderer that cannot be used; the message says why."""


# The EGL plugin draws into a fixed 1024 x 768 surface and copies at most that much of a frame,
# repeating rows or columns to fill a bigger one (an 800 x 800 camera got 768 rows, every 24th twice).
EGL_SURFACE = (1024, 768)


def render(world, width, height, view_matrix, projection_matrix, renderer=TINY):
    """(rgb uint8 height x width x 3, depth buffer float32 height x width). No segmentation mask.
    An EGL frame bigger than the plugin's surface is rendered in tiles that fit it."""
    rgba, depth = render_rgba(world, width, height, view_matrix, projection_matrix, renderer)
    return rgba[:, :, :3], depth


def render_rgba(world, width, height, view_matrix, projection_matrix, renderer=TINY):
    """render() with the renderer's own 4 bytes a pixel (rgba, an array of its own): a pixel is one uint32,
    which numpy overwrites under a mask ~40 times faster than 3 separate bytes (ground planes)."""
    if renderer == EGL and (width > EGL_SURFACE[0] or height > EGL_SURFACE[1]):
        return render_tiled(world, width, height, view_matrix, projection_matrix, renderer, *EGL_SURFACE)
    return _render(world, width, height, view_matrix, projection_matrix, renderer)


def _render(world, width, height, view_matrix, projection_matrix, renderer):
    w, h, rgba, depth, _ = world.client.getCameraImage(width, height, view_matrix, projection_matrix, shadow=0,
                                                       renderer=RENDERER_FLAGS[renderer],
                                                       flags=pb.ER_NO_SEGMENTATION_MASK)
    rgba = np.asarray(rgba, dtype=np.uint8).reshape(h, w, 4)
    return rgba, np.asarray(depth, dtype=np.float32).reshape(h, w)


# rgba -> packed rgb: the first 3 bytes of each 4 as one 3-byte item (one memcpy per pixel, ~3 times faster
# than numpy's copy of the strided [:, :, :3] view: 1.3 against 3.5 ms for 800 x 800)
_RGB_OF_RGBA = np.dtype({'names': ['rgb'], 'formats': ['V3'], 'offsets': [0], 'itemsize': 4})


def packed_rgb(rgba):
    """height x width x 3 uint8, contiguous, of a contiguous height x width x 4 rgba."""
    rgba = np.ascontiguousarray(rgba, dtype=np.uint8)
    height, width = rgba.shape[:2]
    return np.ascontiguousarray(rgba.view(_RGB_OF_RGBA)['rgb']).view(np.uint8).reshape(height, width, 3)


def tile_projection(projection_matrix, width, height, x0, x1, y0, y1):
    """The projection (column-major list of 16) of pixels [x0, x1) x [y0, y1) of a width x height
    image (rows from the top): the full frustum's clip space scaled and shifted so that this part
    fills [-1, 1]. Depth is untouched, so the depth buffer means the same in every tile."""
    # the tile's edges in normalised device coordinates (y up, so row 0 is at +1)
    left, right = 2.0 * x0 / width - 1.0, 2.0 * x1 / width - 1.0
    top, bottom = 1.0 - 2.0 * y0 / height, 1.0 - 2.0 * y1 / height
    m = np.eye(4)
    m[0, 0], m[0, 3] = 2.0 / (right - left), -(right + left) / (right - left)
    m[1, 1], m[1, 3] = 2.0 / (top - bottom), -(top + bottom) / (top - bottom)
    p = np.asarray(projection_matrix, dtype=np.float64).reshape(4, 4).T  # row-major
    return (m @ p).T.reshape(-1).tolist()


def render_tiled(world, width, height, view_matrix, projection_matrix, renderer, tile_width, tile_height):
    """render_rgba() of a width x height frame in tiles of at most tile_width x tile_height pixels."""
    rgba = np.empty((height, width, 4), dtype=np.uint8)
    depth = np.empty((height, width), dtype=np.float32)
    columns = -(-width // tile_width)
    rows = -(-height // tile_height)
    xs = [width * i // columns for i in range(columns + 1)]  # even tiles: no thin strip at the edge
    ys = [height * j // rows for j in range(rows + 1)]
    for y0, y1 in zip(ys, ys[1:]):
        for x0, x1 in zip(xs, xs[1:]):
            part = tile_projection(projection_matrix, width, height, x0, x1, y0, y1)
            rgba[y0:y1, x0:x1], depth[y0:y1, x0:x1] = _render(world, x1 - x0, y1 - y0, view_matrix, part, renderer)
    return rgba, depth


def load_egl(client):
    """Loads PyBullet's EGL renderer plugin into `client` (a PybulletClient, DIRECT, no bodies yet) and
    switches its shadow-map pass off (egl_shadow_map). Returns what the plugin says of the OpenGL driver (e.g.
    'Mesa/X.org, llvmpipe (LLVM 15.0.6, 256 bits)') and of the shadow map when it stays on.
    Raises RendererError when it does not load.

    The plugin prints the driver on fd 1, so the driver is read by pointing fd 1 at a file while it
    loads. fd 1 belongs to the whole process: another thread's output would vanish into that file
    meanwhile, and no lock can make the plugin's C code wait. So it is done only in a process with
    one thread: the render worker process (render_process), which loads the renderer before anything
    else. With other threads running the plugin prints where it likes and the driver goes unnamed."""
    loader = pkgutil.get_loader('eglRenderer')
    if loader is None:
        raise RendererError('PyBullet has no eglRenderer plugin')
    if threading.active_count() > 1:
        plugin = client.loadPlugin(loader.get_filename(), '_eglRendererPlugin')
        said = 'Renderer = driver not read (other threads share stdout)'
    else:
        said, plugin = stdout_of(lambda: client.loadPlugin(loader.get_filename(), '_eglRendererPlugin'))
    if plugin < 0:
        raise RendererError('the EGL plugin did not load (no EGL driver: install libegl1 libegl-mesa0 '
                            'libgl1-mesa-dri for Mesa)')
    lines = dict(line.split(' = ', 1) for line in said.splitlines() if ' = ' in line)
    driver = ', '.join(v.strip() for k, v in lines.items() if k.strip() in ('Vendor', 'Renderer')) or 'unknown driver'
    try:
        egl_shadow_map.switch_off(loader.get_filename())
    except egl_shadow_map.ShadowMapError as err:
        driver += '; its shadow-map pass stays on (about 2-4 times slower): %s' % err
    return driver


def stdout_of(call):
    """(what `call()` wrote on fd 1, its result). Only in a process with no other thread (see load_egl)."""
    with tempfile.TemporaryFile(mode='w+b') as out:
        saved = os.dup(1)
        try:
            os.dup2(out.fileno(), 1)
            result = call()
        finally:
            os.dup2(saved, 1)
            os.close(saved)
        out.seek(0)
        return out.read().decode('utf-8', 'replace'), result


def renderer_draws_correctly(world, renderer):
    """Renders a red cube 1 m in front of a 16 x 16 camera and checks colour and depth: a driver
    can load and still draw black or garbage. Adds and removes its own body."""
    half = 0.1
    visual = world.client.createVisualShape(pb.GEOM_BOX, halfExtents=[half] * 3, rgbaColor=[0.9, 0.1, 0.1, 1.0])
    collision = world.client.createCollisionShape(pb.GEOM_BOX, halfExtents=[half] * 3)
    box = world.client.createMultiBody(0.0, collision, visual, basePosition=[1.0, 0.0, 50.0])
    try:
        camera = PinholeCamera(16, 16, 0.6, 0.05, 10.0)
        view = camera.view_matrix([0.0, 0.0, 50.0], np.eye(3))
        rgb, buffer = render(world, 16, 16, view, camera.projection_matrix(), renderer)
        depth = camera.linear_depth(buffer)
    finally:
        world.client.removeBody(box)
    centre = rgb[7:9, 7:9].astype(int).mean(axis=(0, 1))
    corner = rgb[0, 0].astype(int)
    red = centre[0] > 120 and centre[0] > centre[1] + 60 and centre[0] > centre[2] + 60
    depth_ok = abs(float(np.median(depth[7:9, 7:9])) - (1.0 - half)) < 0.02
    background = not (corner[0] > corner[1] + 60) and abs(float(depth[0, 0]) - 10.0) < 0.5
    return bool(red and depth_ok and background)


def load_renderer(world, choice='auto'):
    """(renderer, description) for `world` (a physics.PhysicsWorld with no bodies yet): EGL when
    `choice` allows it and it loads and draws correctly, else the TinyRenderer. With choice 'egl'
    a failing EGL raises RendererError; with 'auto' the reason is in the description."""
    if choice not in RENDERER_CHOICES:
        raise RendererError('renderer must be one of %s, got %r' % (', '.join(RENDERER_CHOICES), choice))
    if choice == TINY:
        return TINY, RENDERER_NAMES[TINY]
    try:
        driver = load_egl(world.client)
        if not renderer_draws_correctly(world, EGL):
            raise RendererError('the EGL renderer (%s) loaded but drew a wrong test image' % driver)
    except (RendererError, pb.error) as err:
        if choice == EGL:
            raise RendererError(str(err))
        return TINY, '%s; EGL unavailable: %s' % (RENDERER_NAMES[TINY], err)
    return EGL, '%s: %s' % (RENDERER_NAMES[EGL], driver)


class CameraFrames:
    """Makes one camera's frames: render, the analytically drawn ground planes (SceneColours),
    depth along the optical axis in metres (`far` where nothing is) and the image noise."""

    def __init__(self, camera, noise=None):
        """`camera`: camera.PinholeCamera; `noise`: noise.GaussianNoise or None."""
        self.camera = camera
        self.projection = camera.projection_matrix()
        self.noise = noise
        self.image_noise = None  # its sample pool (MBs) is made on the first frame

    def make(self, world, renderer, planes, position, rotation, want_depth=True):
        """(rgb, depth or None) seen from the sensor frame at `position` with world `rotation`
        (3 x 3). Depth is worked out only when `want_depth`."""
        rgba, buffer = self.render(world, renderer, position, rotation)
        return self.finish(rgba, buffer, planes, position, rotation, want_depth)

    def render(self, world, renderer, position, rotation):
        """The renderer's part of a frame: (rgba, depth buffer), read back."""
        camera = self.camera
        return render_rgba(world, camera.width, camera.height, camera.view_matrix(position, rotation),
                           self.projection, renderer)

    def finish(self, rgba, buffer, planes, position, rotation, want_depth):
        """The rest of make(): ground planes, packed rgb, depth in metres, noise."""
        drawn = self.draw_planes(rgba, buffer, planes, position, rotation) if planes else []
        rgb = packed_rgb(rgba)
        depth = None
        if want_depth:
            depth = self.camera.linear_depth(buffer).astype(np.float32)
            for inverse, nearer in drawn:  # the plane's exact depth, not its depth-buffer value
                np.divide(np.float32(1.0), inverse, out=depth, where=nearer)
        if self.noise is not None:
            if self.image_noise is None:
                self.image_noise = ImageNoise.from_noise(self.noise, rgb.size)
            rgb = self.image_noise.apply(rgb)
        return rgb, depth

    def draw_planes(self, rgba, buffer, planes, position, rotation):
        """Draws each ground plane (scene.GroundPlane) into `rgba` and `buffer` where it is nearer than what is
        there, comparing depth-buffer values as OpenGL's depth test does. Returns [(1 / depth, drawn mask)] per
        plane in drawing order (a later plane drawn over an earlier one)."""
        camera = self.camera
        pixels = rgba.view(np.uint32).reshape(rgba.shape[:2])  # one uint32 a pixel
        plane_buffer = np.empty(buffer.shape, dtype=np.float32)
        drawn = []
        for plane in planes:
            inverse = camera.plane_inverse_depth(position, rotation, plane.point, plane.normal)
            camera.depth_buffer_of_inverse(inverse, out=plane_buffer)
            # at or beyond `near` (buffer >= 0) and nearer than what is drawn (a buffer <= 1: not beyond `far`,
            # not behind the camera)
            nearer = (plane_buffer >= 0.0) & (plane_buffer < buffer)
            colour = np.frombuffer(bytes(plane.rgb[:3]) + b'\xff', dtype=np.uint32)[0]
            np.copyto(pixels, colour, where=nearer)
            np.copyto(buffer, plane_buffer, where=nearer)
            drawn.append((inverse, nearer))
        return drawn
