"""Pinhole camera maths for the camera and depth sensors: intrinsics, the renderer's matrices,
depth-buffer linearisation and the depth point cloud.

Pure numpy: no rospy, no pybullet. Frames:
- the sensor frame (Gazebo's camera convention): x forward (the optical axis), y left, z up;
- the optical frame (ROS REP 103 `_optical`): z forward, x right, y down. Images, camera_info and
  point clouds are in it.
The image is rendered, and the depth cloud computed, as Gazebo renders: square pixels with
f = width / (2 tan(hfov / 2)) and the optical axis through the centre of the image, (width - 1) / 2
and (height - 1) / 2 in pixel coordinates (pixel centres at integers, as OpenCV and image_geometry
count them). camera_info reports what gazebo_ros_camera_utils writes (`reported_intrinsics`): the
plugin's <focalLength>, <Cx>, <Cy> where set, else that f and cx = (width + 1) / 2, cy = (height + 1)
/ 2, one pixel right of and below the centre of the image Gazebo renders, as it is there.
"""
import math

import numpy as np

# Sensor frame axes written in the optical frame: optical x = -sensor y, optical y = -sensor z,
# optical z = sensor x. OPTICAL_FROM_SENSOR @ v_sensor = v_optical.
OPTICAL_FROM_SENSOR = np.array([[0.0, -1.0, 0.0],
                                [0.0, 0.0, -1.0],
                                [1.0, 0.0, 0.0]])


