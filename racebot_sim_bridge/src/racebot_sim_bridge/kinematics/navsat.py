"""hector_gazebo_plugins' GPS maths (gazebo_ros_gps.cpp, sensor_model.h), without ROS.

- The local frame to WGS84 as hector does it: a flat-earth tangent plane at the reference latitude and
  longitude, with the WGS84 radii of curvature there; `heading` (rad) turns the local axes (heading 0: x
  north, y west). Velocities are turned the same way.
- The error model (SensorModel3): value * scale_error + offset + drift + white noise, the drift a
  first-order Gauss-Markov process: drift = exp(-dt * f) * drift + dt * N(0, sqrt(2 f) * drift_sigma),
  started at N(0, drift_sigma); per axis.
"""
import math
from dataclasses import dataclass

EQUATORIAL_RADIUS = 6378137.0
FLATTENING = 1.0 / 298.257223563
EXCENTRICITY2 = 2 * FLATTENING - FLATTENING * FLATTENING
DEFAULT_REFERENCE = (49.9, 8.9, 0.0, 0.0)  # latitude, longitude (deg), heading (deg), altitude (m): hector's


@dataclass(frozen=True)
class GeoReference:
    latitude: float   # deg
    longitude: float  # deg
    heading: float    # rad
    altitude: float   # m
    radii_latitude: float = None  # deg: where the radii are taken; None: at `latitude`

    def radii(self):
        """(north, east) radii of curvature (m) at radii_latitude (the reference latitude unless given)."""
        latitude = self.latitude if self.radii_latitude is None else self.radii_latitude
        s = math.sin(math.radians(latitude))
        temp = 1.0 / (1.0 - EXCENTRICITY2 * s * s)
        prime_vertical = EQUATORIAL_RADIUS * math.sqrt(temp)
        return prime_vertical * (1 - EXCENTRICITY2) * temp, prime_vertical * math.cos(math.radians(latitude))

    def moved(self, latitude, longitude, heading, altitude):
        """hector's set_reference_geopose: a new reference whose radii stay those of this one's latitude
        (setGeoposeCb does not recompute them)."""
        kept = self.latitude if self.radii_latitude is None else self.radii_latitude
        return GeoReference(latitude, longitude, heading, altitude, kept)

    def fix(self, position):
        """(latitude, longitude, altitude) of a local position (x, y, z)."""
        north, east = self.radii()
        x, y, z = position
        c, s = math.cos(self.heading), math.sin(self.heading)
        return (self.latitude + (c * x + s * y) / north * 180.0 / math.pi,
                self.longitude - (-s * x + c * y) / east * 180.0 / math.pi,
                self.altitude + z)

    def velocity(self, velocity):
        x, y, z = velocity
        c, s = math.cos(self.heading), math.sin(self.heading)
        return (c * x + s * y, -s * x + c * y, z)


class ErrorModel:
    """hector's SensorModel3 on a 3-vector. Each parameter is a 3-tuple; rng: a random.Random."""

    def __init__(self, rng, offset=(0.0,) * 3, drift=(0.0,) * 3, drift_frequency=(1.0 / 3600.0,) * 3,
                 gaussian_noise=(0.0,) * 3, scale_error=(1.0,) * 3):
        self.rng = rng
        self.offset, self.drift, self.drift_frequency = tuple(offset), tuple(drift), tuple(drift_frequency)
        self.gaussian_noise, self.scale_error = tuple(gaussian_noise), tuple(scale_error)
        self.reset()

    def reset(self):
        self.current_drift = [self.rng.gauss(0.0, d) if d else 0.0 for d in self.drift]

    def apply(self, value, dt):
        """The measured value of `value` after `dt` seconds since the last one."""
        out = []
        for i in range(3):
            f, d = self.drift_frequency[i], self.drift[i]
            sigma = math.sqrt(2 * f) * d if f > 0 else 0.0
            self.current_drift[i] = math.exp(-dt * f) * self.current_drift[i] + \
                (dt * self.rng.gauss(0.0, sigma) if sigma else 0.0)
            noise = self.rng.gauss(0.0, self.gaussian_noise[i]) if self.gaussian_noise[i] else 0.0
            out.append(value[i] * self.scale_error[i] + self.offset[i] + self.current_drift[i] + noise)
        return tuple(out)

    def variance(self):
        """hector's published position covariance diagonal: drift^2 + noise^2 per axis."""
        return tuple(d * d + n * n for d, n in zip(self.drift, self.gaussian_noise))
