"""What an IMU measures, from the motion of the point it sits on.

Pure numpy: no rospy, no pybullet. As gazebo/sensors/ImuSensor does it:
- angular velocity: the carrying link's world angular velocity, in the sensor frame;
- linear acceleration: the change of the sensor point's world velocity since the previous measurement over
  the time between them, minus gravity, in the sensor frame (a sensor at rest reads +|g| along its up axis, as
  an accelerometer does), as Gazebo's ImuSensor::UpdateImpl differences it (`prime` records a velocity without a
  measurement: the one Gazebo's Load records);
- orientation: the sensor frame's orientation in the world frame (ENU, REP 145: a level IMU facing
  east reads identity), or with gazebo_ros_imu_sensor's initialOrientationAsReference relative to
  the orientation the sensor had when it was made (`reference`).
An update with no velocity recorded before it (none primed, or after reset()) returns None rather than invent an
acceleration.
"""
import numpy as np

from racebot_sim_bridge.kinematics.rotations import conjugate, matrix, quaternion_multiply


def quaternion_to_matrix(q):
    """3 x 3 rotation matrix (numpy) of a unit quaternion (x, y, z, w)."""
    return np.array(matrix(q))


class ImuMeasurement:
    __slots__ = ('orientation', 'angular_velocity', 'linear_acceleration')

    def __init__(self, orientation, angular_velocity, linear_acceleration):
        self.orientation = tuple(orientation)  # x, y, z, w
        self.angular_velocity = np.asarray(angular_velocity, dtype=np.float64)
        self.linear_acceleration = np.asarray(linear_acceleration, dtype=np.float64)


class ImuKinematics:
    def __init__(self, gravity, reference=None):
        """`gravity`: the world's gravity vector, e.g. (0, 0, -9.8); `reference`: None for the world
        as orientation reference (REP 145), or the quaternion orientations are reported relative to."""
        self.gravity = np.asarray(gravity, dtype=np.float64)
        self.reference = None if reference is None else conjugate(tuple(reference))
        self.last_time = None
        self.last_velocity = None

    def reset(self):
        """Forget the recorded velocity (after a pause in measuring, or time going backwards)."""
        self.last_time = None
        self.last_velocity = None

    def prime(self, time, point_velocity):
        """Records the sensor point's world velocity at sim `time` (the step before an update)."""
        self.last_time, self.last_velocity = time, np.asarray(point_velocity, dtype=np.float64)

    def measure(self, time, orientation, point_velocity, angular_velocity):
        """One measurement at sim `time` from the sensor's world orientation (quaternion), the world
        velocity of the sensor point and the world angular velocity; None without a velocity recorded
        before `time`. The velocity given is recorded for the next update (an IMU updated every step)."""
        velocity = np.asarray(point_velocity, dtype=np.float64)
        previous_time, previous_velocity = self.last_time, self.last_velocity
        self.last_time, self.last_velocity = time, velocity
        if previous_time is None or not time > previous_time:
            return None
        world_to_sensor = quaternion_to_matrix(orientation).T
        acceleration = (velocity - previous_velocity) / (time - previous_time)
        reported = orientation if self.reference is None else quaternion_multiply(self.reference, tuple(orientation))
        return ImuMeasurement(reported,
                              world_to_sensor @ np.asarray(angular_velocity, dtype=np.float64),
                              world_to_sensor @ (acceleration - self.gravity))

