"""libhector_gazebo_ros_magnetic.so (hector_gazebo_plugins, melodic-devel): the earth's magnetic field as a
magnetometer on a link measures it.

Parameters as its Load(): robotNamespace (none: the node's namespace; spawn's -robot_namespace fills it),
topicName (magnetic), bodyName (default: the root link), frameId (default: bodyName), magnitude (1.0),
referenceHeading (0 deg), declination (0 deg), inclination (60 deg), useMagneticFieldMsgs (false: a
geometry_msgs/Vector3Stamped; true: sensor_msgs/MagneticField, covariance left all zeros as upstream), the error
model offset, drift, driftFrequency, gaussianNoise, scaleError (3-vectors, hector's SensorModel3) and updateRate
or updatePeriod (0, the default: every world update; hector's UpdateTimer on the world clock). The field in the
world, fixed at Load as upstream (hector calls Gazebo's axes north-west-up; heading and declination are compass
angles): magnitude * (cos(inc) cos(heading - dec), cos(inc) sin(heading - dec), -sin(inc)); each update
publishes it turned into the link's axes (the inverse of the link's world rotation) through the error model,
whether or not anybody listens (as upstream). A dynamic_reconfigure server `<topic>` (SensorModel) changes the
error model. Not here: useWorldSphericalCoordinates (the world's <spherical_coordinates> are not read: warned,
referenceHeading is used).
"""
import math
import random

from racebot_sim_bridge.gazebo_plugins import hector_reconfigure
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_gps import HectorTimedPlugin, UpdateTimer, sensor_model
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.kinematics.rotations import rotate_back

DEFAULT_MAGNITUDE, DEFAULT_REFERENCE_HEADING, DEFAULT_DECLINATION, DEFAULT_INCLINATION = 1.0, 0.0, 0.0, 60.0


def world_field(magnitude, heading, declination, inclination):
    """hector's magnetic_field_world_ (angles in radians)."""
    horizontal = magnitude * math.cos(inclination)
    return (horizontal * math.cos(heading - declination), horizontal * math.sin(heading - declination),
            -magnitude * math.sin(inclination))


def update_period(params, default_rate=0.0):
    """hector's UpdateTimer::Load: updateRate (Hz, 0: every update), then updatePeriod (s) over it."""
    rate = params.number('updateRate', default_rate, minimum=0.0)
    period = 1.0 / rate if rate > 0 else 0.0
    return params.number('updatePeriod', period, minimum=0.0)


class HectorMagnetic(HectorTimedPlugin):
    libraries = ('libhector_gazebo_ros_magnetic.so',)
    error_models = ('model',)

    def __init__(self, ctx, robot, spec, rng=None):
        super().__init__(ctx, robot, spec)
        p = self.params
        if p.boolean('useWorldSphericalCoordinates', False):
            self.warn('<useWorldSphericalCoordinates> is not supported (the world\'s <spherical_coordinates> are '
                      'not read); <referenceHeading> is used')
        self.field = world_field(p.number('magnitude', DEFAULT_MAGNITUDE),
                                 math.radians(p.number('referenceHeading', DEFAULT_REFERENCE_HEADING)),
                                 math.radians(p.number('declination', DEFAULT_DECLINATION)),
                                 math.radians(p.number('inclination', DEFAULT_INCLINATION)))
        self.rng = rng or random.Random()
        self.model = sensor_model(p, self.rng)
        self.timer = UpdateTimer(update_period(p))
        topic = p.string('topicName', 'magnetic')
        ns = model_plugin_namespace('planar_move', p.string('robotNamespace', None), robot.spawn_namespace,
                                    robot.name, ctx.sim.node_namespace)
        if p.boolean('useMagneticFieldMsgs', False):
            from sensor_msgs.msg import MagneticField as message
        else:
            from geometry_msgs.msg import Vector3Stamped as message
        self.message = message
        self.pub = self.publisher(name_in(ns, topic), message, 1)
        model_config, _ = hector_reconfigure.config_types()
        self.reconfigure_server(name_in(ns, topic), model_config, hector_reconfigure.sensor_model_callback(self.model))
        self.reset()

    def before_physics(self, time):
        dt = self.due(time)
        if dt is None:
            return
        _, rotation, _, _ = link_motion(self.world, self.robot.body, self.body_name)
        field = self.model.apply(rotate_back(rotation, self.field), dt)
        msg = self.message()
        msg.header.stamp, msg.header.frame_id = self.stamp(time), self.frame_id
        vector = msg.magnetic_field if hasattr(msg, 'magnetic_field') else msg.vector
        vector.x, vector.y, vector.z = field
        self.pub.publish(msg)
