"""libgazebo_ros_camera.so (gazebo_plugins noetic-devel): a camera sensor's sensor_msgs/Image and CameraInfo, and
camera_info_manager's set_camera_info service.

Frames are rendered in a worker process (../sensors/render_worker.py) from the world's poses at the frame's sim time
and published from its reader thread when ready, still stamped with that sim time; without the worker, in the
physics thread within the render budget (../sensors/render.py). Pinhole maths: ../sensors/camera.py.

Parameters: gazebo_ros_camera_utils.py's (topics image_raw and camera_info), updateRate (0): it does not change the
rate frames come at but skips whole frames (../sensors/schedule.py's FrameThrottle), as upstream's OnNewFrame; and
triggerTopicName (image_trigger, which only the triggered cameras subscribe to).
"""
import time as walltime

from sensor_msgs.msg import CameraInfo, Image
from sensor_msgs.srv import SetCameraInfo

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera_utils import CameraUtils
from racebot_sim_bridge.gazebo_plugins.sensor_plugin import SensorKind
from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.camera import PinholeCamera
from racebot_sim_bridge.sensors.config_types import join_topic
from racebot_sim_bridge.sensors.frame_publisher import FramePublisher
from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix
from racebot_sim_bridge.sensors.noise import make_noise
from racebot_sim_bridge.sensors.render import TINY, CameraFrames
from racebot_sim_bridge.sensors.render_worker import FrameBuffers, InFlight
from racebot_sim_bridge.sensors.schedule import FrameThrottle

# Frames of one camera the worker may hold at once. With one, the worker sat idle after each frame
# until the camera's next due time; with two, the next frame already waits in its queue (measured:
# 11.7 -> 12.5 Hz for the 800 x 800 camera). Each frame is still of the sim time it is stamped with.
FRAMES_IN_WORKER = 2
# Frame buffers: those in the worker, one being published and one rendered, waiting for it.
FRAME_BUFFERS = FRAMES_IN_WORKER + 2


def _serialized(msg):
    from io import BytesIO
    buf = BytesIO()
    msg.serialize(buf)
    return buf.getvalue()


