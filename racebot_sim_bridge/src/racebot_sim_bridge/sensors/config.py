"""What gazebo_ros's sensor plugins would publish for a URDF <sensor>: kind, topics, frame, rate.

No rospy, no pybullet in this module. `sensor_config(spec)` reads a urdf_model.SensorSpec and the first
<plugin> inside it that the registry (../gazebo_plugins/registry.py) has a sensor class for,
applying each plugin's own defaults and naming rules:

| plugin (filename)                              | kind   | topics                                        |
| gazebo_ros_laser, gazebo_ros_gpu_laser         | laser  | topicName                                     |
| gazebo_ros_camera                              | camera | cameraName/{imageTopicName,cameraInfoTopicName} |
| gazebo_ros_openni_kinect, gazebo_ros_depth_camera | depth | cameraName/{imageTopicName, cameraInfoTopicName,
|     depthImageTopicName, depthImageCameraInfoTopicName, pointCloudTopicName} |
| gazebo_ros_imu_sensor                          | imu    | topicName                                     |
| gazebo_ros_range                               | range  | topicName                                     |
| gazebo_ros_bumper                              | bumper | bumperTopicName                               |
| gazebo_ros_multicamera                         | multicamera | cameraName/{left,right}/{image..., cameraInfo...} |

(the kind is the class's `kind`; the sensor types it may sit in, its `sensor_types`)

Relative topic names resolve in the plugin's namespace as Gazebo sets it: its own <robotNamespace>,
else the spawn request's robot_namespace, else each plugin's default (../gazebo_plugins/plugin_namespace.py has
the rules); absolute ones stay. So the racebot's IMU (topicName imu, no robotNamespace) publishes
/imu when spawn_model runs at the root (it sends '/'), and /<model>/imu for a spawn request with an
empty robot_namespace, as gazebo_ros_imu_sensor does. Frame ids are the plugins': the laser's and
cameras' frameName resolved with the `tf_prefix` parameter of their namespace as tf::resolve does
(laser default /world, i.e. `world`; cameras none), the IMU's frameName as written (it has no
default: without one the sensor is refused, as gazebo_ros_imu_sensor stops). The update rate is the
sensor's <update_rate> (0: every world update, as in Gazebo), throttled by gazebo_ros_imu_sensor's
updateRateHZ; gazebo_ros_camera's updateRate does not change the rate frames come at but skips whole
frames (params['update_rate'], schedule.FrameThrottle), as upstream's OnNewFrame does.
"""
from dataclasses import dataclass, field, replace

from racebot_sim_bridge.gazebo_plugins import PluginKind, library_key
from racebot_sim_bridge.gazebo_plugins.plugin_namespace import sensor_namespace
from racebot_sim_bridge.gazebo_plugins.registry import REGISTRY
from racebot_sim_bridge.kinematics.rotations import as_xyz_rpy, compose
from racebot_sim_bridge.supported_table import WHERE as SUPPORTED_TABLE

class SensorConfigError(ValueError):
    """A sensor block that cannot be simulated as written; the message says why."""


@dataclass
class SensorConfig:
    name: str
    kind: str                       # the sensor class's kind: laser, camera, depth, imu, range, ...
    reference: str                  # the link Gazebo mounts it on (SensorSpec.reference: after lumping)
    frame_id: str
    rate: float                     # Hz of sim time; 0 = every world update
    topics: dict = field(default_factory=dict)   # role -> absolute topic name
    params: dict = field(default_factory=dict)   # kind-specific numbers (cutoffs, baseline, noise)
    warnings: list = field(default_factory=list)
    sensor_class: type = None       # the registered sensor plugin class that runs it


def join_topic(namespace, *parts):
    """Resolves a topic as a ros::NodeHandle in `namespace` would: an absolute last part stays."""
    names = [p for p in parts if p]
    if names and names[-1].startswith('/'):
        return '/' + names[-1].strip('/')
    pieces = [namespace] + names
    return '/' + '/'.join(p.strip('/') for p in pieces if p and p.strip('/'))


def _number(params, key, default, warnings, what):
    text = params.get(key)
    if text is None or text == '':
        return default
    try:
        return float(text)
    except ValueError:
        warnings.append('%s: <%s> %r is not a number; using %g' % (what, key, text, default))
        return default


