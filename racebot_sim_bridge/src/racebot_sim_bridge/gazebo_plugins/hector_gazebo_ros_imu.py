"""libhector_gazebo_ros_imu.so (hector_gazebo_plugins, melodic-devel): an IMU with drifting biases, as Husky
and Jackal declare it.

Parameters as its Load(): robotNamespace (none: the node's namespace; spawn's -robot_namespace fills it),
bodyName (default: the root link), frameId (default: bodyName), topicName (imu; empty: no topic),
biasTopicName (<topic>/bias), serviceName (<topic>/calibrate, std_srvs/Empty: the rate bias drift set to
0), the error models accel* and rate* (3-vectors: Offset, Drift, DriftFrequency, GaussianNoise,
ScaleError) and yaw* (numbers), gaussianNoise (a non-zero value sets accel and rate noise on every axis),
rpyOffset, updateRate (0, the default: every world update). Each update, as upstream's Update():
acceleration = the change of the link's world velocity since the last update, minus gravity, in the
link's (offset) axes; angular rate from the change of orientation; both through their error models; the
orientation tilted by the accelerometer bias and turned by the yaw bias; covariances from the noises; the
bias on <topic>/bias. Published whether or not anybody listens, as upstream.
Services `<topic>/set_accel_bias` and `<topic>/set_rate_bias` (hector_gazebo_plugins/SetBias: that model's
drift from now on); with a topic, dynamic_reconfigure servers `<topic>/accel`, `/rate` and `/yaw`
(SensorModel).
"""
import math
import random

from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.kinematics.rotations import (conjugate, quaternion_multiply, rotate, rotate_back,
                                                     rpy_to_quaternion)
from racebot_sim_bridge.gazebo_plugins import hector_reconfigure
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_gps import HectorTimedPlugin, UpdateTimer, sensor_model
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion


def _normalized(q):
    n = math.sqrt(sum(c * c for c in q))
    return tuple(c / n for c in q) if n > 0 else (0.0, 0.0, 0.0, 1.0)


def rate_from_rotation(previous, current, dt):
    """hector's angular rate: the rotation from `previous` to `current` (x, y, z, w) over dt, as an axis times
    angle / dt, in the axes `previous * delta = current` expresses it (delta = previous^-1 * current)."""
    delta = quaternion_multiply(conjugate(previous), current)
    axis = delta[:3]
    n = math.sqrt(sum(c * c for c in axis))
    if n == 0 or dt <= 0:
        return (0.0, 0.0, 0.0)
    angle = 2.0 * math.acos(max(min(delta[3], 1.0), -1.0))
    return tuple(angle * c / n / dt for c in axis)


