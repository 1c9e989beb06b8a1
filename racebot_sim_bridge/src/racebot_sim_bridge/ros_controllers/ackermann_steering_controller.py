"""ackermann_steering_controller/AckermannSteeringController (ros_controllers noetic-devel): one rear
wheel on a VelocityJointInterface and one front steering joint on a PositionJointInterface (a bicycle
model). cmd_vel's linear.x is the speed and, as upstream, its angular.z is taken as the STEERING ANGLE
(rad), not a yaw rate. Odometry, limits, timeout and publishing are diff_drive_controller's
(OdometryDriveController)."""
import math

from racebot_sim_bridge.ros_control.hardware_interface import POSITION, VELOCITY
from racebot_sim_bridge.kinematics.controller_odometry import AckermannOdometry, ackermann_params_from_urdf
from racebot_sim_bridge.ros_controllers.diff_drive_controller import OdometryDriveController


class AckermannSteeringController(OdometryDriveController):
    type_name = 'ackermann_steering_controller/AckermannSteeringController'
    interface = VELOCITY
    odometry_class = AckermannOdometry

    def _init_drive(self):
        rear = self._text('rear_wheel', 'rear_wheel_joint')
        steer = self._text('front_steer', 'front_steer_joint')
        self.separation_h_multiplier = self._number('wheel_separation_h_multiplier', 1.0)
        self.radius_multiplier = self._number('wheel_radius_multiplier', 1.0)
        self.steer_pos_multiplier = self._number('steer_pos_multiplier', 1.0)
        self.separation_h, self.radius = self._wheel_geometry(
            ('wheel_separation_h', 'wheel_radius'),
            lambda *missing: ackermann_params_from_urdf(self.hw.model, rear, steer, *missing),
            'wheel_separation_h %g and wheel radius %g must both be > 0 (from the URDF: the rear wheel and the '
            'steering joint at the same x?); set wheel_separation_h and wheel_radius')
        self.rear = self._handle(rear, VELOCITY)
        self.steer = self._handle(steer, POSITION)

    def claimed_resources(self):
        return [(POSITION, [self.steer.name]), (VELOCITY, [self.rear.name])]

    def _brake(self):
        self.rear.command = 0.0
        self.steer.command = 0.0

    def _read_odometry(self, time):
        self.odometry.set_wheel_params(self.separation_h_multiplier * self.separation_h,
                                       self.radius_multiplier * self.radius)
        wheel, steer = self.rear.position, self.steer.position
        if math.isnan(wheel) or math.isnan(steer):
            return False
        self.odometry.update(wheel, steer * self.steer_pos_multiplier, time)
        return True

    def _command(self, lin, ang):
        # upstream divides by the wheel radius without its multiplier
        self.rear.command = lin / self.radius
        self.steer.command = ang


TYPES = (AckermannSteeringController,)