def sensor_config(spec, spawn_namespace='', model_name='', node_namespace='/'):
    """The SensorConfig of a urdf_model.SensorSpec, or None when none of its plugins publishes to
    ROS (Gazebo would run such a sensor for nobody). Raises SensorConfigError for a plugin that
    does not fit its sensor (e.g. a camera plugin in a ray sensor). spawn_namespace: the spawn
    request's robot_namespace; model_name: the spawned model's name; node_namespace: the world
    server's."""
    plugin, cls = None, None
    for p in spec.plugins:
        cls = REGISTRY.find(p.filename, PluginKind.SENSOR)
        if cls is not None:
            plugin = p
            break
    if plugin is None:
        return None
    kind = cls.kind
    what = "sensor '%s' plugin '%s'" % (spec.name, plugin.name)
    if spec.type not in cls.sensor_types:
        raise SensorConfigError('%s: %s is a %s plugin but the sensor is of type %r (expected %s)'
                                % (what, plugin.filename, kind, spec.type, ' or '.join(cls.sensor_types)))
    if kind in ('camera', 'depth') and spec.camera is None:
        raise SensorConfigError('%s: the sensor has no <camera> block' % what)
    if kind in ('laser', 'range') and spec.ray is None:
        raise SensorConfigError('%s: the sensor has no <ray> block' % what)
    if kind == 'multicamera':
        return _multicamera_config(cls, spec, plugin, what, spawn_namespace, model_name, node_namespace)
    if kind in ('range', 'bumper'):
        return _range_or_bumper_config(cls, spec, plugin, what, spawn_namespace, model_name, node_namespace)
    params = plugin.params
    warnings = []
    own_ns = params.get('robotNamespace')

    def namespace(camera_name=''):
        return sensor_namespace(kind, own_ns, spawn_namespace, model_name, camera_name, node_namespace)
    rate = spec.update_rate
    config = SensorConfig(spec.name, kind, spec.reference, '', rate, warnings=warnings, sensor_class=cls)
    if kind == 'laser':
        topic = params.get('topicName')
        if topic == '':
            return None  # gazebo_ros_laser advertises nothing for an empty <topicName>
        if topic is None:
            topic = '/world'  # gazebo_ros_laser's default, odd as it is
            warnings.append('%s has no <topicName>; publishing on /world as gazebo_ros_laser does' % what)
        if params.get('frameName') is None:
            warnings.append('%s has no <frameName>; frame_id world, as gazebo_ros_laser defaults' % what)
        _frame(config, params, '/world', namespace())  # resolved with <ns>/tf_prefix, as upstream
        config.topics['scan'] = join_topic(namespace(), topic)
    elif kind == 'imu':
        # gazebo_ros_imu_sensor writes frameName as it is into the header, and without one it stops
        # ("missing <frameName>, cannot proceed"): no topic at all.
        if params.get('frameName') is None:
            raise SensorConfigError('%s has no <frameName>: gazebo_ros_imu_sensor cannot proceed without one and '
                                    'publishes nothing; add <frameName>LINK</frameName> to the plugin' % what)
        config.frame_id = params.get('frameName')
        config.topics['imu'] = join_topic(namespace(), params.get('topicName') or 'imu_data')
        throttle = _number(params, 'updateRateHZ', 1.0, warnings, what)
        config.rate = _throttled(rate, throttle)
        config.params['gaussian_noise'] = _number(params, 'gaussianNoise', 0.0, warnings, what)
        config.params['initial_orientation_as_reference'] = \
            (params.get('initialOrientationAsReference') or '').strip().lower() in ('true', '1')
        rpy = (params.get('rpyOffset') or '0 0 0').split()
        try:
            config.params['rpy_offset'] = tuple(float(v) for v in rpy) if len(rpy) == 3 else (0.0, 0.0, 0.0)
        except ValueError:
            config.params['rpy_offset'] = (0.0, 0.0, 0.0)
            warnings.append('%s: <rpyOffset> %r is not three numbers; using 0 0 0' % (what, params.get('rpyOffset')))
    else:
        ns = namespace((params.get('cameraName') or '').strip())
        _frame(config, params, '', ns)  # no default (an empty frame_id), resolved with <ns>/tf_prefix
        config.params['baseline'] = _number(params, 'hackBaseline', 0.0, warnings, what)
        # camera_info's intrinsics as gazebo_ros_camera_utils writes them: 0 (unset) = worked out
        config.params['focal_length'] = _number(params, 'focalLength', 0.0, warnings, what)
        config.params['cx'] = _number(params, 'Cx', 0.0, warnings, what)
        config.params['cy'] = _number(params, 'Cy', 0.0, warnings, what)
        # camera_info D = (k1, k2, t1, t2, k3): the plugin's distortion* values, or with <autoDistortion> the
        # sensor's own <distortion> (gazebo_ros_camera_utils reads the camera's lens model then)
        if (params.get('autoDistortion') or '').strip().lower() in ('true', '1'):
            k1, k2, k3, p1, p2 = spec.camera.distortion
            config.params['distortion'] = [k1, k2, p1, p2, k3]
        else:
            config.params['distortion'] = [_number(params, k, 0.0, warnings, what) for k in
                                           ('distortionK1', 'distortionK2', 'distortionT1', 'distortionT2',
                                            'distortionK3')]
        if kind == 'camera':
            config.params['update_rate'] = _number(params, 'updateRate', 0.0, warnings, what)
            config.topics['image'] = join_topic(ns, params.get('imageTopicName') or 'image_raw')
            config.topics['info'] = join_topic(ns, params.get('cameraInfoTopicName') or 'camera_info')
            config.params['set_camera_info'] = join_topic(ns, 'set_camera_info')  # camera_info_manager's service
            # gazebo_ros_camera_utils reads it for every camera; only the triggered cameras subscribe to it
            config.params['trigger_topic'] = join_topic(ns, params.get('triggerTopicName') or 'image_trigger')
        else:
            config.topics['image'] = join_topic(ns, params.get('imageTopicName') or 'ir/image_raw')
            config.topics['info'] = join_topic(ns, params.get('cameraInfoTopicName') or 'ir/camera_info')
            config.topics['depth'] = join_topic(ns, params.get('depthImageTopicName') or 'depth/image_raw')
            config.topics['depth_info'] = join_topic(ns, params.get('depthImageCameraInfoTopicName')
                                                     or 'depth/camera_info')
            config.topics['points'] = join_topic(ns, params.get('pointCloudTopicName') or 'points')
            config.params['set_camera_info'] = join_topic(ns, 'set_camera_info')  # camera_info_manager's service
            if 'depthImageInfoTopicName' in params and 'depthImageCameraInfoTopicName' not in params:
                warnings.append('%s: <depthImageInfoTopicName> is not read by %s (it reads '
                                '<depthImageCameraInfoTopicName>); depth camera_info goes to %s, as upstream'
                                % (what, plugin.filename, config.topics['depth_info']))
            config.params['cutoff'] = _number(params, 'pointCloudCutoff', 0.4, warnings, what)
            # gazebo_ros_openni_kinect's useDepth16UC1Format (sdformat's bool: true/1, false/0)
            flag = (params.get('useDepth16UC1Format') or 'false').strip().lower()
            config.params['depth_16uc1'] = (flag in ('true', '1')
                                            and library_key(plugin.filename) == 'gazebo_ros_openni_kinect')
            if flag not in ('true', '1', 'false', '0'):
                warnings.append('%s: <useDepth16UC1Format> %r is not true or false; 32FC1 it is' % (what, flag))
            config.params['cutoff_max'] = _number(params, 'pointCloudCutoffMax', 5.0, warnings, what)
        if config.params['focal_length'] or config.params['cx'] or config.params['cy']:
            warnings.append('%s: <focalLength>, <Cx>, <Cy> go into camera_info as set; the image is rendered from '
                            'the image size and horizontal_fov (as in Gazebo)' % what)
        if any(config.params['distortion']) or any(spec.camera.distortion):
            warnings.append('%s: lens distortion is not rendered (see %s); camera_info reports '
                            'the coefficients' % (what, SUPPORTED_TABLE))
    return config


