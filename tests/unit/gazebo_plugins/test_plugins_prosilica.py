"""gazebo_ros_prosilica on a real Simulator (PyBullet DIRECT, frames rendered in the physics thread): streaming as
gazebo_ros_camera; in polled mode nothing streamed and polled_camera's GetPolledImage (upstream's md5 sums) answered
with a frame rendered at the next step, its roi cropped and published latched under the response namespace, the
roi's camera_info with the principal point moved, upstream's refusals."""
import threading

import numpy as np
import pytest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_plugins.polled_camera_types import get_polled_image
from racebot_sim_bridge.gazebo_plugins.sensor_manager import SensorManager

from model_plugin_sim import PluginRospy
from camera_worlds import CAMERA, WORLD
from fakes import FakeLog, FakePublisher, NullIO
from sensors_sim import listen, run

ROBOT = """<robot name="cam_bot">
 <link name="base_link"><inertial><mass value="1.0"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
  </inertial><collision><origin xyz="0 0 0.05"/><geometry><box size="0.3 0.3 0.1"/></geometry></collision></link>
 <gazebo reference="base_link">
  <sensor type="camera" name="prosilica_sensor">
   <pose>0.1 0 0.3 0 0 0</pose><update_rate>10</update_rate>%s
   <plugin name="prosilica_controller" filename="libgazebo_ros_prosilica.so">
    <cameraName>prosilica</cameraName><frameName>prosilica_optical</frameName><hackBaseline>0.1</hackBaseline>
    <distortionK1>0.1</distortionK1><distortionK3>0.3</distortionK3><distortionT1>0.01</distortionT1>
   </plugin>
  </sensor>
 </gazebo>
</robot>""" % (CAMERA % ('cam', 0))
# upstream's sums (Debian's python3-polled-camera 1.12.0, image_common noetic)
UPSTREAM_MD5 = ('1f3fb0d09d6e1c72d4a7eeb9822d9030', 'c77ed43e530fd48e9e7a2a93845e154c',
                'dbf1f851bc511800e6129ccd5a3542ab')


class PollRospy(PluginRospy):
    """PluginRospy whose publishers may be latched (polled_camera's responses are)."""

    def Publisher(self, topic, msg_class, queue_size=None, latch=False):
        assert queue_size
        self.publishers[topic] = FakePublisher(topic)
        self.publishers[topic].latch = latch
        return self.publishers[topic]


def make(tmp_path, params):
    path = tmp_path / 'box.world'
    path.write_text(WORLD)
    sim = Simulator(sdf_reader.load_world(str(path)), NullIO(), FakeLog(), lambda path: None)
    fake = PollRospy(dict({'~sensors/report_period': 0, '~sensors/render_budget': 1.0, '~sensors/noise': False,
                           '~sensors/render_worker': False}, **params))
    SensorManager(fake, sim)
    robot = sim.spawn_urdf('cam_bot', ROBOT, '/', (0.0, 0.0, 0.0))
    frame = robot.body.com_pose_for_frame((0.0, 0.0, 0.0), (0, 0, 0, 1))
    robot.body.set_pose(frame.position, frame.orientation)
    return sim, fake


def request(fake, sim, namespace='poll', roi=(8, 4, 32, 24), binning=(0, 0)):
    """Calls the service from another thread, as rospy would, while the world steps."""
    req = get_polled_image()._request_class(response_namespace=namespace, binning_x=binning[0], binning_y=binning[1])
    req.roi.x_offset, req.roi.y_offset, req.roi.width, req.roi.height = roi
    out = {}
    caller = threading.Thread(target=lambda: out.setdefault('response', fake.services['/prosilica'](req)))
    caller.start()
    while caller.is_alive():
        run(sim, 0.01)
        caller.join(0.001)
    return out['response']


def test_the_service_type_is_upstreams():
    srv = get_polled_image()
    assert (srv._md5sum, srv._request_class._md5sum, srv._response_class._md5sum) == UPSTREAM_MD5
    assert srv._type == 'polled_camera/GetPolledImage'


