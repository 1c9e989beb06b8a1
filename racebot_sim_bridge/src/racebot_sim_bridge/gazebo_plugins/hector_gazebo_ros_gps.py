"""libhector_gazebo_ros_gps.so (hector_gazebo_plugins, melodic-devel, the last ROS 1 branch): a GNSS
receiver on a link, as Husky and Jackal declare it.

Parameters as its Load(): robotNamespace (none: the node's namespace; spawn's -robot_namespace fills it),
bodyName (default: the model's root link), frameId (/world), topicName (fix), velocityTopicName
(fix_velocity), referenceLatitude 49.9, referenceLongitude 8.9, referenceHeading 0 (deg), referenceAltitude 0,
status 0 (STATUS_FIX), service 0; the error models' offset, drift, driftFrequency, gaussianNoise, scaleError
(3-vectors; the velocity's with the prefix `velocity`, e.g. velocityGaussianNoise); updateRate 4 Hz (or
updatePeriod), on the world's clock as hector's UpdateTimer counts it. Every update publishes
sensor_msgs/NavSatFix (position covariance: drift^2 + noise^2 per axis, DIAGONAL_KNOWN) and
geometry_msgs/Vector3Stamped, whether or not anybody listens (as upstream). The maths are kinematics/navsat.py.
`<fix topic>/set_reference_geopose` (hector_gazebo_plugins/SetReferenceGeoPose) moves the reference (heading
pi/2 - the pose's yaw; the earth radii stay the first reference's, as upstream) and restarts the timer and
the error models; dynamic_reconfigure servers `<fix topic>/position` and `/velocity` (SensorModel) and
`/status` (GNSS: the fix status and service bits).
Not here: useWorldSphericalCoordinates (the world's <spherical_coordinates> are not read: warned, the
reference parameters are used).
"""
import math
import random

from racebot_sim_bridge.kinematics.navsat import DEFAULT_REFERENCE, ErrorModel, GeoReference
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.kinematics.rotations import yaw_of
from racebot_sim_bridge.gazebo_plugins import hector_reconfigure
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion


def update_due(time, period, step):
    """hector's UpdateTimer::checkUpdate: on the world's clock, within half a step of a multiple of the period."""
    if period == 0:
        return True
    fraction = math.fmod(time + step / 2.0, period)
    return 0.0 <= fraction < step


class UpdateTimer:
    """hector's UpdateTimer on the world's clock: checkUpdate, getTimeSinceLastUpdate and Reset in one."""

    def __init__(self, period):
        self.period = period
        self.last_update = 0.0

    def reset(self):
        self.last_update = 0.0

    def tick(self, time, step):
        """None when no update is due at `time`; else the time since the last update (0 until a first: last
        update time 0 is "none"), and `time` becomes the last update."""
        if not update_due(time, self.period, step):
            return None
        dt, self.last_update = (time - self.last_update if self.last_update != 0.0 else 0.0), time
        return dt


def sensor_model(params, rng, prefix='', scalar=False):
    """hector's SensorModel_::Load(sdf, prefix) as an ErrorModel: offset, drift, driftFrequency, gaussianNoise,
    scaleError (with a prefix: prefixOffset, prefixDrift, ...), 3-vectors (SensorModel3); `scalar`: SensorModel's
    single numbers, in axis 0 (the other axes at the defaults, unused)."""
    defaults = {'offset': 0.0, 'drift': 0.0, 'driftFrequency': 1.0 / 3600.0, 'gaussianNoise': 0.0,
                'scaleError': 1.0}
    values = {}
    for name, default in defaults.items():
        tag = prefix + name[0].upper() + name[1:] if prefix else name
        if scalar:
            values[name] = (params.number(tag, default), default, default)
        else:
            values[name] = params.vector(tag, 3, (default,) * 3)
    return ErrorModel(rng, values['offset'], values['drift'], values['driftFrequency'], values['gaussianNoise'],
                      values['scaleError'])


class HectorTimedPlugin(ModelPlugin):
    """What hector's GPS, IMU, magnetometer and barometer share: the link (bodyName, default the root link, read
    first) and frame (frameId) they report, an UpdateTimer (`self.timer`) on the world's clock and the error models
    restarted with it (reset); due() asks the timer at each world update."""
    error_models = ()     # the names of its ErrorModel attributes
    frame_default = None  # frameId's default; None: bodyName

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        self.body_name = self.link_param('bodyName', None, default=self.root_link())
        self.frame_id = self.params.string('frameId', self.frame_default or self.body_name)

    def reset(self):
        self.timer.reset()
        for name in self.error_models:
            getattr(self, name).reset()

    def due(self, time):
        """None when no update is due at `time`, else the time since the last update (UpdateTimer.tick)."""
        return self.timer.tick(time, self.ctx.sim.step_size)


