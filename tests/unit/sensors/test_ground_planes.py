"""Ground planes drawn into a rendered frame (render.CameraFrames.finish): the per-pixel reference (depth along
each pixel's ray, compared in metres) against the fast path (1 / depth as an outer sum, compared in depth-buffer
values, one uint32 per pixel). No renderer: the frames are made up."""
import math

import numpy as np
import pytest

from racebot_sim_bridge.sensors.camera import PinholeCamera
from racebot_sim_bridge.sensors.render import CameraFrames, packed_rgb
from racebot_sim_bridge.sensors.scene import GroundPlane


def rotation_rpy(roll, pitch, yaw):
    cr, sr, cp, sp, cy, sy = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw), \
        math.sin(yaw)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


POSES = [((0.0, 0.0, 0.5), (0.0, 0.3, 0.0)), ((1.0, -2.0, 0.2), (0.1, -0.2, 2.0)), ((0.0, 0.0, 3.0), (0.0, 1.2, 0.5)),
         ((0.0, 0.0, 0.5), (0.0, -0.4, 0.0)), ((0.0, 0.0, -0.5), (0.0, 0.3, 0.0))]


@pytest.mark.parametrize('position, rpy', POSES)
def test_inverse_depth_is_the_reciprocal_of_the_plane_depth(position, rpy):
    cam = PinholeCamera(64, 48, 1.2, 0.05, 30.0)
    rot = rotation_rpy(*rpy)
    t = cam.plane_depth(cam.rays_optical_3d(), position, rot, (0, 0, 0), (0, 0, 1))
    inverse = cam.plane_inverse_depth(position, rot, (0, 0, 0), (0, 0, 1))
    seen = np.isfinite(t)
    assert inverse.shape == t.shape and inverse.dtype == np.float32
    np.testing.assert_allclose(1.0 / inverse[seen], t[seen], rtol=1e-4)
    assert (inverse[~seen] <= 1e-6).all()  # not in front of the camera: never drawn


def test_a_camera_on_the_plane_sees_none_of_it():
    cam = PinholeCamera(8, 6, 1.0, 0.05, 30.0)
    assert not cam.plane_inverse_depth((0, 0, 0), np.eye(3), (0, 0, 0), (0, 0, 1)).any()


def test_depth_buffer_of_inverse_undoes_linear_depth():
    cam = PinholeCamera(8, 6, 1.0, 0.05, 8.0)
    z = np.array([0.05, 0.1, 1.0, 4.0, 8.0], dtype=np.float32)
    buffer = cam.depth_buffer_of_inverse((1.0 / z).astype(np.float32))
    np.testing.assert_allclose(buffer[[0, -1]], [0.0, 1.0], atol=1e-6)
    np.testing.assert_allclose(cam.linear_depth(buffer), z, rtol=1e-4)


def made_up_frame(cam, rng):
    """rgba of random colours and a depth buffer: a box 1.5 m away in the middle, nothing elsewhere (far)."""
    rgba = rng.integers(0, 256, (cam.height, cam.width, 4), dtype=np.uint8)
    z = np.full((cam.height, cam.width), cam.far)
    z[cam.height // 3: 2 * cam.height // 3, cam.width // 3: 2 * cam.width // 3] = 1.5
    return rgba, cam.depth_buffer_of_inverse((1.0 / z).astype(np.float32)).astype(np.float32)


def reference(cam, rgba, buffer, planes, position, rotation):
    """The per-pixel way: each ray's depth to the plane against the frame's depth in metres."""
    rgb = rgba[:, :, :3].copy()
    depth = cam.linear_depth(buffer)
    for plane in planes:
        t = cam.plane_depth(cam.rays_optical_3d(), position, rotation, plane.point, plane.normal)
        nearer = (t >= cam.near) & (t < depth)
        rgb[nearer] = plane.rgb
        depth[nearer] = t[nearer]
    return rgb, depth


@pytest.mark.parametrize('position, rpy', POSES)
def test_planes_are_drawn_where_the_reference_draws_them(position, rpy):
    cam = PinholeCamera(80, 60, 1.3, 0.05, 8.0)
    rot = rotation_rpy(*rpy)
    rgba, buffer = made_up_frame(cam, np.random.default_rng(3))
    planes = [GroundPlane(None, (0, 0, 0), (0, 0, 1), (10, 200, 30)),
              GroundPlane(None, (0, 0, 0.1), (0.2, 0, 1), (250, 5, 90))]  # a tilted one over it in places
    want_rgb, want_depth = reference(cam, rgba, buffer, planes, position, rot)
    rgb, depth = CameraFrames(cam).finish(rgba.copy(), buffer.copy(), planes, np.asarray(position), rot, True)
    assert rgb.shape == (60, 80, 3) and rgb.flags.c_contiguous
    differ = (rgb != want_rgb).any(axis=2)
    assert differ.sum() <= 2, 'pixels drawn differently: %d' % differ.sum()  # at most where depths tie
    np.testing.assert_allclose(depth[~differ], want_depth[~differ], rtol=2e-4)
    drawn = (want_rgb == planes[0].rgb).all(axis=2) | (want_rgb == planes[1].rgb).all(axis=2)
    assert 0 < drawn.sum() < drawn.size or not drawn.any()


def test_an_rgb_frame_needs_no_depth():
    cam = PinholeCamera(40, 30, 1.3, 0.05, 8.0)
    rgba, buffer = made_up_frame(cam, np.random.default_rng(4))
    plane = GroundPlane(None, (0, 0, 0), (0, 0, 1), (1, 2, 3))
    rgb, depth = CameraFrames(cam).finish(rgba, buffer, [plane], np.array([0.0, 0.0, 0.5]), rotation_rpy(0, 0.4, 0),
                                          False)
    assert depth is None
    assert (rgb == (1, 2, 3)).all(axis=2)[-1].all()  # the bottom row looks down at the ground


def test_packed_rgb_drops_alpha():
    rgba = np.random.default_rng(5).integers(0, 256, (7, 9, 4), dtype=np.uint8)
    rgb = packed_rgb(rgba)
    assert rgb.shape == (7, 9, 3) and rgb.flags.c_contiguous
    np.testing.assert_array_equal(rgb, rgba[:, :, :3])