def test_streaming_by_default_as_a_camera(tmp_path):
    sim, fake = make(tmp_path, {})
    try:
        assert '/prosilica' not in fake.services and '/prosilica/set_camera_info' in fake.services
        listen(fake, '/prosilica/image_raw')
        run(sim, 0.35)
        images = fake.publishers['/prosilica/image_raw'].messages
        assert len(images) == 4 and images[0].header.frame_id == 'prosilica_optical'  # 10 Hz from t = 0
    finally:
        sim.close()


def test_polled_mode_answers_with_the_roi_of_a_fresh_frame(tmp_path):
    sim, fake = make(tmp_path, {'/trigger_mode': 'polled'})  # searchParam finds it above /prosilica
    try:
        listen(fake, '/prosilica/image_raw', '/prosilica/camera_info')
        run(sim, 0.5)
        assert fake.publishers['/prosilica/image_raw'].messages == []  # polled: nothing streamed
        before = sim.time
        response = request(fake, sim)
        assert response.success and response.stamp.to_sec() == pytest.approx(before + sim.step_size, abs=1e-9)
        full = fake.publishers['/prosilica/image_raw'].messages
        assert len(full) == 1 and (full[0].width, full[0].height) == (64, 48)  # the whole frame, on the camera's
        roi_image = fake.publishers['/prosilica/poll/image_raw']
        roi_info = fake.publishers['/prosilica/poll/camera_info']
        assert roi_image.latch and roi_info.latch
        crop = roi_image.messages[-1]
        assert (crop.width, crop.height, crop.encoding, crop.step) == (32, 24, 'rgb8', 96)
        whole = np.frombuffer(full[0].data, np.uint8).reshape(48, 64, 3)
        assert np.array_equal(np.frombuffer(crop.data, np.uint8).reshape(24, 32, 3), whole[4:28, 8:40])
        assert crop.header.stamp == response.stamp
        info = roi_info.messages[-1]
        f = 64 / (2 * np.tan(0.5))
        assert (info.width, info.height) == (32, 24)
        assert info.K == pytest.approx([f, 0, 32.5 - 8, 0, f, 24.5 - 4, 0, 0, 1])  # cx = (w + 1) / 2, less the offset
        assert info.P[3] == pytest.approx(-f * 0.1)
        assert list(info.D) == pytest.approx([0.1, 0.0, 0.3, 0.01, 0.0])  # upstream's order: k1 k2 k3 t1 t2
        assert fake.publishers['/prosilica/camera_info'].messages[-1].width == 32  # the roi's, as upstream
        run(sim, 0.5)
        assert len(fake.publishers['/prosilica/image_raw'].messages) == 1  # one frame per poll
    finally:
        sim.close()


def test_polled_mode_refusals_and_the_whole_image_for_an_roi_at_the_edge(tmp_path):
    sim, fake = make(tmp_path, {'/prosilica/trigger_mode': 'polled'})
    try:
        refused = request(fake, sim, binning=(2, 1))
        assert not refused.success and refused.status_message == 'Gazebo Prosilica plugin does not support binning'
        whole = request(fake, sim, namespace='/snap', roi=(0, 4, 32, 24))  # x_offset 0: upstream takes it all
        assert whole.success
        assert (fake.publishers['/snap/image_raw'].messages[-1].width,
                fake.publishers['/snap/camera_info'].messages[-1].K[2]) == (64, 32.5)
        fake.params['/prosilica/trigger_mode'] = 'streaming'
        moved = request(fake, sim)
        assert not moved.success and moved.status_message == 'Camera is not in triggered mode'
        listen(fake, '/prosilica/image_raw')
        count = len(fake.publishers['/prosilica/image_raw'].messages)
        run(sim, 0.3)
        assert len(fake.publishers['/prosilica/image_raw'].messages) == count + 3  # streaming now, at 10 Hz
    finally:
        sim.close()
