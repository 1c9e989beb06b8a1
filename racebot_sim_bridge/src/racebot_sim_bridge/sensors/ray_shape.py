"""Gazebo's MultiRayShape: the raw rays of a ray sensor and the ranges its LaserShape()->GetRange gives.

Pure numpy: no rospy, no pybullet. What gazebo_ros_block_laser and hector's sonar read (ray.py is what the
RaySensor reports, for the LaserScan and velodyne plugins):
- one ray per <samples> (the <resolution>s are not rays), `samples` x `vertical samples`, horizontal index
  fastest, the lowest layer first (index = i + j * samples), as MultiRayShape::Init builds them;
- yaw i * (max - min) / (samples - 1) + min, but 0 for a single sample (not min_angle); pitch likewise, 0 for
  one layer; positive pitch up;
- each ray from range min to range max; GetRange(i) = range min + its length, a miss the full length
  (range max: never inf); a ray starting inside an object reads range min.
"""
from __future__ import annotations

import numpy as np


def ray_angles(samples: int, min_angle: float, max_angle: float) -> np.ndarray:
    """MultiRayShape::Init's angles of one axis: 0 for a single sample."""
    if samples <= 1:
        return np.zeros(1)
    return np.arange(samples) * (max_angle - min_angle) / (samples - 1) + min_angle


class RayShape:
    """The raw rays of a urdf_model.RaySpec: directions in the sensor frame (x forward, y left, z up)."""

    def __init__(self, ray):
        if not (ray.range_max > ray.range_min >= 0.0):
            raise ValueError('the ray sensor needs 0 <= range min < range max, got %g .. %g'
                             % (ray.range_min, ray.range_max))
        self.samples = max(1, int(ray.samples))
        self.vertical_samples = max(1, int(ray.vertical_samples))
        self.range_min = float(ray.range_min)
        self.range_max = float(ray.range_max)
        yaws = ray_angles(self.samples, ray.min_angle, ray.max_angle)
        pitches = ray_angles(self.vertical_samples, ray.vertical_min_angle, ray.vertical_max_angle)
        elev, azim = np.meshgrid(pitches, yaws, indexing='ij')
        self.directions = np.stack([np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim), np.sin(elev)],
                                   axis=-1).reshape(-1, 3)

    def endpoints(self, origin, rotation):
        """World start and end points of every ray (range min to range max); `rotation`: 3 x 3 world matrix."""
        world_dirs = self.directions @ np.asarray(rotation, dtype=np.float64).T
        origin = np.asarray(origin, dtype=np.float64)
        return origin + self.range_min * world_dirs, origin + self.range_max * world_dirs

    def ranges(self, fractions, hit) -> np.ndarray:
        """GetRange of every ray from the hit fractions along [min, max]: range max for a miss."""
        lengths = np.asarray(fractions, dtype=np.float64) * (self.range_max - self.range_min)
        lengths = np.where(np.asarray(hit, dtype=bool), lengths, self.range_max - self.range_min)
        return self.range_min + lengths