class CameraSensor(CameraUtils, libraries=('libgazebo_ros_camera.so',), sensor_types=('camera',),
                   kind=SensorKind.CAMERA, main_topic='image'):
    """gazebo_ros_camera: image + camera_info."""

    @classmethod
    def load_camera(cls, config, sdf, ns):
        config.params['update_rate'] = sdf.number('updateRate', 0.0)
        # gazebo_ros_camera_utils reads it for every camera; only the triggered cameras subscribe to it
        config.params['trigger_topic'] = join_topic(ns, sdf.params.get('triggerTopicName') or 'image_trigger')

    def __init__(self, manager, robot, spec, config):
        super().__init__(manager, robot, spec, config)
        cam = spec.camera
        self.encoding = msgs.image_encoding(cam.format)
        if cam.format not in msgs.IMAGE_ENCODINGS:
            config.warnings.append("sensor '%s': image format %r is not one gazebo_ros_camera knows (L8, L16, R8G8B8, "
                                   "B8G8R8, R16G16B16, BAYER_RGGB8, ...); published as bgr8, as upstream does"
                                   % (spec.name, cam.format))
        self.stored_info = None  # a camera_info set through set_camera_info (camera_info_manager's), else None
        self.camera = PinholeCamera(cam.width, cam.height, cam.horizontal_fov, cam.clip_near, cam.clip_far)
        noise = make_noise(cam.noise_type, cam.noise_mean, cam.noise_stddev, manager.noise_enabled)
        self.frames = CameraFrames(self.camera, noise)  # frames rendered in the physics thread
        # What the worker needs to make this camera's frames (hashable: it keys them by it).
        self.worker_camera = (self.camera.width, self.camera.height, self.camera.hfov, self.camera.near,
                              self.camera.far, noise.mean if noise else 0.0, noise.stddev if noise else None)
        self.buffers = None  # FrameBuffers shared with the worker, made for the first frame it renders
        self.in_worker = InFlight(FRAMES_IN_WORKER)  # frames sent to the worker, not rendered yet
        self.publisher = FramePublisher('camera %s' % spec.name, self._frame_failed)  # the worker's frames
        self.throttle = FrameThrottle(config.params.get('update_rate', 0.0))
        self.advertise('image', Image, 2)
        self.advertise('info', CameraInfo, 2)
        self.service = manager.rospy.Service(config.params['set_camera_info'], SetCameraInfo, self.set_camera_info)

    def _frame_failed(self, message):
        # A frame may still be on its way when its topics close: the world server's shutdown closes the sensors
        # (unregistering their publishers) before rospy's, and rospy's closes the topics. That frame is dropped,
        # as Gazebo's publishers drop theirs once ROS is down, and nothing is logged (soak_short read both as an
        # ERROR: "publish() to an unregistered() handle", "publish() to a closed topic")
        if not (self.closed or self.manager.rospy.is_shutdown()):
            self.manager.rospy.logerr(message)

    def set_camera_info(self, req):
        """camera_info_manager's set_camera_info: the camera_info published from now on (until the model goes).
        Upstream also writes it to ~/.ros/camera_info/<camera>.yaml; racebot keeps it in memory only."""
        from sensor_msgs.srv import SetCameraInfoResponse
        info = req.camera_info
        if (info.width, info.height) not in ((0, 0), (self.camera.width, self.camera.height)):
            return SetCameraInfoResponse(False, 'camera_info is %d x %d; this camera is %d x %d'
                                         % (info.width, info.height, self.camera.width, self.camera.height))
        self.stored_info = info  # one assignment: the publishing thread sees the old or the new one
        return SetCameraInfoResponse(True, 'camera_info stored (in memory: racebot writes no calibration file)')

    def info(self, stamp):
        stored = self.stored_info
        if stored is not None:
            msg = CameraInfo()
            msg.deserialize(_serialized(stored))  # a copy: the stored one is published from two threads
            msg.header.stamp = stamp
            return msg
        p = self.config.params
        return msgs.camera_info(stamp, self.config.frame_id, self.camera, p['baseline'], p['distortion'],
                                self.camera.reported_intrinsics(p.get('focal_length', 0.0), p.get('cx', 0.0),
                                                                p.get('cy', 0.0)))

    def capture(self, time, stamp, wanted, want_depth):
        """A frame of the world at sim `time`, published as `wanted` roles when it is ready: from the
        render worker when there is one, else rendered here within the render budget. A frame
        that cannot be taken is skipped (counted): False, else True (the triggered cameras count on it)."""
        manager = self.manager
        if manager.worker_expected():
            worker = manager.worker
            if not worker.ready or not self.in_worker.take():
                self.meter.skip()  # starting, restarting, or this camera's frames not rendered yet
                return False
            if self.buffers is None:
                self.buffers = FrameBuffers(self.camera.width, self.camera.height, FRAME_BUFFERS)
            slot = self.buffers.take()
            if slot is None:  # every buffer still being rendered or published
                self.in_worker.give_back()
                self.meter.skip()
                return False
            position, orientation = self.mount.pose()
            buffers = self.buffers

            def publish(rgb, depth):
                try:
                    self.publish_frame(stamp, wanted, rgb, depth)
                finally:
                    buffers.give_back(slot)

            def done(rgb, depth):  # on the reader thread: hand the frame to this camera's publisher thread
                self.in_worker.give_back()
                self.publisher.run(lambda: publish(rgb, depth), cancel=lambda: buffers.give_back(slot))

            def failed(reason):
                self.in_worker.give_back()
                buffers.give_back(slot)
                self.meter.skip()
                manager.frame_failed(self, reason)

            if not worker.submit(self.sim.world, manager.snapshot(), self.worker_camera, position,
                                 quaternion_to_matrix(orientation), want_depth, buffers, slot, done, failed):
                self.in_worker.give_back()
                buffers.give_back(slot)
                self.meter.skip()
                return False
            return True
        budget = manager.budget
        if not budget.allow(self):
            self.meter.skip()
            return False
        start = walltime.perf_counter()
        planes = manager.scene_colours().planes
        position, orientation = self.mount.pose()
        rgb, depth = self.frames.make(self.sim.world, TINY, planes, position, quaternion_to_matrix(orientation),
                                      want_depth)
        budget.spend(walltime.perf_counter() - start)
        self.publish_frame(stamp, wanted, rgb, depth)
        return True

    def update(self, time, stamp):
        if not self.listened('image'):
            if self.listened('info'):  # camera_info alone needs no render
                self.publishers['info'].publish(self.info(stamp))
            return
        if not self.throttle.passes(time):  # gazebo_ros_camera's updateRate: skips whole frames
            return
        self.capture(time, stamp, {'image'}, want_depth=False)

    def close(self):
        self.publisher.close()  # frames not yet published are dropped before their topics go
        super().close()
        service, self.service = self.service, None
        if service is not None:
            service.shutdown()
        if self.buffers is not None:
            self.buffers.close()

    def publish_frame(self, stamp, wanted, rgb, depth):
        pubs = self.publishers  # the reader thread may publish while the robot is deleted
        if self.failed or not pubs:
            return
        pubs['image'].publish(msgs.rgb_image(stamp, self.config.frame_id, rgb, self.encoding))
        pubs['info'].publish(self.info(stamp))
        self.meter.tick()
