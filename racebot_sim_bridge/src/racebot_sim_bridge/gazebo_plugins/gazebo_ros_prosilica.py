"""libgazebo_ros_prosilica.so (gazebo_plugins noetic-devel): a gazebo_ros_camera with the Prosilica driver's two
modes, chosen by the parameter trigger_mode (searched upwards from the camera's namespace, as searchParam; else
<ns>/<cameraName>/trigger_mode; default streaming), read when the plugin loads and again at each poll.

- streaming: image and camera_info as gazebo_ros_camera (its updateRate throttling too).
- polled: nothing is streamed; polled_camera's GetPolledImage service answers. Upstream advertises it under its
  pollServiceName, a member nothing sets, so at the camera node handle's own name: `<ns>/<cameraName>`. A request
  in another mode fails ("Camera is not in triggered mode"), binning above 1 fails ("Gazebo Prosilica plugin does
  not support binning"), an roi with any field <= 0 means the whole image (so one at x 0 or y 0 too, as upstream);
  the frame is published whole on the camera's image topic, the camera_info of the roi (K and P with cx, cy less
  the offsets, D in upstream's order k1 k2 k3 t1 t2) on its camera_info topic, and the roi's image and camera_info,
  latched, on `<response_namespace>/image_raw` and `/camera_info` under the camera's namespace (polled_camera's
  PublicationServer); the response's stamp is the frame's.
Where racebot differs: upstream hands back the last frame the camera rendered (none until something made the
camera render: a poll alone can wait forever); racebot renders a fresh one at the next physics step, stamped with
its sim time, and answers success false after POLL_TIMEOUT wall seconds without one (a paused world). trigger_mode
changed after loading is seen at the next poll (upstream reads it every frame as well).
"""
from __future__ import annotations

import math
import threading

import numpy as np
from sensor_msgs.msg import CameraInfo, Image

from racebot_sim_bridge.engine.sim_time import ros_time
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_camera import CameraSensor
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import name_in
from racebot_sim_bridge.gazebo_plugins.polled_camera_types import get_polled_image
from racebot_sim_bridge.gazebo_plugins.sensor_plugin import SensorKind
from racebot_sim_bridge.sensors import messages as msgs

POLL_TIMEOUT = 10.0  # wall seconds a poll waits for its frame


class _Poll:
    """One GetPolledImage request waiting for a frame: the physics thread (or the render worker's reader) hands it
    (rgb, stamp), the service thread waits."""

    def __init__(self):
        self.done = threading.Event()
        self.frame = None


class _PollFrame(set):
    """The `wanted` roles of a frame taken for polls (capture hands them back to publish_frame), and those polls."""

    def __init__(self, polls):
        super().__init__(('poll',))
        self.polls = polls


