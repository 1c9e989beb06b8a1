"""What each sensor a robot description declares should publish, read from the description itself.

A corpus row's `sensors` check does not list topics by hand: it reads the URDF the launch put on the
parameter server and derives, per `<sensor>` with a gazebo_ros plugin (and per model-level IMU/GPS
plugin), the topic that plugin advertises and the shape its messages must have, with gazebo_plugins'
own defaults (noetic-devel: gazebo_ros_laser.cpp, gazebo_ros_camera_utils.cpp,
gazebo_ros_openni_kinect.cpp, gazebo_ros_imu_sensor.cpp, gazebo_ros_imu.cpp; velodyne_gazebo_plugins;
hector_gazebo_plugins). It parses on its own, independently of racebot's loader, so a loader bug
cannot hide itself. Pure: no rospy.
"""
import xml.etree.ElementTree as ET

LASER = ('libgazebo_ros_laser.so', 'libgazebo_ros_gpu_laser.so')
CAMERA = ('libgazebo_ros_camera.so',)
DEPTH = ('libgazebo_ros_openni_kinect.so', 'libgazebo_ros_depth_camera.so')
IMU_SENSOR = ('libgazebo_ros_imu_sensor.so',)
VELODYNE = ('libgazebo_ros_velodyne_laser.so', 'libgazebo_ros_velodyne_gpu_laser.so')
# model-level plugins (a <gazebo> block without reference) that are sensors too
MODEL_SENSORS = {
    'libgazebo_ros_imu.so': ('sensor_msgs/Imu', '/default_imu'),
    'libhector_gazebo_ros_imu.so': ('sensor_msgs/Imu', 'imu'),
    'libhector_gazebo_ros_gps.so': ('sensor_msgs/NavSatFix', 'fix'),
}
# Gazebo's image formats (gazebo_ros_camera_utils.cpp) as sensor_msgs encodings
ENCODINGS = {'L8': 'mono8', 'L_INT8': 'mono8', 'L16': 'mono16', 'L_INT16': 'mono16', 'R8G8B8': 'rgb8',
             'RGB_INT8': 'rgb8', 'B8G8R8': 'bgr8', 'BGR_INT8': 'bgr8', 'R16G16B16': 'rgb16', 'RGB_INT16': 'rgb16',
             'BAYER_RGGB8': 'bayer_rggb8', 'BAYER_BGGR8': 'bayer_bggr8', 'BAYER_GBRG8': 'bayer_gbrg8',
             'BAYER_GRBG8': 'bayer_grbg8'}


class Expect(dict):
    """One topic a declared sensor must publish: keys sensor, plugin, topic, type and `fields`, a dict of
    message attribute -> expected value (`len(x)` for a sequence's length, `<=width*height` for a bound)."""


def join(namespace, name):
    """ROS name resolution of a plugin's node handle: an absolute name ignores the namespace."""
    if name.startswith('/'):
        path = name
    else:
        path = '/'.join(p for p in (namespace or '').split('/') + name.split('/') if p)
        path = '/' + path
    return '/' + '/'.join(p for p in path.split('/') if p)


def _text(element, path, default=None):
    found = element.find(path) if element is not None else None
    return found.text.strip() if found is not None and found.text is not None else default


def _number(element, path, default=None):
    text = _text(element, path)
    return float(text) if text is not None else default


def _namespace(plugin, spawn_namespace):
    """A plugin's robotNamespace, else the one spawn_model's -robot_namespace writes into every plugin
    without one (gazebo_ros_api_plugin.cpp, walkChildAddRobotNamespace)."""
    own = _text(plugin, 'robotNamespace')
    return own if own is not None else spawn_namespace


def _laser(sensor, plugin, ns):
    scan = sensor.find('ray/scan/horizontal')
    samples = int(_number(scan, 'samples', 640))
    resolution = _number(scan, 'resolution', 1.0)
    count = int(round(samples * resolution)) if resolution >= 1.0 else samples
    fields = {'len(ranges)': count, 'angle_min': _number(scan, 'min_angle', 0.0),
              'angle_max': _number(scan, 'max_angle', 0.0), 'range_max': _number(sensor, 'ray/range/max')}
    return [Expect(topic=join(ns, _text(plugin, 'topicName', '/world')), type='sensor_msgs/LaserScan',
                   fields={k: v for k, v in fields.items() if v is not None})]


def _image_fields(sensor):
    image = sensor.find('camera/image')
    if image is None:
        image = sensor.find('.//image')
    width, height = int(_number(image, 'width', 320)), int(_number(image, 'height', 240))
    return width, height, ENCODINGS.get(_text(image, 'format', 'R8G8B8'), 'rgb8')