def _throttled(sensor_rate, plugin_rate):
    """The rate a plugin publishes at: the sensor's, or the plugin's own if that is lower."""
    rates = [r for r in (sensor_rate, plugin_rate) if r and r > 0]
    return min(rates) if rates else 0.0


def tf_resolve(prefix, frame):
    """tf::resolve (noetic): a frame with a leading slash loses it and ignores the prefix; else
    prefix/frame (the prefix without a leading slash), or the frame alone without a prefix."""
    if frame.startswith('/'):
        return frame.lstrip('/')
    prefix = prefix.lstrip('/')
    return '%s/%s' % (prefix, frame) if prefix else frame


def _frame(config, params, default, namespace):
    """Sets a range or bumper config's frame as its Load() does: frameName (or `default`) resolved
    with the tf_prefix parameter of the plugin's namespace; the manager reads that parameter
    (config.params['tf_prefix_param']) and calls resolve_frame. Without it: tf_resolve('', frame)."""
    text = params.get('frameName')
    config.params['frame_name'] = (default if text is None else text).strip()
    config.params['tf_prefix_param'] = namespace.rstrip('/') + '/tf_prefix'
    config.frame_id = tf_resolve('', config.params['frame_name'])


def resolve_frame(config, tf_prefix):
    """Gives a config whose plugin reads tf_prefix (config.params['tf_prefix_param']) its frame."""
    config.frame_id = tf_resolve(str(tf_prefix or ''), config.params['frame_name'])


