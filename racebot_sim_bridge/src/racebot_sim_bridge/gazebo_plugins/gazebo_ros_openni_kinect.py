"""libgazebo_ros_openni_kinect.so and libgazebo_ros_depth_camera.so (gazebo_plugins noetic-devel): a depth
sensor's rgb image, depth image, point cloud and their camera_infos, on the camera's rendering (gazebo_ros_camera.py).

Parameters: gazebo_ros_camera_utils.py's (topics ir/image_raw and ir/camera_info; updateRate throttles nothing here:
every frame is published), depthImageTopicName (depth/image_raw), depthImageCameraInfoTopicName (depth/camera_info; the
often written depthImageInfoTopicName is not read: warned), pointCloudTopicName (points), pointCloudCutoff (0.4 m),
pointCloudCutoffMax (5 m), useDepth16UC1Format (false; openni_kinect's only).
"""
from sensor_msgs.msg import CameraInfo, Image, PointCloud2

from racebot_sim_bridge.description.plugin_library import library_key
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera import CameraSensor
from racebot_sim_bridge.gazebo_plugins.sensor_plugin import SensorKind
from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.camera import mask_depth
from racebot_sim_bridge.sensors.config_types import join_topic


class DepthCameraSensor(CameraSensor,
                        libraries=('libgazebo_ros_openni_kinect.so', 'libgazebo_ros_depth_camera.so'),
                        sensor_types=('depth',), kind=SensorKind.DEPTH, main_topic='depth'):
    """gazebo_ros_openni_kinect: rgb image, depth image (32FC1 m), point cloud, two camera_infos.
    Depth is worked out only while its depth image or point cloud has a subscriber."""
    image_topic = 'ir/image_raw'
    info_topic = 'ir/camera_info'

    @classmethod
    def load_camera(cls, config, sdf, ns):
        params, what, warnings = sdf.params, sdf.what, config.warnings
        config.topics['depth'] = join_topic(ns, params.get('depthImageTopicName') or 'depth/image_raw')
        config.topics['depth_info'] = join_topic(ns, params.get('depthImageCameraInfoTopicName')
                                                 or 'depth/camera_info')
        config.topics['points'] = join_topic(ns, params.get('pointCloudTopicName') or 'points')
        if 'depthImageInfoTopicName' in params and 'depthImageCameraInfoTopicName' not in params:
            warnings.append('%s: <depthImageInfoTopicName> is not read by %s (it reads '
                            '<depthImageCameraInfoTopicName>); depth camera_info goes to %s, as upstream'
                            % (what, sdf.plugin.filename, config.topics['depth_info']))
        config.params['cutoff'] = sdf.number('pointCloudCutoff', 0.4)
        # gazebo_ros_openni_kinect's useDepth16UC1Format (sdformat's bool: true/1, false/0)
        flag = (params.get('useDepth16UC1Format') or 'false').strip().lower()
        config.params['depth_16uc1'] = (flag in ('true', '1')
                                        and library_key(sdf.plugin.filename) == 'gazebo_ros_openni_kinect')
        if flag not in ('true', '1', 'false', '0'):
            warnings.append('%s: <useDepth16UC1Format> %r is not true or false; 32FC1 it is' % (what, flag))
        config.params['cutoff_max'] = sdf.number('pointCloudCutoffMax', 5.0)

    def __init__(self, manager, robot, spec, config):
        super().__init__(manager, robot, spec, config)
        self.advertise('depth', Image, 2)
        self.advertise('depth_info', CameraInfo, 2)
        self.advertise('points', PointCloud2, 2)
        self.rays = None  # per-pixel rays of the point cloud, made when first needed

    def update(self, time, stamp):
        wanted = {role for role in ('image', 'depth', 'points') if self.listened(role)}
        if not wanted:
            for role in ('info', 'depth_info'):
                if self.listened(role):
                    self.publishers[role].publish(self.info(stamp))
            return
        self.capture(time, stamp, wanted, want_depth=bool(wanted & {'depth', 'points'}))

    def publish_frame(self, stamp, wanted, rgb, depth):
        pubs = self.publishers
        if self.failed or not pubs:
            return
        if 'points' in wanted and self.rays is None:
            self.rays = self.camera.rays_optical()
        for role, msg in frame_messages(self.camera, self.config.params, self.config.frame_id, self.encoding,
                                        self.rays, stamp, wanted, rgb, depth):
            pubs[role].publish(msg)
        for role in ('info', 'depth_info'):
            pubs[role].publish(self.info(stamp))
        self.meter.tick()


def frame_messages(camera, params, frame_id, encoding, rays, stamp, wanted, rgb, depth):
    """[(role, message)] of one frame, in the order publish_frame sends them: the `wanted` roles of 'depth' (the
    depth image), 'points' (the cloud; `rays`: camera.rays_optical()) and 'image'. `params`: the sensor config's
    (cutoff, cutoff_max, depth_16uc1). Also what make bench's camera budget times (tools/bench/camera_budget.py)."""
    out = []
    if depth is not None and wanted & {'depth', 'points'}:
        depth = mask_depth(depth, params['cutoff'], params['cutoff_max'])
        if 'depth' in wanted:
            out.append(('depth', msgs.depth_image(stamp, frame_id, depth, params.get('depth_16uc1', False))))
        if 'points' in wanted:
            out.append(('points', msgs.point_cloud(stamp, frame_id, camera.points(depth, rays), rgb)))
    if 'image' in wanted:
        out.append(('image', msgs.rgb_image(stamp, frame_id, rgb, encoding)))
    return out
