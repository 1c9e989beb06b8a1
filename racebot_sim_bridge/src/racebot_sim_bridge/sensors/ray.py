"""The geometry of a Gazebo ray (laser) sensor and what it makes of its ray hits.

Pure numpy: no rospy, no pybullet. From urdf_model.RaySpec:
- the beams: `samples` x `resolution` ranges per layer (Gazebo's range count), evenly spread from
  min_angle to max_angle, so angle_increment = (max - min) / (count - 1); `vertical` layers
  likewise (a 2D lidar has one, at elevation 0). Gazebo casts `samples` rays and interpolates
  (resolution > 1) or averages them to the range count; here every reported range is a ray of
  its own, which is what the interpolation approximates;
- every beam is cast from range_min to range_max along its direction, as Gazebo's ODE ray
  shapes are (so a surface nearer than range_min is not seen, unless the beam starts inside it);
- the ranges as gazebo/sensors/RaySensor.cc reports them (REP 117): a beam that hits nothing, or
  hits at range_max or beyond, reads +inf; one that reads range_min or less (starts inside an
  object) reads -inf; any other reading gets the declared noise and is clamped to
  [range_min, range_max].
"""
import math

import numpy as np


class ScanGeometry:
    """Beam directions (in the sensor frame: x forward, y left, z up) and range post-processing."""

    def __init__(self, ray):
        """`ray`: a urdf_model.RaySpec."""
        if not (ray.range_max > ray.range_min >= 0.0):
            raise ValueError('the ray sensor needs 0 <= range min < range max, got %g .. %g'
                             % (ray.range_min, ray.range_max))
        self.count = range_count(ray.samples, ray.resolution)
        self.vertical_count = range_count(ray.vertical_samples, 1.0)
        self.angle_min = float(ray.min_angle)
        self.angle_max = float(ray.max_angle)
        self.angle_increment = angle_step(self.angle_min, self.angle_max, self.count)
        self.range_min = float(ray.range_min)
        self.range_max = float(ray.range_max)
        yaws = self.angle_min + self.angle_increment * np.arange(self.count)
        if self.vertical_count > 1:
            step = angle_step(ray.vertical_min_angle, ray.vertical_max_angle, self.vertical_count)
            pitches = ray.vertical_min_angle + step * np.arange(self.vertical_count)
        else:
            pitches = np.zeros(1)  # one layer: Gazebo casts it level, whatever the vertical angles say
        # Layer after layer (lowest first), each from min_angle to max_angle: Gazebo's order.
        elev, azim = np.meshgrid(pitches, yaws, indexing='ij')
        self.directions = np.stack([np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim), np.sin(elev)],
                                   axis=-1).reshape(-1, 3)

    @property
    def beams(self):
        return len(self.directions)

    def endpoints(self, origin, rotation):
        """World start and end points of every beam: from range_min to range_max.

        `origin`: the sensor's world position; `rotation`: its 3 x 3 world rotation matrix.
        """
        world_dirs = self.directions @ np.asarray(rotation, dtype=np.float64).T
        origin = np.asarray(origin, dtype=np.float64)
        return origin + self.range_min * world_dirs, origin + self.range_max * world_dirs

    def ranges_from_hits(self, fractions, hit):
        """Distances from the sensor for hit fractions along [range_min, range_max]; +inf for
        beams that hit nothing (`hit` False)."""
        fractions = np.asarray(fractions, dtype=np.float64)
        ranges = self.range_min + fractions * (self.range_max - self.range_min)
        return np.where(np.asarray(hit, dtype=bool), ranges, math.inf)

    def report(self, ranges, noise=None):
        """The ranges RaySensor publishes: +inf at or beyond max, -inf at or below min, else
        noisy (if a noise model is given) and clamped to [min, max]."""
        ranges = np.asarray(ranges, dtype=np.float64)
        out = ranges.copy()
        inside = (ranges > self.range_min) & (ranges < self.range_max)
        if noise is not None and inside.any():
            out[inside] = np.clip(noise.apply(ranges[inside]), self.range_min, self.range_max)
        out[ranges >= self.range_max] = math.inf
        out[ranges <= self.range_min] = -math.inf
        return out


def range_count(samples, resolution):
    """Gazebo's range count: samples x resolution, at least 1."""
    return max(1, int(round(samples * resolution)))


def angle_step(angle_min, angle_max, count):
    """(max - min) / (count - 1), 0 for a single beam."""
    return (angle_max - angle_min) / (count - 1) if count > 1 else 0.0