def _range_or_bumper_config(cls, spec, plugin, what, spawn_namespace, model_name, node_namespace):
    """gazebo_ros_range (a ray sensor to sensor_msgs/Range) and gazebo_ros_bumper (a contact sensor
    to gazebo_msgs/ContactsState): parameters and defaults as their Load() reads them."""
    kind = cls.kind
    params = plugin.params
    warnings = []
    ns = sensor_namespace(kind, params.get('robotNamespace'), spawn_namespace, model_name, '', node_namespace)
    if kind == 'bumper':
        if not spec.contact_collisions or not all(spec.contact_collisions):
            raise SensorConfigError("%s: the contact sensor needs <contact><collision>NAME</collision></contact> "
                                    "naming one of its link's collisions" % what)
        config = SensorConfig(spec.name, kind, spec.reference, '', spec.update_rate, warnings=warnings,
                              sensor_class=cls)
        _frame(config, params, 'world', ns)
        config.topics['bumper'] = join_topic(ns, params.get('bumperTopicName') or 'bumper_states')
        config.params['collisions'] = list(spec.contact_collisions)
        return config
    topic = params.get('topicName')
    if topic == '':
        return None  # gazebo_ros_range advertises nothing for an empty <topicName>
    radiation = params.get('radiation')
    if radiation is None:
        radiation = 'ultrasound'
        warnings.append('%s has no <radiation>; ultrasound, as gazebo_ros_range defaults' % what)
    elif radiation not in ('ultrasound', 'infrared'):
        warnings.append("%s: <radiation> %r is neither 'ultrasound' nor 'infrared'; published as INFRARED, as "
                        "gazebo_ros_range does with any text but 'ultrasound'" % (what, radiation))
    if params.get('fov') is None:
        warnings.append('%s has no <fov>; field_of_view 0.05 rad, as gazebo_ros_range defaults' % what)
    config = SensorConfig(spec.name, kind, spec.reference, '', spec.update_rate, warnings=warnings,
                          sensor_class=cls)
    _frame(config, params, '/world', ns)
    config.topics['range'] = join_topic(ns, '/range' if topic is None else topic)
    config.params['radiation'] = radiation
    config.params['fov'] = _number(params, 'fov', 0.05, warnings, what)
    config.params['gaussian_noise'] = _number(params, 'gaussianNoise', 0.0, warnings, what)
    config.params['update_rate'] = _number(params, 'updateRate', 0.0, warnings, what)
    return config


# gazebo_ros_multicamera gives a camera whose name holds 'left' the namespace suffix /left and no
# baseline, one whose name holds 'right' /right and the plugin's hackBaseline (P[3] = -f * it).
STEREO_SIDES = (('left', False), ('right', True))


def _multicamera_config(cls, spec, plugin, what, spawn_namespace, model_name, node_namespace):
    """A SensorConfig of kind 'multicamera' whose params['parts'] are (camera SensorSpec, camera
    SensorConfig) pairs: each <camera> as the gazebo_ros_camera that gazebo_ros_multicamera makes
    of it, under <cameraName>/left or <cameraName>/right, posed at the sensor's pose + its own."""
    if not spec.cameras:
        raise SensorConfigError('%s: the multicamera sensor has no <camera> block' % what)
    warnings = []
    parts = []
    camera_name = (plugin.params.get('cameraName') or '').strip()
    for camera in spec.cameras:
        side = next(((name, baseline) for name, baseline in STEREO_SIDES if name in camera.name), None)
        if side is None:
            warnings.append("%s: camera '%s' has neither 'left' nor 'right' in its name, so "
                            'gazebo_ros_multicamera publishes nothing for it' % (what, camera.name))
            continue
        params = dict(plugin.params, cameraName='%s/%s' % (camera_name, side[0]))
        params['hackBaseline'] = (plugin.params.get('hackBaseline') or '0') if side[1] else '0'
        part_spec = replace(spec, type='camera', camera=camera, cameras=[camera],
                            pose=as_xyz_rpy(compose(spec.pose, camera.pose)),
                            plugins=[replace(plugin, filename='libgazebo_ros_camera.so', params=params)])
        part = sensor_config(part_spec, spawn_namespace, model_name, node_namespace)
        if part is not None:
            parts.append((part_spec, part))
    config = SensorConfig(spec.name, cls.kind, spec.reference, '', spec.update_rate, warnings=warnings,
                          sensor_class=cls)
    for part_spec, part in parts:
        config.topics.update({'%s/%s' % (part_spec.camera.name, role): topic for role, topic in part.topics.items()})
        warnings.extend(w for w in part.warnings if w not in warnings)  # both sides share the plugin's
        part.warnings = []
    if parts:
        config.frame_id = parts[0][1].frame_id
    config.params['parts'] = parts
    return config
