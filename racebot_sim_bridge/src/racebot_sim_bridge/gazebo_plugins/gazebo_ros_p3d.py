"""libgazebo_ros_p3d.so (gazebo_plugins noetic-devel): the true pose and velocity of a link, as
nav_msgs/Odometry.

Parameters: bodyName (required: the link), topicName (required; empty: nothing is published),
frameName world (world, map, or a link of the same model), xyzOffset 0 0 0, rpyOffset 0 0 0,
gaussianNoise 0, updateRate 0 (every world update), robotNamespace. Upstream's own arithmetic is kept:
- with frameName world or map: pose and velocities are the link's in world axes (the velocity is
  the link frame origin's, as Gazebo's Link::WorldLinearVel), not in the body's axes;
- with a link as frameName: position in that link's axes, orientation q_body * q_frame^-1, and the
  velocity differences (body - frame) turned BY the frame's rotation (not into its axes);
- then xyzOffset is added to the position and rpyOffset's rotation is applied before the orientation;
- gaussianNoise (a standard deviation) is added to each twist component only, its square on the
  diagonal of both covariances; header.frame_id is frameName under tf_prefix, child_frame_id bodyName;
  the stamp is the sim time; nothing is computed while nobody subscribes.
Refused: a missing bodyName or topicName, a bodyName or frameName that is no link of the model. One naming
a link Gazebo lumps into its parent through a fixed joint arrives as that parent, with xyzOffset and
rpyOffset composed with the joint, as sdformat rewrites it (description/sdf_reduction).
"""
import random

from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.kinematics.rotations import (conjugate, quaternion_multiply, rotate, rotate_back,
                                                     rpy_to_quaternion)
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin, PluginError
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.gazebo_plugins.odometry_output import odometry, tf_prefix, tf_resolve
from racebot_sim_bridge.gazebo_plugins.update_timing import AtLeastPeriod

WORLD_FRAMES = ('/world', 'world', '/map', 'map')


def relative_state(body, frame, xyz_offset, rpy_offset):
    """p3d's (position, orientation, linear, angular) of `body` (position, quaternion, linear velocity,
    angular velocity, world axes) relative to `frame` (the same, or None for the world), offsets applied."""
    position, orientation, linear, angular = body
    if frame is not None:
        f_pos, f_q, f_lin, f_ang = frame
        position = rotate_back(f_q, tuple(position[i] - f_pos[i] for i in range(3)))
        orientation = quaternion_multiply(orientation, conjugate(f_q))
        linear = rotate(f_q, tuple(linear[i] - f_lin[i] for i in range(3)))
        angular = rotate(f_q, tuple(angular[i] - f_ang[i] for i in range(3)))
    position = tuple(position[i] + xyz_offset[i] for i in range(3))
    q = quaternion_multiply(rpy_to_quaternion(*rpy_offset), orientation)
    norm = sum(c * c for c in q) ** 0.5
    return position, tuple(c / norm for c in q), tuple(linear), tuple(angular)


def covariance(sigma):
    cov = [0.0] * 36
    for i in range(6):
        cov[7 * i] = sigma * sigma
    return cov


class P3D(ModelPlugin):
    libraries = ('libgazebo_ros_p3d.so',)

    def __init__(self, ctx, robot, spec, rng=None):
        super().__init__(ctx, robot, spec)
        p = self.params
        self.body_name = self.link_param('bodyName', 'the link whose pose is published')
        if not p.has('topicName'):
            raise PluginError('<topicName> is missing: give the topic to publish nav_msgs/Odometry on')
        for old, new in (('xyzOffsets', 'xyzOffset'), ('rpyOffsets', 'rpyOffset')):
            if p.has(old) and not p.has(new):
                self.warn('<%s> is not read (gazebo_plugins noetic reads <%s>); no offset is applied' % (old, new))
        self.frame_name = p.string('frameName', 'world')
        self.reference = None if self.frame_name in WORLD_FRAMES else self.link_param('frameName', 'the reference link',
                                                                                     name=self.frame_name)
        self.xyz_offset = p.vector('xyzOffset', 3, (0.0, 0.0, 0.0))
        self.rpy_offset = p.vector('rpyOffset', 3, (0.0, 0.0, 0.0))
        self.noise = p.number('gaussianNoise', 0.0)  # a negative sigma draws as its absolute value, as upstream
        self.clock = AtLeastPeriod(p.number('updateRate', 0.0), ctx.sim.time)
        self.rng = rng or random.Random()
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        self.frame_id = tf_resolve(tf_prefix(ctx.rospy, ns, search=False), self.frame_name)
        self.cov = covariance(self.noise)
        topic = p.string('topicName', '')
        self.pub = None
        if topic:
            from nav_msgs.msg import Odometry
            self.pub = self.publisher(name_in(ns, topic), Odometry)

    def before_physics(self, time):
        if self.pub is None:
            return
        since = self.clock.since(time)
        if since is None or self.pub.get_num_connections() == 0 or since == 0:
            return
        body = link_motion(self.world, self.robot.body, self.body_name)
        frame = None if self.reference is None else link_motion(self.world, self.robot.body, self.reference)
        position, orientation, linear, angular = relative_state(body, frame, self.xyz_offset, self.rpy_offset)
        gauss = self.rng.gauss
        linear = tuple(v + gauss(0.0, self.noise) for v in linear) if self.noise else linear
        angular = tuple(v + gauss(0.0, self.noise) for v in angular) if self.noise else angular
        self.pub.publish(odometry(self.stamp(time), self.frame_id, self.body_name, position, orientation, linear,
                                  angular, self.cov, self.cov))
        self.clock.mark(time)