class HectorGps(HectorTimedPlugin):
    libraries = ('libhector_gazebo_ros_gps.so',)
    error_models = ('position_error', 'velocity_error')
    frame_default = '/world'

    def __init__(self, ctx, robot, spec, rng=None):
        super().__init__(ctx, robot, spec)
        p = self.params
        if p.boolean('useWorldSphericalCoordinates', False):
            self.warn('<useWorldSphericalCoordinates> is not supported (the world\'s <spherical_coordinates> are '
                      'not read); the reference parameters are used')
        lat, lon, heading, alt = DEFAULT_REFERENCE
        self.reference = GeoReference(p.number('referenceLatitude', lat), p.number('referenceLongitude', lon),
                                      math.radians(p.number('referenceHeading', heading)),
                                      p.number('referenceAltitude', alt))
        self.status = p.integer('status', 0)
        self.service_bits = p.integer('service', 0)
        self.rng = rng or random.Random()
        self.position_error = sensor_model(p, self.rng)
        self.velocity_error = sensor_model(p, self.rng, 'velocity')
        rate = p.number('updateRate', 4.0, minimum=0.0)
        period = 1.0 / rate if rate > 0 else 0.0
        if p.has('updatePeriod') and not p.has('updateRate'):
            period = p.number('updatePeriod', period, minimum=0.0)
        self.timer = UpdateTimer(period)
        ns = model_plugin_namespace('planar_move', p.string('robotNamespace', None), robot.spawn_namespace,
                                    robot.name, ctx.sim.node_namespace)
        from geometry_msgs.msg import Vector3Stamped
        from sensor_msgs.msg import NavSatFix
        self.fix_topic = name_in(ns, p.string('topicName', 'fix'))
        self.fix_pub = self.publisher(self.fix_topic, NavSatFix, 10)
        self.velocity_pub = self.publisher(name_in(ns, p.string('velocityTopicName', 'fix_velocity')),
                                           Vector3Stamped, 10)
        self.NavSatFix, self.Vector3Stamped = NavSatFix, Vector3Stamped
        from hector_gazebo_plugins.srv import SetReferenceGeoPose, SetReferenceGeoPoseResponse
        self.SetReferenceGeoPoseResponse = SetReferenceGeoPoseResponse
        self.service(self.fix_topic + '/set_reference_geopose', SetReferenceGeoPose, self._set_geopose)
        model_config, gnss = hector_reconfigure.config_types()
        self.reconfigure_server(self.fix_topic + '/position', model_config,
                                hector_reconfigure.sensor_model_callback(self.position_error))
        self.reconfigure_server(self.fix_topic + '/velocity', model_config,
                                hector_reconfigure.sensor_model_callback(self.velocity_error))
        self.reconfigure_server(self.fix_topic + '/status', gnss, hector_reconfigure.gnss_callback(self))

    def _set_geopose(self, req):
        """setGeoposeCb, then Reset(), under the world's lock (the update reads the reference)."""
        p, q = req.geo_pose.position, req.geo_pose.orientation
        with self.ctx.sim.lock:
            self.reference = self.reference.moved(p.latitude, p.longitude,
                                                  math.pi / 2.0 - yaw_of((q.x, q.y, q.z, q.w)), p.altitude)
            self.reset()
        return self.SetReferenceGeoPoseResponse()

    def before_physics(self, time):
        dt = self.due(time)
        if dt is None:
            return
        position, _, linear, _ = link_motion(self.world, self.robot.body, self.body_name)
        velocity = self.velocity_error.apply(linear, dt)
        position = self.position_error.apply(position, dt)
        self.position_error.current_drift = [p + dt * v for p, v in zip(self.position_error.current_drift,
                                                                         self.velocity_error.current_drift)]
        stamp = self.stamp(time)
        fix = self.NavSatFix()
        fix.header.stamp, fix.header.frame_id = stamp, self.frame_id
        fix.status.status, fix.status.service = self.status, self.service_bits
        fix.latitude, fix.longitude, fix.altitude = self.reference.fix(position)
        fix.position_covariance_type = self.NavSatFix.COVARIANCE_TYPE_DIAGONAL_KNOWN
        var = self.position_error.variance()
        fix.position_covariance = [var[0], 0.0, 0.0, 0.0, var[1], 0.0, 0.0, 0.0, var[2]]
        vel = self.Vector3Stamped()
        vel.header.stamp, vel.header.frame_id = stamp, self.frame_id
        vel.vector.x, vel.vector.y, vel.vector.z = self.reference.velocity(velocity)
        self.fix_pub.publish(fix)
        self.velocity_pub.publish(vel)
