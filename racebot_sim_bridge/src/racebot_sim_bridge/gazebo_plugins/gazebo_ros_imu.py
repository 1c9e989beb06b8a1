"""libgazebo_ros_imu.so (gazebo_plugins noetic-devel): the MODEL plugin's sensor_msgs/Imu of a link
(the `imu` sensor's libgazebo_ros_imu_sensor.so is sensors/'s).

Parameters: bodyName (required: a link of the model; one Gazebo lumps into its parent through a fixed joint
arrives as that parent, with xyzOffset and rpyOffset composed with the joint, and so does such a frameName,
as sdformat rewrites them: description/sdf_reduction),
topicName /default_imu (empty: nothing is advertised), serviceName /default_imu (std_srvs/Empty,
answers at once: "always calibrated in sim"), gaussianNoise 0 (a standard deviation), xyzOffset 0 0 0
(read and, as upstream, used for nothing the message carries), rpyOffset 0 0 0, updateRate 0 (every
world update), frameName (default bodyName; used as written), robotNamespace (text + '/', none: '').
The old xyzOffsets/rpyOffsets are not read by noetic: a warning says so.

Upstream's arithmetic is kept: orientation is the rpyOffset rotation times the link's world
orientation; the angular velocity and the linear acceleration (the difference of the link frame
origin's world velocity since the last message, over the sim time between them, without gravity:
a resting IMU reads 0) get gaussian noise per axis and are then turned BY that orientation (not into
the link's axes); gaussianNoise squared is on the diagonal of the three covariances. Nothing is
computed while nobody subscribes, and the acceleration then spans the whole gap. Stamp: the sim time.
"""
import random

from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.kinematics.rotations import quaternion_multiply, rotate, rpy_to_quaternion
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.gazebo_plugins.update_timing import AtLeastPeriod
from racebot_sim_bridge.engine.sim_time import to_ns

DEFAULT_NAME = '/default_imu'  # upstream's topic and service when not given
NEVER = (-(1 << 63), 1 << 63)  # the quiet span of an IMU with no topic: all time


def acceleration(last_velocity, velocity, dt):
    """(velocity - last_velocity) / dt per axis; None when dt is 0 (upstream then keeps the last)."""
    if dt == 0:
        return None
    return tuple((velocity[i] - last_velocity[i]) / dt for i in range(3))


def imu_vectors(orientation, offset_rotation, angular, linear_acceleration, noise):
    """Upstream's (orientation, angular velocity, linear acceleration) of the message, from the link's
    world orientation, world angular velocity and world acceleration; `noise()` draws one sample."""
    q = quaternion_multiply(offset_rotation, orientation)
    x, y, z, s = q  # spelled out, not generators: 50-100 messages a sim second per IMU
    norm = (((x * x + y * y) + z * z) + s * s) ** 0.5  # sum()'s order
    q = (x / norm, y / norm, z / norm, s / norm)
    w = rotate(q, (angular[0] + noise(), angular[1] + noise(), angular[2] + noise()))
    acc = linear_acceleration
    a = rotate(q, (acc[0] + noise(), acc[1] + noise(), acc[2] + noise()))
    return q, w, a


class Imu(ModelPlugin):
    libraries = ('libgazebo_ros_imu.so',)

    def __init__(self, ctx, robot, spec, rng=None):
        super().__init__(ctx, robot, spec)
        p = self.params
        self.body_name = self.link_param('bodyName', 'the link whose motion the IMU reports')
        self.topic = p.string('topicName', DEFAULT_NAME)
        self.service_name = p.string('serviceName', DEFAULT_NAME)
        self.noise = p.number('gaussianNoise', 0.0)
        for old, new in (('xyzOffsets', 'xyzOffset'), ('rpyOffsets', 'rpyOffset')):
            if p.has(old) and not p.has(new):
                self.warn('<%s> is not read (gazebo_plugins noetic reads <%s>); no offset is applied' % (old, new))
        self.xyz_offset = p.vector('xyzOffset', 3, (0.0, 0.0, 0.0))
        self.offset_rotation = rpy_to_quaternion(*p.vector('rpyOffset', 3, (0.0, 0.0, 0.0)))
        self.clock = AtLeastPeriod(p.number('updateRate', 0.0), ctx.sim.time)
        self.frame_name = p.string('frameName', self.body_name)
        self.rng = rng or random.Random()
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        _, _, self.last_velocity, _ = link_motion(self.world, robot.body, self.body_name)
        self.linear_acceleration = (0.0, 0.0, 0.0)
        self.pub = None
        if self.topic:
            from sensor_msgs.msg import Imu as ImuMsg
            from std_srvs.srv import Empty, EmptyResponse
            self.msg_class = ImuMsg
            self.pub = self.publisher(name_in(ns, self.topic), ImuMsg)
            self.service(name_in(ns, self.service_name), Empty, lambda request: EmptyResponse())

    def quiet_span(self):
        if self.pub is None:
            return NEVER
        return self.clock.quiet_span()

    def before_physics(self, time):
        if self.pub is None or 0 <= to_ns(time) - self.clock.last < self.clock.quiet_ns:  # clock.quiet, inline
            return
        since = self.clock.since(time)
        if since is None or self.pub.get_num_connections() == 0:
            return
        _, orientation, velocity, angular = link_motion(self.world, self.robot.body, self.body_name)
        a = acceleration(self.last_velocity, velocity, since)
        if a is not None:
            self.linear_acceleration, self.last_velocity = a, velocity
        gauss, sigma = self.rng.gauss, self.noise
        noise = (lambda: gauss(0.0, sigma)) if sigma else (lambda: 0.0)
        q, w, acc = imu_vectors(orientation, self.offset_rotation, angular, self.linear_acceleration, noise)
        msg = self.msg_class()
        msg.header.frame_id = self.frame_name
        msg.header.stamp = self.stamp(time)
        o = msg.orientation
        o.x, o.y, o.z, o.w = q
        msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = w
        msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z = acc
        variance = sigma * sigma
        for cov in (msg.orientation_covariance, msg.angular_velocity_covariance, msg.linear_acceleration_covariance):
            cov[0] = cov[4] = cov[8] = variance
        self.pub.publish(msg)
        self.clock.mark(time)