class ProsilicaCameraSensor(CameraSensor, libraries=('libgazebo_ros_prosilica.so',), sensor_types=('camera',),
                            kind=SensorKind.CAMERA):
    """gazebo_ros_prosilica: streaming like gazebo_ros_camera, or polled through GetPolledImage."""

    def __init__(self, manager, robot, spec, config):
        super().__init__(manager, robot, spec, config)
        rospy = manager.rospy
        self.node_namespace = config.params['set_camera_info'].rsplit('/', 1)[0] or '/'
        self.mode_param = self._search_param('trigger_mode')
        self.mode = self._mode()
        rospy.loginfo('%s: trigger_mode %s %s' % (spec.name, self.mode_param, self.mode))
        self._lock = threading.Lock()
        self.polls = []           # _Poll requests no frame was taken for yet
        self.responders = {}      # response image topic -> (image publisher, camera_info publisher), latched
        self.poll_service = None
        if self.mode == 'polled':
            if self.node_namespace == '/':
                config.warnings.append("sensor '%s': polled mode needs a <cameraName> or robotNamespace: upstream "
                                       'advertises the service at the camera\'s namespace, here the root, which '
                                       'ROS refuses; no service' % spec.name)
            else:
                self.GetPolledImage = get_polled_image()
                self.poll_service = rospy.Service(self.node_namespace, self.GetPolledImage, self.poll)
        elif self.mode != 'streaming':
            rospy.logerr('%s: trigger_mode is invalid: %s, using streaming mode' % (spec.name, self.mode))

    def _search_param(self, key):
        """ros::NodeHandle::searchParam from the camera's namespace upwards; `<ns>/key` when none is set."""
        has_param = getattr(self.manager.rospy, 'has_param', None)
        parts = [p for p in self.node_namespace.split('/') if p]
        for depth in range(len(parts), -1, -1):
            name = '/' + '/'.join(parts[:depth] + [key])
            if has_param is not None and has_param(name):
                return name
        return name_in(self.node_namespace, key)

    def _mode(self):
        return str(self.manager.rospy.get_param(self.mode_param, 'streaming'))

    # -- physics thread ------------------------------------------------------------------------
    def wake_time(self):
        return -math.inf if self.polls else super().wake_time()

    def step(self, time):
        with self._lock:
            polls, self.polls = self.polls, []
        if polls and not self.capture(time, ros_time(self.manager.rospy.Time, time), _PollFrame(polls),
                                      want_depth=False):
            with self._lock:
                self.polls[:0] = polls  # the frame could not be taken: the next step tries again
        super().step(time)

    def update(self, time, stamp):
        if self.mode == 'streaming':  # upstream streams only then, even after "using streaming mode"
            super().update(time, stamp)

    def publish_frame(self, stamp, wanted, rgb, depth):
        if not isinstance(wanted, _PollFrame):
            super().publish_frame(stamp, wanted, rgb, depth)
            return
        frame = (np.array(rgb, dtype=np.uint8, copy=True), stamp)  # the worker reuses its buffer
        for poll in wanted.polls:
            poll.frame = frame
            poll.done.set()

    # -- the service (rospy's thread) ----------------------------------------------------------
    def poll(self, req):
        """GazeboRosProsilica::pollCallback behind polled_camera's PublicationServer."""
        response = self.GetPolledImage._response_class()
        self.mode = self._mode()
        if self.mode != 'polled':
            return self._failed(response, 'Camera is not in triggered mode')
        if max(req.binning_x, 1) > 1 or max(req.binning_y, 1) > 1:  # the server makes 0 into 1 first
            return self._failed(response, 'Gazebo Prosilica plugin does not support binning')
        roi = req.roi
        width, height = self.camera.width, self.camera.height
        if roi.x_offset <= 0 or roi.y_offset <= 0 or roi.width <= 0 or roi.height <= 0:
            roi.x_offset, roi.y_offset, roi.width, roi.height = 0, 0, width, height
        if roi.x_offset + roi.width > width or roi.y_offset + roi.height > height:
            return self._failed(response, 'roi %d+%d x %d+%d is outside the %d x %d image (upstream: an OpenCV '
                                'error)' % (roi.x_offset, roi.width, roi.y_offset, roi.height, width, height))
        request = _Poll()
        with self._lock:
            self.polls.append(request)
        self.manager.wake()
        if not request.done.wait(POLL_TIMEOUT) or request.frame is None:
            with self._lock:
                if request in self.polls:
                    self.polls.remove(request)
            return self._failed(response, 'no frame within %g s: the world did not step (paused?)' % POLL_TIMEOUT)
        rgb, stamp = request.frame
        image = msgs.rgb_image(stamp, self.config.frame_id, rgb, self.encoding)
        info = self.roi_info(stamp, roi)
        pubs = self.publishers
        if pubs:  # the plugin may be closing
            pubs['info'].publish(info)
            pubs['image'].publish(image)
        image_pub, info_pub = self._responder(req.response_namespace)
        image_pub.publish(_cropped(image, roi))
        info_pub.publish(info)
        response.success, response.stamp = True, stamp
        return response

    def _failed(self, response, message):
        self.manager.rospy.logerr('Failed to capture requested image, status message: \'%s\'' % message)
        response.success, response.status_message = False, message
        return response

    def _responder(self, response_namespace):
        topic = name_in(self.node_namespace, response_namespace.rstrip('/') + '/image_raw')
        with self._lock:
            if topic not in self.responders:
                rospy = self.manager.rospy
                self.responders[topic] = (
                    rospy.Publisher(topic, Image, queue_size=1, latch=True),
                    rospy.Publisher(topic.rsplit('/', 1)[0] + '/camera_info', CameraInfo, queue_size=1, latch=True))
                rospy.loginfo('Advertising %s' % topic)
            return self.responders[topic]

    def roi_info(self, stamp, roi):
        """pollCallback's camera_info: the roi's size, K and P with the principal point less the offsets."""
        p = self.config.params
        f, cx, cy = self.camera.reported_intrinsics(p.get('focal_length', 0.0), p.get('cx', 0.0), p.get('cy', 0.0))
        k1, k2, t1, t2, k3 = p['distortion']
        cx, cy = cx - roi.x_offset, cy - roi.y_offset
        return CameraInfo(header=msgs.header(stamp, self.config.frame_id), width=roi.width, height=roi.height,
                          distortion_model='plumb_bob', D=[k1, k2, k3, t1, t2],
                          K=[f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0],
                          R=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
                          P=[f, 0.0, cx, -f * p['baseline'], 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0])

    def close(self):
        service, self.poll_service = self.poll_service, None
        if service is not None:
            service.shutdown()
        with self._lock:
            polls, self.polls = self.polls, []
            responders, self.responders = self.responders, {}
        for poll in polls:
            poll.done.set()  # no frame: the waiting service answers success false
        for image_pub, info_pub in responders.values():
            image_pub.unregister()
            info_pub.unregister()
        super().close()


def _cropped(image, roi):
    """The roi of an Image, in its encoding (cv_bridge's copy and cv::Mat roi upstream)."""
    pixel = image.step // image.width
    rows = np.frombuffer(image.data, np.uint8).reshape(image.height, image.step)
    data = np.ascontiguousarray(rows[roi.y_offset:roi.y_offset + roi.height,
                                     roi.x_offset * pixel:(roi.x_offset + roi.width) * pixel])
    return Image(header=image.header, height=roi.height, width=roi.width, encoding=image.encoding,
                 is_bigendian=image.is_bigendian, step=roi.width * pixel, data=data.tobytes())
