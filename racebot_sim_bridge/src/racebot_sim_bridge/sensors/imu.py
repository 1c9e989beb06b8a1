"""What an IMU measures, from the motion of the point it sits on.

Pure numpy: no rospy, no pybullet. As gazebo/sensors/ImuSensor does it:
- angular velocity: the carrying link's world angular velocity, in the sensor frame;
- linear acceleration: the change of the sensor point's world velocity since the previous
  measurement divided by the time between them, minus gravity, in the sensor frame; so a sensor
  at rest reads +|g| along its up axis, as an accelerometer does;
- orientation: the sensor frame's orientation in the world frame (ENU, REP 145: a level IMU
  facing east reads identity). Gazebo reports it relative to the sensor's pose at load time; the
  two agree for a robot spawned level and facing along x.
The first measurement after (re)activation has no previous velocity: `measure` returns None for
it (a 'priming' sample) rather than invent an acceleration.
"""
import numpy as np

from ..rotations import matrix


def quaternion_to_matrix(q):
    """3 x 3 rotation matrix (numpy) of a unit quaternion (x, y, z, w)."""
    return np.array(matrix(q))


class ImuMeasurement(object):
    __slots__ = ('orientation', 'angular_velocity', 'linear_acceleration')

    def __init__(self, orientation, angular_velocity, linear_acceleration):
        self.orientation = tuple(orientation)  # x, y, z, w
        self.angular_velocity = np.asarray(angular_velocity, dtype=np.float64)
        self.linear_acceleration = np.asarray(linear_acceleration, dtype=np.float64)


class ImuKinematics(object):
    def __init__(self, gravity):
        """`gravity`: the world's gravity vector, e.g. (0, 0, -9.8)."""
        self.gravity = np.asarray(gravity, dtype=np.float64)
        self.last_time = None
        self.last_velocity = None

    def reset(self):
        """Forget the previous sample (after a pause in measuring, or time going backwards)."""
        self.last_time = None
        self.last_velocity = None

    def measure(self, time, orientation, point_velocity, angular_velocity):
        """One measurement at sim `time` from the sensor's world orientation (quaternion), the
        world velocity of the sensor point and the world angular velocity; None when priming."""
        velocity = np.asarray(point_velocity, dtype=np.float64)
        previous_time, previous_velocity = self.last_time, self.last_velocity
        self.last_time, self.last_velocity = time, velocity
        if previous_time is None or not time > previous_time:
            return None
        world_to_sensor = quaternion_to_matrix(orientation).T
        acceleration = (velocity - previous_velocity) / (time - previous_time)
        return ImuMeasurement(orientation,
                              world_to_sensor @ np.asarray(angular_velocity, dtype=np.float64),
                              world_to_sensor @ (acceleration - self.gravity))
