"""libhector_gazebo_ros_sonar.so (hector_gazebo_plugins, melodic-devel): a ray sensor's shortest ray as
sensor_msgs/Range, as GazeboRosSonar::Update makes it.

Parameters as its Load(): robotNamespace (none: the node's namespace; spawn's -robot_namespace fills it),
topicName (sonar), frameId (/sonar_link, written as it is: no tf_prefix), the error model of hector's SensorModel
(offset, drift, driftFrequency, gaussianNoise, scaleError: numbers), and its UpdateTimer: updateRate (10 Hz: on
the world's clock, within half a step of a multiple of the period), updatePeriod, updateOffset. Every timer tick
publishes, whether or not anybody listens (as upstream), stamped with the sim time: radiation ULTRASOUND,
field_of_view min(|horizontal span|, |vertical span|) of the sensor's angles (0 without a <vertical>, as
upstream), min/max range the sensor's; the range the shortest raw ray (../sensors/ray_shape.py: one per sample
and layer, a miss reads range max), and when below range max: range * scaleError + offset + drift + N(0,
gaussianNoise), clamped to [range min, range max]. dynamic_reconfigure server `<ns>/<topicName>` (SensorModel).
~sensors/noise false sets the model's gaussianNoise and drift to 0.
"""
import math
import random

import numpy as np
from sensor_msgs.msg import Range

from racebot_sim_bridge.gazebo_plugins import hector_reconfigure
from racebot_sim_bridge.gazebo_plugins.model_plugin import _ReconfigureHandle
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import name_in
from racebot_sim_bridge.gazebo_plugins.sensor_plugin import Sensor, SensorKind
from racebot_sim_bridge.kinematics.navsat import ErrorModel
from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix
from racebot_sim_bridge.sensors.range_reading import ULTRASOUND
from racebot_sim_bridge.sensors.ray_shape import RayShape
from racebot_sim_bridge.sensors.raycast import cast_rays

FLOAT_MAX = float(np.finfo(np.float32).max)  # std::numeric_limits<Range::_range_type>::max()
MODEL_PARAMETERS = (('offset', 0.0), ('drift', 0.0), ('driftFrequency', 1.0 / 3600.0), ('gaussianNoise', 0.0),
                    ('scaleError', 1.0))


def timer_due(time, period, offset, step):
    """hector's UpdateTimer::checkUpdate: within half a step of offset + a multiple of the period (0: always)."""
    if period == 0:
        return True
    fraction = math.fmod(time - offset + step / 2.0, period)
    return 0.0 <= fraction < step


def sonar_reading(ray_ranges, range_min, range_max, model=None, dt=0.0):
    """Range.range of the raw rays' ranges as Update() makes it (float32 all along, as the message field)."""
    reading = np.float32(min(FLOAT_MAX, float(np.min(ray_ranges)))) if len(ray_ranges) else np.float32(FLOAT_MAX)
    if reading < np.float32(range_max):
        if model is not None:
            reading = np.float32(model.apply((float(reading), 0.0, 0.0), dt)[0])
        reading = min(max(reading, np.float32(range_min)), np.float32(range_max))
    return float(reading)


class HectorSonar(Sensor, libraries=('libhector_gazebo_ros_sonar.so',), sensor_types=('ray',),
                  kind=SensorKind.SONAR, main_topic='range', block='ray'):
    """hector_gazebo_plugins' GazeboRosSonar: the shortest ray through hector's error model, on its own timer."""

    @classmethod
    def load(cls, config, sdf):
        params, what, warnings = sdf.params, sdf.what, config.warnings
        ns = sdf.resolve(sdf.own_namespace() or '')
        topic = params.get('topicName', 'sonar')
        if not topic:
            warnings.append('%s: an empty <topicName>; nothing is published' % what)
            return None
        frame = params.get('frameId')
        if frame is None and params.get('frameName') is not None:
            warnings.append("%s: hector's sonar reads <frameId>, not <frameName>; frame_id /sonar_link, as upstream"
                            % what)
        ray = sdf.spec.ray
        config.frame_id = '/sonar_link' if frame is None else frame
        config.topics['range'] = name_in(ns, topic)
        config.params['fov'] = min(abs(ray.max_angle - ray.min_angle),
                                   abs(ray.vertical_max_angle - ray.vertical_min_angle))
        for name, default in MODEL_PARAMETERS:
            config.params[name] = sdf.number(name, default)
        rate = sdf.number('updateRate', 10.0)
        period = 1.0 / rate if rate > 0.0 else 0.0
        config.params['update_period'] = sdf.number('updatePeriod', period)
        config.params['update_offset'] = sdf.number('updateOffset', 0.0)
        period = config.params['update_period']
        config.rate = 1.0 / period if period > 0 else 0.0  # for the log: step() keeps hector's timer
        return config

    def __init__(self, manager, robot, spec, config, rng=None):
        super().__init__(manager, robot, spec, config)
        self.shape = RayShape(spec.ray)
        p = config.params
        self.period, self.offset = p['update_period'], p['update_offset']
        self.model = ErrorModel(rng or random.Random(),
                                *[(p[name], default, default) for name, default in MODEL_PARAMETERS])
        if not manager.noise_enabled:
            self.model.gaussian_noise, self.model.drift = (0.0,) * 3, (0.0,) * 3
        self.model.reset()
        self.last_update = 0.0
        self._next = self.sim.time
        self.advertise('range', Range, 1)
        sensor_model, _ = hector_reconfigure.config_types()
        server = manager.reconfigure(config.topics['range'], sensor_model,
                                     hector_reconfigure.sensor_model_callback(self.model, scalar=True))
        self._server = _ReconfigureHandle(server)

    def wake_time(self):
        return self._next

    def step(self, time):
        step = self.sim.step_size
        if self.period > 0:  # the next tick: within half a step before offset + k * period
            ticks = math.floor((time - self.offset + step / 2.0) / self.period) + 1
            self._next = self.offset + ticks * self.period - step / 2.0
        if time < self.last_update:  # a world reset: hector's Reset()
            self.last_update = 0.0
            self.model.reset()
        if not timer_due(time, self.period, self.offset, step):
            return
        dt = time - self.last_update if self.last_update != 0.0 else 0.0  # getTimeSinceLastUpdate
        self.last_update = time
        position, orientation = self.mount.pose()
        starts, ends = self.shape.endpoints(position, quaternion_to_matrix(orientation))
        fractions, hit = cast_rays(self.sim.world, starts, ends)
        shape = self.shape
        reading = sonar_reading(shape.ranges(fractions, hit), shape.range_min, shape.range_max, self.model, dt)
        self.publishers['range'].publish(msgs.range_message(
            ros_time(self.manager.rospy.Time, time), self.config.frame_id, ULTRASOUND, self.config.params['fov'],
            shape.range_min, shape.range_max, reading))
        self.meter.tick()

    def close(self):
        super().close()
        self._server.unregister()