class HectorImu(HectorTimedPlugin):
    libraries = ('libhector_gazebo_ros_imu.so',)
    error_models = ('accel_model', 'rate_model', 'yaw_model')

    def __init__(self, ctx, robot, spec, rng=None):
        super().__init__(ctx, robot, spec)
        p = self.params
        topic = p.string('topicName', 'imu')
        bias_topic = p.string('biasTopicName', topic + '/bias' if topic else '')
        service = p.string('serviceName', topic + '/calibrate')
        self.rng = rng or random.Random()
        self.accel_model = sensor_model(p, self.rng, 'accel')
        self.rate_model = sensor_model(p, self.rng, 'rate')
        self.yaw_model = sensor_model(p, self.rng, 'yaw', scalar=True)
        noise = p.number('gaussianNoise', 0.0)
        if noise != 0.0:
            for m in (self.accel_model, self.rate_model):
                m.gaussian_noise = (noise,) * 3
        self.offset = rpy_to_quaternion(*p.vector('rpyOffset', 3, (0.0, 0.0, 0.0)))
        rate = p.number('updateRate', 0.0, minimum=0.0)
        self.timer = UpdateTimer(1.0 / rate if rate > 0 else 0.0)
        gravity = ctx.sim.world.gravity
        self.gravity = tuple(gravity)
        self.gravity_length = math.sqrt(sum(g * g for g in gravity))
        ns = model_plugin_namespace('planar_move', p.string('robotNamespace', None), robot.spawn_namespace,
                                    robot.name, ctx.sim.node_namespace)
        from sensor_msgs.msg import Imu
        self.Imu = Imu
        self.pub = self.publisher(name_in(ns, topic), Imu, 10) if topic else None
        self.bias_pub = self.publisher(name_in(ns, bias_topic), Imu, 10) if bias_topic else None
        if service:
            from std_srvs.srv import Empty, EmptyResponse
            self.EmptyResponse = EmptyResponse
            self.service(name_in(ns, service), Empty, self._calibrate)
        from hector_gazebo_plugins.srv import SetBias, SetBiasResponse
        self.SetBiasResponse = SetBiasResponse
        for name, model in (('set_accel_bias', self.accel_model), ('set_rate_bias', self.rate_model)):
            self.service(name_in(ns, topic + '/' + name), SetBias, lambda req, model=model: self._set_bias(model, req))
        if topic:
            model_config, _ = hector_reconfigure.config_types()
            for name, model in (('accel', self.accel_model), ('rate', self.rate_model), ('yaw', self.yaw_model)):
                self.reconfigure_server(name_in(ns, topic + '/' + name), model_config,
                                        hector_reconfigure.sensor_model_callback(model, scalar=name == 'yaw'))
        self.reset()

    def _set_bias(self, model, req):
        """SetAccelBiasCallback / SetRateBiasCallback: the model's reset(bias), its drift set."""
        with self.ctx.sim.lock:
            model.current_drift = [req.bias.x, req.bias.y, req.bias.z]
        return self.SetBiasResponse()

    def _calibrate(self, _req):
        self.rate_model.current_drift = [0.0, 0.0, 0.0]  # hector's rateModel.reset(Vector3(0, 0, 0))
        return self.EmptyResponse()

    def reset(self):
        super().reset()
        self.orientation = (0.0, 0.0, 0.0, 1.0)
        self.velocity = (0.0, 0.0, 0.0)
        self.accel = (0.0, 0.0, 0.0)
        self.rate = (0.0, 0.0, 0.0)

    def before_physics(self, time):
        dt = self.due(time)
        if dt is None:
            return
        _, pose_rot, velocity, _ = link_motion(self.world, self.robot.body, self.body_name)
        rot = _normalized(quaternion_multiply(self.offset, pose_rot))
        if dt > 0.0:
            change = tuple((velocity[i] - self.velocity[i]) / dt - self.gravity[i] for i in range(3))
            self.accel = rotate_back(rot, change)
            self.rate = rotate(conjugate(self.offset), rate_from_rotation(self.orientation, rot, dt))
        self.velocity = velocity
        self.orientation = rot
        accel = self.accel_model.apply(self.accel, dt)
        rate = self.rate_model.apply(self.rate, dt)
        self.yaw_model.apply((0.0, 0.0, 0.0), dt)
        accel_bias = tuple(d + o for d, o in zip(self.accel_model.current_drift, self.accel_model.offset))
        rate_bias = tuple(d + o for d, o in zip(self.rate_model.current_drift, self.rate_model.offset))
        yaw_error = self.yaw_model.current_drift[0] + self.yaw_model.offset[0]
        drift = rotate(pose_rot, accel_bias)
        g = self.gravity_length or 1.0
        tilt = (0.5 * drift[1] / g, 0.5 * -drift[0] / g, 0.0, 1.0)  # Gazebo's Quaternion(w=1, x, y, z=0)
        error = _normalized(quaternion_multiply((0.0, 0.0, math.sin(yaw_error / 2), math.cos(yaw_error / 2)), tilt))
        reported = quaternion_multiply(error, rot)
        stamp = self.stamp(time)
        if self.pub is not None:
            msg = self._imu(stamp, reported, rate, accel)
            an, rn, yn = self.accel_model.gaussian_noise, self.rate_model.gaussian_noise, self.yaw_model.gaussian_noise
            oc = [0.0] * 9
            oc[8] = yn[0] * yn[0]
            if self.gravity_length > 0:
                oc[0], oc[4] = an[0] ** 2 / self.gravity_length ** 2, an[1] ** 2 / self.gravity_length ** 2
            else:
                oc[0] = oc[4] = -1.0
            msg.orientation_covariance = oc
            msg.angular_velocity_covariance = [rn[0] ** 2, 0.0, 0.0, 0.0, rn[1] ** 2, 0.0, 0.0, 0.0, rn[2] ** 2]
            msg.linear_acceleration_covariance = [an[0] ** 2, 0.0, 0.0, 0.0, an[1] ** 2, 0.0, 0.0, 0.0, an[2] ** 2]
            self.pub.publish(msg)
        if self.bias_pub is not None:
            self.bias_pub.publish(self._imu(stamp, error, rate_bias, accel_bias))

    def _imu(self, stamp, orientation, rate, accel):
        """A sensor_msgs/Imu in this plugin's frame: orientation (x, y, z, w), angular velocity, acceleration."""
        msg = self.Imu()
        msg.header.stamp, msg.header.frame_id = stamp, self.frame_id
        msg.orientation.x, msg.orientation.y, msg.orientation.z, msg.orientation.w = orientation
        msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = rate
        msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z = accel
        return msg
