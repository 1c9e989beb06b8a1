"""libhector_gazebo_ros_baro.so (hector_quadrotor's hector_quadrotor_gazebo_plugins, the last ROS 1 version): a
barometric altimeter on a link.

Parameters as its Load(): robotNamespace (none: the node's namespace; spawn's -robot_namespace fills it),
bodyName (default: the root link), frameId (default: the link's name), topicName (pressure_height),
altimeterTopicName (altimeter), elevation (0 m), qnh (1013.25 hPa), the error model offset, drift,
driftFrequency, gaussianNoise, scaleError (single numbers: hector's scalar SensorModel) and updateRate or
updatePeriod (0: every world update, hector's UpdateTimer). Each update: height = the error model of the link's
world z; geometry_msgs/PointStamped on topicName with point.z = height; hector_uav_msgs/Altimeter on
altimeterTopicName with altitude = height + elevation, pressure = qnh * (1 - altitude / 44330)^5.263157 (hPa,
the international barometric formula) and qnh; an empty topic name advertises nothing. The Altimeter's header is
the PointStamped's, as upstream copies it: without a height topic its stamp stays 0. A dynamic_reconfigure server
`<altimeterTopicName>` (SensorModel) changes the error model. hector_uav_msgs is racebot's stand-in
(upstream_compat/hector_uav_msgs: Altimeter only, same md5), as Debian has no hector_quadrotor.
"""
import random

from racebot_sim_bridge.gazebo_plugins import hector_reconfigure
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_gps import HectorTimedPlugin, UpdateTimer, sensor_model
from racebot_sim_bridge.gazebo_plugins.hector_gazebo_ros_magnetic import update_period
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in

DEFAULT_ELEVATION, DEFAULT_QNH = 0.0, 1013.25


def pressure(altitude, qnh):
    """hector's pressure (hPa) at `altitude` (m) for sea-level pressure `qnh` (hPa)."""
    return (1.0 - altitude / 44330.0) ** 5.263157 * qnh


class HectorBaro(HectorTimedPlugin):
    libraries = ('libhector_gazebo_ros_baro.so',)
    error_models = ('model',)

    def __init__(self, ctx, robot, spec, rng=None):
        super().__init__(ctx, robot, spec)
        p = self.params
        height_topic = p.string('topicName', 'pressure_height')
        altimeter_topic = p.string('altimeterTopicName', 'altimeter')
        self.elevation = p.number('elevation', DEFAULT_ELEVATION)
        self.qnh = p.number('qnh', DEFAULT_QNH)
        self.rng = rng or random.Random()
        self.model = sensor_model(p, self.rng, scalar=True)
        self.timer = UpdateTimer(update_period(p))
        ns = model_plugin_namespace('planar_move', p.string('robotNamespace', None), robot.spawn_namespace,
                                    robot.name, ctx.sim.node_namespace)
        from geometry_msgs.msg import PointStamped
        from hector_uav_msgs.msg import Altimeter
        self.PointStamped, self.Altimeter = PointStamped, Altimeter
        self.height_stamp = None  # the PointStamped's last stamp, which the Altimeter copies, as upstream
        self.height_pub = self.publisher(name_in(ns, height_topic), PointStamped, 10) if height_topic else None
        self.altimeter_pub = self.publisher(name_in(ns, altimeter_topic), Altimeter, 10) if altimeter_topic else None
        model_config, _ = hector_reconfigure.config_types()
        self.reconfigure_server(name_in(ns, altimeter_topic) if altimeter_topic else ns, model_config,
                                hector_reconfigure.sensor_model_callback(self.model, scalar=True))
        self.reset()

    def before_physics(self, time):
        dt = self.due(time)
        if dt is None:
            return
        position, _, _, _ = link_motion(self.world, self.robot.body, self.body_name)
        height = self.model.apply((position[2], 0.0, 0.0), dt)[0]
        if self.height_pub is not None:
            self.height_stamp = self.stamp(time)
            msg = self.PointStamped()
            msg.header.stamp, msg.header.frame_id = self.height_stamp, self.frame_id
            msg.point.z = height
            self.height_pub.publish(msg)
        if self.altimeter_pub is not None:
            msg = self.Altimeter()
            msg.header.frame_id = self.frame_id
            if self.height_stamp is not None:
                msg.header.stamp = self.height_stamp
            msg.altitude = height + self.elevation
            msg.pressure = pressure(msg.altitude, self.qnh)
            msg.qnh = self.qnh
            self.altimeter_pub.publish(msg)
