"""The simulator driven in-process, without ROS: what the world server does in each update, with
commands applied at exact sim times.

This is also how to get reproducible runs (docs/BENCHMARK.md, "Reproducible runs"): build a Simulator from the world
file, spawn the URDF, load and start the controllers with the YAML's parameters, and set each
controller's `command` from a script keyed to `sim.time` between `sim.step()` calls. Through ROS,
commands arrive at sim times that depend on the machine's load; here they cannot.
"""
import math

import rospy  # only for rospy.Time in message stamps (no master, no node)

from racebot_control.wheel_commands import CarGeometry, wheel_commands
from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from . import common

WHEEL_CONTROLLERS = common.CONTROLLERS[:6]  # WheelCommands order (servo_commands_node.CONTROLLERS)
HINGE_STEP = 0.3          # rad, the step command
HINGE_STEP_DURATION = 1.0  # s of sim time recorded after the step
SETTLING_BAND = 0.02      # settling: within 2 % of the step for good


class _Topic:
    def publish(self, msg):
        pass

    def unregister(self):
        pass

    def get_num_connections(self):
        return 0


class NullIO:
    """The controllers' I/O with nobody listening and nothing arriving: commands are set directly."""

    def publisher(self, topic, cls, queue_size):
        return _Topic()

    def subscriber(self, topic, cls, callback):
        return _Topic()

    def stamp(self, time):
        return rospy.Time.from_sec(time)

    def warn_throttle(self, key, period, message):
        pass


class _Log:
    errors = []
    error = staticmethod(errors.append)
    warn = info = staticmethod(lambda msg: None)


class Car:
    """A Simulator with the racebot spawned at the origin and the tutorial's seven controllers running."""

    def __init__(self, world_file, urdf_xml=None):
        params = common.controller_params()
        ns = common.NAMESPACE

        def get_params(path):
            return params.get(path[len(ns) + 1:]) if path.startswith(ns + '/') else None
        self.sim = Simulator(sdf_reader.load_world(world_file), NullIO(), _Log, get_params)
        GazeboRosControlPlugin.attach(self.sim)  # the controller manager, without its services
        xml = urdf_xml or common.render_racebot()
        self.robot = self.sim.spawn_urdf('racebot', xml, '', (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
        body = self.robot.body
        frame = body.com_pose_for_frame((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))  # as spawn_model places it
        body.set_pose(frame.position, frame.orientation)
        body.spawn_pose = body.pose()
        cm = self.robot.control.cm
        for name in common.CONTROLLERS:
            if not cm.load(name):
                raise common.BenchError('could not load %s: %s' % (name, '; '.join(_Log.errors[-1:])))
        if not cm.request_switch(list(common.CONTROLLERS), [], 2):
            raise common.BenchError('could not start the controllers')
        self.sim.step()  # ros_control starts them at the next update
        self.controllers = {n: cm.loaded[n].controller for n in common.CONTROLLERS}
        self.geometry = CarGeometry()

    def drive(self, speed, steering_angle, mode='parallel'):
        """What servo_commands does with one AckermannDriveStamped."""
        commands = wheel_commands(speed, steering_angle, mode, self.geometry)
        for name, value in zip(WHEEL_CONTROLLERS, commands):
            self.controllers[name].command = value

    def rear_axle(self):
        """(x, y) of the rear axle middle, and the yaw."""
        pose = self.robot.body.frame_pose()
        x, y, _ = pose.position
        qx, qy, qz, qw = pose.orientation
        yaw = math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
        return (x + common.REAR_AXLE_X * math.cos(yaw), y + common.REAR_AXLE_X * math.sin(yaw)), yaw

    def step_until(self, t):
        while self.sim.time < t - 1e-12:
            self.sim.step()

    def close(self):
        self.sim.close()


def hinge_step(world_file, urdf_xml=None):
    """Step response of the left steering hinge, 0 -> 0.3 rad, with the tutorial's gains (p 10, d 0.5),
    car standing: [(t, angle)] every update and the figures."""
    car = Car(world_file, urdf_xml)
    try:
        car.step_until(0.5)  # the car lands and stands
        hinge = car.robot.control.hw.handles['left_steering_hinge_joint']
        t0, start = car.sim.time, hinge.position
        for name in ('left_steering_hinge_position_controller', 'right_steering_hinge_position_controller'):
            car.controllers[name].command = HINGE_STEP
        samples = [(0.0, start)]
        while car.sim.time < t0 + HINGE_STEP_DURATION - 1e-12:
            car.sim.step()
            samples.append((car.sim.time - t0, hinge.position))
    finally:
        car.close()
    return samples, step_figures(samples, start, HINGE_STEP)


def step_figures(samples, start, target):
    """Rise time (10 % -> 90 %), overshoot (% of the step), settling time (last entry into the
    2 % band), final value."""
    size = target - start

    def first_time(fraction):
        for t, v in samples:
            if (v - start) / size >= fraction:
                return t
        return None
    t10, t90 = first_time(0.1), first_time(0.9)
    peak = max((v - start) / size for _, v in samples)
    settle = None
    for t, v in samples:
        if abs(v - target) > SETTLING_BAND * abs(size):
            settle = None
        elif settle is None:
            settle = t
    return {'rise_time_s': (t90 - t10) if t10 is not None and t90 is not None else None,
            'overshoot_pct': max(0.0, (peak - 1.0) * 100.0),
            'settling_time_s': settle,
            'final_rad': samples[-1][1],
            'step_rad': size}


# Commands keyed to sim time: (from t [s], speed [m/s], steering angle [rad]).
SCRIPT = ((0.0, 1.0, 0.0), (1.0, 1.5, 0.3), (3.0, 0.8, -0.45), (5.0, 2.0, 0.1), (7.0, -0.5, 0.6),
          (9.0, 1.2, -0.2))
RECORD_EVERY = 10  # updates between trajectory samples


def scripted_run(world_file, duration, urdf_xml=None):
    """The car driven by SCRIPT for `duration` s of sim time: [(t, x, y, yaw)] of the rear axle."""
    car = Car(world_file, urdf_xml)
    script = list(SCRIPT)
    trajectory = []
    try:
        n = 0
        while car.sim.time < duration - 1e-12:
            while script and script[0][0] <= car.sim.time + 1e-12:
                _, speed, angle = script.pop(0)
                car.drive(speed, angle)
            car.sim.step()
            n += 1
            if n % RECORD_EVERY == 0:
                (x, y), yaw = car.rear_axle()
                trajectory.append((car.sim.time, x, y, yaw))
    finally:
        car.close()
    return trajectory
