"""libgazebo_ros_openni_kinect.so and libgazebo_ros_depth_camera.so (gazebo_plugins noetic-devel): a depth
sensor's rgb image, depth image, point cloud and their camera_infos, on the camera's rendering (gazebo_ros_camera.py).
"""
from sensor_msgs.msg import CameraInfo, Image, PointCloud2

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera import CameraSensor
from racebot_sim_bridge.gazebo_plugins.sensor_plugin import SensorKind
from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.camera import mask_depth


class DepthCameraSensor(CameraSensor,
                        libraries=('libgazebo_ros_openni_kinect.so', 'libgazebo_ros_depth_camera.so'),
                        sensor_types=('depth',), kind=SensorKind.DEPTH, main_topic='depth'):
    """gazebo_ros_openni_kinect: rgb image, depth image (32FC1 m), point cloud, two camera_infos.
    Depth is worked out only while its depth image or point cloud has a subscriber."""

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