class PinholeCamera:
    def __init__(self, width, height, hfov, near, far):
        if width < 1 or height < 1:
            raise ValueError('image size must be at least 1 x 1, got %r x %r' % (width, height))
        if not 0.0 < hfov < math.pi:
            raise ValueError('horizontal field of view must be in (0, pi) rad, got %r' % (hfov,))
        if not 0.0 < near < far:
            raise ValueError('clip planes need 0 < near < far, got %r, %r' % (near, far))
        self.width = int(width)
        self.height = int(height)
        self.hfov = float(hfov)
        self.near = float(near)
        self.far = float(far)
        self.f = self.width / (2.0 * math.tan(self.hfov / 2.0))
        self.cx = (self.width - 1) / 2.0
        self.cy = (self.height - 1) / 2.0
        self.vfov = 2.0 * math.atan(self.height / (2.0 * self.f))

    # -- camera_info ------------------------------------------------------------------------
    def reported_intrinsics(self, focal_length=0.0, cx=0.0, cy=0.0):
        """(f, cx, cy) as gazebo_ros_camera_utils fills camera_info: each plugin value that is set (not 0),
        else f from the field of view and (width + 1) / 2, (height + 1) / 2."""
        return (focal_length or self.f, cx or (self.width + 1) / 2.0, cy or (self.height + 1) / 2.0)

    def K(self, intrinsics=None):
        f, cx, cy = intrinsics or self.reported_intrinsics()
        return [f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0]

    def P(self, baseline=0.0, intrinsics=None):
        """Projection matrix; P[3] = -f * baseline as gazebo_ros_camera_utils (hackBaseline)."""
        f, cx, cy = intrinsics or self.reported_intrinsics()
        return [f, 0.0, cx, -f * baseline, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0]

    def project(self, point_optical):
        """Pixel (u, v) of a point in the optical frame (z > 0)."""
        x, y, z = point_optical
        return self.f * x / z + self.cx, self.f * y / z + self.cy

    # -- renderer (OpenGL conventions, column-major 4 x 4 as lists of 16) ----------------------
    def projection_matrix(self):
        """OpenGL perspective projection with this vertical field of view and aspect."""
        t = 1.0 / math.tan(self.vfov / 2.0)
        aspect = self.width / float(self.height)
        n, f = self.near, self.far
        return [t / aspect, 0.0, 0.0, 0.0,
                0.0, t, 0.0, 0.0,
                0.0, 0.0, (f + n) / (n - f), -1.0,
                0.0, 0.0, 2.0 * f * n / (n - f), 0.0]

    @staticmethod
    def view_matrix(position, rotation):
        """OpenGL view matrix of a camera at `position` whose sensor frame has world rotation
        `rotation` (3 x 3): it looks along the sensor x axis with the sensor z axis up."""
        r = np.asarray(rotation, dtype=np.float64)
        forward, left, up = r[:, 0], r[:, 1], r[:, 2]
        # OpenGL eye axes: x right (= -left), y up, z backwards (= -forward).
        rot = np.stack([-left, up, -forward])  # rows: eye axes in world coordinates
        trans = -rot @ np.asarray(position, dtype=np.float64)
        m = np.eye(4)
        m[:3, :3] = rot
        m[:3, 3] = trans
        return m.T.reshape(-1).tolist()  # column-major

    def linear_depth(self, depth_buffer):
        """Distance along the optical axis (metres) from OpenGL depth-buffer values in [0, 1]."""
        d = np.asarray(depth_buffer, dtype=np.float64)
        n, f = self.near, self.far
        return f * n / (f - (f - n) * d)

    # -- depth products -----------------------------------------------------------------------
    def rays_optical(self):
        """(height, width, 2): x/z and y/z of every pixel's ray in the optical frame."""
        u = (np.arange(self.width) - self.cx) / self.f
        v = (np.arange(self.height) - self.cy) / self.f
        return np.stack(np.meshgrid(u, v, indexing='xy'), axis=-1)

    def rays_optical_3d(self):
        """(height, width, 3) float32: every pixel's ray in the optical frame, scaled to z = 1."""
        rays = self.rays_optical()
        return np.concatenate([rays, np.ones(rays.shape[:2] + (1,))], axis=-1).astype(np.float32)

    def plane_depth(self, rays3, position, rotation, plane_point, plane_normal):
        """(height, width) depth along the optical axis at which each pixel's ray meets a plane
        (+inf where it does not, or behind the camera). `rays3`: rays_optical_3d(); `position`,
        `rotation`: the sensor frame's world pose; the plane by a point and its normal. Ray by ray: the reference
        that plane_inverse_depth, which cameras use, is tested against."""
        world_from_optical = np.asarray(rotation, dtype=np.float64) @ OPTICAL_FROM_SENSOR.T
        m = (world_from_optical.T @ np.asarray(plane_normal, dtype=np.float64)).astype(np.float32)
        height = float(np.dot(plane_normal, np.asarray(plane_point, dtype=np.float64) - np.asarray(position)))
        denom = rays3 @ m
        with np.errstate(divide='ignore', invalid='ignore'):
            t = np.float32(height) / denom
        return np.where(t > 0, t, np.float32(np.inf))

    def plane_inverse_depth(self, position, rotation, plane_point, plane_normal):
        """(height, width) float32: 1 / the depth along the optical axis at which each pixel's ray meets a
        plane, <= 0 where it does not meet it in front of the camera (plane_depth, as its reciprocal). 1 / depth
        is affine in the pixel's column and row, so this is one outer sum: no per-pixel rays."""
        world_from_optical = np.asarray(rotation, dtype=np.float64) @ OPTICAL_FROM_SENSOR.T
        m = world_from_optical.T @ np.asarray(plane_normal, dtype=np.float64)  # the normal, optical frame
        height = float(np.dot(plane_normal, np.asarray(plane_point, dtype=np.float64) - np.asarray(position)))
        if height == 0.0 or not math.isfinite(height):  # the camera on the plane sees it edge-on: nowhere
            return np.zeros((self.height, self.width), dtype=np.float32)
        # a pixel's ray (x/z, y/z, 1) reaches the plane at depth t with t (ray . m) = height
        columns = ((np.arange(self.width) - self.cx) / self.f * (m[0] / height)).astype(np.float32)
        rows = ((np.arange(self.height) - self.cy) / self.f * (m[1] / height) + m[2] / height).astype(np.float32)
        return rows[:, None] + columns[None, :]

    def depth_buffer_of_inverse(self, inverse_depth, out=None):
        """The OpenGL depth-buffer value (projection_matrix) of points at 1 / `inverse_depth` along the optical
        axis: linear_depth's inverse, affine in 1 / depth; < 0 nearer than `near`, > 1 beyond `far` or behind."""
        n, f = self.near, self.far
        scale = f * n / (f - n)
        return np.multiply(np.float32(1.0 / n) - inverse_depth, np.float32(scale), out=out)

    def points(self, depth, rays=None):
        """(height, width, 3) float32 points in the optical frame for a depth image (metres
        along the optical axis); NaN depth gives NaN points."""
        rays = self.rays_optical() if rays is None else rays
        depth = np.asarray(depth, dtype=np.float32)
        out = np.empty((self.height, self.width, 3), dtype=np.float32)
        out[..., 0] = rays[..., 0] * depth
        out[..., 1] = rays[..., 1] * depth
        out[..., 2] = depth
        return out


def mask_depth(depth, near, far):
    """gazebo_ros_openni_kinect's depth image: NaN where the depth is not strictly inside (near, far)."""
    depth = np.asarray(depth, dtype=np.float32)
    return np.where((depth > near) & (depth < far), depth, np.float32(np.nan)).astype(np.float32)
