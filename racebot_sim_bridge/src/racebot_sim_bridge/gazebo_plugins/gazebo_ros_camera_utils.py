"""gazebo_ros_camera_utils (gazebo_plugins noetic-devel): what every gazebo_ros camera plugin reads the same way
(GazeboRosCameraUtils::Load), for gazebo_ros_camera, the triggered and prosilica cameras, each camera of the
multicameras, and gazebo_ros_openni_kinect / depth_camera.

Parameters: robotNamespace and cameraName (the node handle's namespace: robotNamespace/cameraName, as
plugin_namespace.py resolves it), frameName (no default: an empty frame_id) resolved with the tf_prefix parameter
of that namespace as tf::resolve, imageTopicName and cameraInfoTopicName (each plugin's defaults), hackBaseline
(0: P[3] = -f * it), focalLength, Cx, Cy (0, unset: worked out from the image size and horizontal_fov;
camera_info reports them as set, the image is rendered without them, warned), distortionK1, K2, K3, T1, T2
(camera_info's D = k1 k2 t1 t2 k3), or with autoDistortion the sensor's own <distortion> (not rendered either:
warned). camera_info_manager's set_camera_info service in the same namespace.
"""
from racebot_sim_bridge.gazebo_plugins.sensor_plugin import Sensor
from racebot_sim_bridge.sensors.config_types import join_topic, set_frame
from racebot_sim_bridge.supported_table import WHERE as SUPPORTED_TABLE

DISTORTION_KEYS = ('distortionK1', 'distortionK2', 'distortionT1', 'distortionT2', 'distortionK3')


class CameraUtils(Sensor):
    """GazeboRosCameraUtils: the camera plugins' shared loading. A camera plugin gives its topics' defaults and reads
    its own parameters in load_camera()."""
    block = 'camera'
    counts_frames = True
    image_topic = 'image_raw'     # imageTopicName's default
    info_topic = 'camera_info'    # cameraInfoTopicName's default

    @classmethod
    def load(cls, config, sdf):
        params, what, p = sdf.params, sdf.what, config.params
        ns = sdf.namespace(cls.kind, (params.get('cameraName') or '').strip())
        set_frame(config, params, '', ns)  # no default (an empty frame_id), resolved with <ns>/tf_prefix
        p['baseline'] = sdf.number('hackBaseline', 0.0)
        # camera_info's intrinsics as gazebo_ros_camera_utils writes them: 0 (unset) = worked out
        p['focal_length'] = sdf.number('focalLength', 0.0)
        p['cx'] = sdf.number('Cx', 0.0)
        p['cy'] = sdf.number('Cy', 0.0)
        # camera_info D = (k1, k2, t1, t2, k3): the plugin's distortion* values, or with <autoDistortion> the
        # sensor's own <distortion> (gazebo_ros_camera_utils reads the camera's lens model then)
        if (params.get('autoDistortion') or '').strip().lower() in ('true', '1'):
            k1, k2, k3, p1, p2 = sdf.spec.camera.distortion
            p['distortion'] = [k1, k2, p1, p2, k3]
        else:
            p['distortion'] = [sdf.number(k, 0.0) for k in DISTORTION_KEYS]
        config.topics['image'] = join_topic(ns, params.get('imageTopicName') or cls.image_topic)
        config.topics['info'] = join_topic(ns, params.get('cameraInfoTopicName') or cls.info_topic)
        p['set_camera_info'] = join_topic(ns, 'set_camera_info')  # camera_info_manager's service
        cls.load_camera(config, sdf, ns)
        if p['focal_length'] or p['cx'] or p['cy']:
            config.warnings.append('%s: <focalLength>, <Cx>, <Cy> go into camera_info as set; the image is rendered '
                                   'from the image size and horizontal_fov (as in Gazebo)' % what)
        if any(p['distortion']) or any(sdf.spec.camera.distortion):
            config.warnings.append('%s: lens distortion is not rendered (see %s); camera_info reports '
                                   'the coefficients' % (what, SUPPORTED_TABLE))
        return config

    @classmethod
    def load_camera(cls, config, sdf, ns):
        """The camera plugin's own parameters, read after gazebo_ros_camera_utils' (`ns`: the camera's namespace)."""