def _camera_image(sensor, plugin, ns, image_default):
    """What every camera plugin shares: (its base, cameraName under the namespace; the image size fields; the
    Expect of its imageTopicName)."""
    width, height, encoding = _image_fields(sensor)
    base = join(ns, _text(plugin, 'cameraName', ''))
    size = {'width': width, 'height': height}
    return base, size, Expect(topic=join(base, _text(plugin, 'imageTopicName', image_default)),
                              type='sensor_msgs/Image', fields=dict(size, encoding=encoding))


def _camera(sensor, plugin, ns):
    base, size, image = _camera_image(sensor, plugin, ns, 'image_raw')
    return [image, Expect(topic=join(base, _text(plugin, 'cameraInfoTopicName', 'camera_info')),
                          type='sensor_msgs/CameraInfo', fields=dict(size))]


def _depth(sensor, plugin, ns):
    base, size, image = _camera_image(sensor, plugin, ns, 'ir/image_raw')
    return [image,
            Expect(topic=join(base, _text(plugin, 'depthImageTopicName', 'depth/image_raw')),
                   type='sensor_msgs/Image', fields=dict(size, encoding='32FC1')),
            Expect(topic=join(base, _text(plugin, 'pointCloudTopicName', 'points')), type='sensor_msgs/PointCloud2',
                   fields=dict(size))]


def _velodyne(sensor, plugin, ns):
    horizontal = int(_number(sensor, 'ray/scan/horizontal/samples', 1))
    vertical = int(_number(sensor, 'ray/scan/vertical/samples', 1))
    return [Expect(topic=join(ns, _text(plugin, 'topicName', '/points')), type='sensor_msgs/PointCloud2',
                   fields={'height': 1, '<=width': horizontal * vertical, 'ring<': vertical})]


def _imu_sensor(sensor, plugin, ns):
    return [Expect(topic=join(ns, _text(plugin, 'topicName', 'imu_data')), type='sensor_msgs/Imu',
                   fields={'finite(orientation)': True})]


KINDS = [(LASER, _laser), (CAMERA, _camera), (DEPTH, _depth), (VELODYNE, _velodyne), (IMU_SENSOR, _imu_sensor)]


def declared(urdf_xml, spawn_namespace=''):
    """(expectations, unchecked): the topics the description's sensors must publish, and the names of
    declared sensors whose plugin this module has no rule for (reported, not failed)."""
    root = ET.fromstring(urdf_xml)
    expects, unchecked = [], []
    for gazebo in root.iter('gazebo'):
        for sensor in gazebo.iter('sensor'):
            plugins = sensor.findall('plugin')
            name = '%s (%s on %s)' % (sensor.get('name'), sensor.get('type'), gazebo.get('reference', '?'))
            rule = None
            for plugin in plugins:
                rule = next((fn for files, fn in KINDS if plugin.get('filename') in files), None)
                if rule:
                    for e in rule(sensor, plugin, _namespace(plugin, spawn_namespace)):
                        e.update(sensor=name, plugin=plugin.get('filename'))
                        expects.append(e)
                    break
            if rule is None and plugins:  # a sensor without a plugin publishes nothing on ROS
                unchecked.append('%s: %s' % (name, ', '.join(p.get('filename', '?') for p in plugins) or 'no plugin'))
        if gazebo.get('reference') is None:
            for plugin in gazebo.findall('plugin'):
                known = MODEL_SENSORS.get(plugin.get('filename'))
                if known:
                    msg_type, default_topic = known
                    ns = _namespace(plugin, spawn_namespace)
                    fields = {'finite(orientation)': True} if msg_type.endswith('Imu') else {}
                    expects.append(Expect(sensor='%s (model plugin on %s)' % (plugin.get('name'),
                                                                             _text(plugin, 'bodyName', '?')),
                                          plugin=plugin.get('filename'), type=msg_type, fields=fields,
                                          topic=join(ns, _text(plugin, 'topicName', default_topic))))
    return expects, unchecked


def compare(fields, observed):
    """The first mismatch between expected `fields` and `observed` (attribute -> value, as the checker
    read it off the message), or None. Angles and ranges agree within 1e-3."""
    for key, want in fields.items():
        if key.startswith('<='):
            got = observed.get(key[2:])
            if got is None or got > want:
                return '%s %s > %s' % (key[2:], got, want)
            continue
        if key.endswith('<'):
            got = observed.get(key[:-1] + '_max')
            if got is not None and got >= want:
                return '%s max %s >= %s' % (key[:-1], got, want)
            continue
        got = observed.get(key)
        if isinstance(want, float):
            if got is None or abs(float(got) - want) > 1e-3:
                return '%s %s != %s' % (key, got, want)
        elif got != want:
            return '%s %s != %s' % (key, got, want)
    return None
