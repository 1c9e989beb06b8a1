"""gazebo_ros_triggered_camera and gazebo_ros_triggered_multicamera on a real Simulator (PyBullet DIRECT, frames
rendered in the physics thread as test_sensor_plugins_sim's cameras) with the rospy stand-in: no frame before a
trigger whatever the sensor's rate, exactly one per trigger after it, and a multicamera's trigger of either side
giving one stereo pair."""
import time

import numpy as np
import pytest
from std_msgs.msg import Empty

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_plugins.sensor_manager import SensorManager

from model_plugin_sim import PluginRospy
from fakes import FakeLog, NullIO
from sensors_sim import listen, run
from camera_worlds import CAMERA, WORLD

ROBOT = """<robot name="cam_bot">
 <link name="base_link"><inertial><mass value="1.0"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
  </inertial><collision><origin xyz="0 0 0.05"/><geometry><box size="0.3 0.3 0.1"/></geometry></collision></link>
 <link name="cam_link"><inertial><mass value="0.01"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0"
  izz="1e-6"/></inertial></link>
 <joint name="cam_joint" type="fixed"><parent link="base_link"/><child link="cam_link"/><origin xyz="0.1 0 0.3"/>
 </joint>
 <gazebo reference="cam_link">
  <sensor type="camera" name="shot">
   <update_rate>2</update_rate>%s
   <plugin name="shot_controller" filename="libgazebo_ros_triggered_camera.so">
    <cameraName>shot</cameraName><frameName>cam_link</frameName><updateRate>1</updateRate>
   </plugin>
  </sensor>
  <sensor type="multicamera" name="pair">
   <update_rate>2</update_rate>%s%s
   <plugin name="pair_controller" filename="libgazebo_ros_triggered_multicamera.so">
    <cameraName>pair</cameraName><frameName>cam_link</frameName><hackBaseline>0.07</hackBaseline>
   </plugin>
  </sensor>
 </gazebo>
</robot>""" % (CAMERA % ('shot', 0), CAMERA % ('left', 0.035), CAMERA % ('right', -0.035))
SIDES = ('/pair/left/image_raw', '/pair/right/image_raw')


def make(tmp_path, worker=False):
    path = tmp_path / 'box.world'
    path.write_text(WORLD)
    sim = Simulator(sdf_reader.load_world(str(path)), NullIO(), FakeLog(), lambda path: None)
    fake = PluginRospy({'~sensors/report_period': 0, '~sensors/render_budget': 1.0, '~sensors/noise': False,
                        '~sensors/render_worker': worker, '~sensors/renderer': 'tiny'})
    manager = SensorManager(fake, sim)
    robot = sim.spawn_urdf('cam_bot', ROBOT, '/', (0.0, 0.0, 0.0))
    frame = robot.body.com_pose_for_frame((0.0, 0.0, 0.0), (0, 0, 0, 1))
    robot.body.set_pose(frame.position, frame.orientation)
    return sim, fake, manager


@pytest.fixture
def world(tmp_path):
    sim, fake, _ = make(tmp_path)
    yield sim, fake
    sim.close()


def images(fake, topic):
    return fake.publishers[topic].messages


def trigger(fake, topic, times=1):
    for _ in range(times):
        fake.subscribers[topic](Empty())


def test_no_frame_before_a_trigger_and_exactly_one_after_each(world):
    sim, fake = world
    assert {'/shot/image_trigger', '/pair/left/image_trigger', '/pair/right/image_trigger'} <= set(fake.subscribers)
    listen(fake, '/shot/image_raw', '/shot/camera_info')
    run(sim, 1.0)  # the sensor's update_rate is 2 Hz: a camera would have published twice by now
    assert images(fake, '/shot/image_raw') == [] and images(fake, '/shot/camera_info') == []
    trigger(fake, '/shot/image_trigger')
    before = sim.time
    run(sim, 0.5)
    shots = images(fake, '/shot/image_raw')
    assert len(shots) == 1 and len(images(fake, '/shot/camera_info')) == 1
    # the next step's frame, not the next 2 Hz update: upstream enables the camera at rate 0 when triggered
    assert shots[0].header.stamp.to_sec() == pytest.approx(before + sim.step_size, abs=1e-9)
    pixels = np.frombuffer(shots[0].data, np.uint8).reshape(48, 64, 3)
    assert (shots[0].encoding, shots[0].header.frame_id) == ('rgb8', 'cam_link')
    assert pixels.std() > 5.0  # the box on the ground, not an empty frame
    trigger(fake, '/shot/image_trigger', 3)
    run(sim, 0.5)
    stamps = [m.header.stamp.to_sec() for m in images(fake, '/shot/image_raw')]
    assert len(stamps) == 4 and len(set(stamps)) == 4  # one frame per trigger, each at its own step
    run(sim, 1.0)
    assert len(images(fake, '/shot/image_raw')) == 4


def test_a_trigger_nobody_listens_to_is_used_up(world):
    sim, fake = world
    trigger(fake, '/shot/image_trigger', 2)
    run(sim, 0.1)
    listen(fake, '/shot/image_raw')
    run(sim, 0.5)
    assert images(fake, '/shot/image_raw') == []
    trigger(fake, '/shot/image_trigger')
    run(sim, 0.1)
    assert len(images(fake, '/shot/image_raw')) == 1


def test_a_trigger_of_either_side_gives_one_stereo_pair(world):
    sim, fake = world
    listen(fake, *SIDES)
    run(sim, 1.0)
    assert [len(images(fake, t)) for t in SIDES] == [0, 0]
    trigger(fake, '/pair/left/image_trigger')
    run(sim, 0.3)
    assert [len(images(fake, t)) for t in SIDES] == [1, 1]  # one parent sensor: both cameras render
    left, right = (images(fake, t)[0] for t in SIDES)
    assert left.header.stamp == right.header.stamp
    assert not np.array_equal(np.frombuffer(left.data, np.uint8), np.frombuffer(right.data, np.uint8))
    info = fake.publishers['/pair/right/camera_info'].messages[-1]
    assert info.P[3] == pytest.approx(-64 / (2 * np.tan(0.5)) * 0.07)
    trigger(fake, '/pair/left/image_trigger')
    trigger(fake, '/pair/right/image_trigger')
    run(sim, 0.3)
    assert [len(images(fake, t)) for t in SIDES] == [2, 2]  # both at once: one render serves both
    trigger(fake, '/pair/right/image_trigger', 2)
    run(sim, 0.3)
    assert [len(images(fake, t)) for t in SIDES] == [4, 4]
    assert images(fake, '/shot/image_raw') == []  # the other sensor's trigger is its own


def test_with_the_render_worker_triggers_wait_for_it_and_each_gives_one_frame(tmp_path):
    """The default path: frames rendered in the worker process, published from its reader thread. Triggers sent
    before the worker is up are kept (the frames it cannot take yet are skipped, not the triggers)."""
    sim, fake, manager = make(tmp_path, worker=True)
    try:
        listen(fake, '/shot/image_raw')
        trigger(fake, '/shot/image_trigger', 3)
        shots = images(fake, '/shot/image_raw')
        deadline = time.monotonic() + 90.0  # wall time for a shared machine, not a speed assertion
        while len(shots) < 3:
            assert time.monotonic() < deadline, 'timed out waiting for three frames'
            run(sim, 0.01)
            time.sleep(0.002)
        assert manager.worker is not None and manager.worker.ready
        for _ in range(50):  # the worker's frames of the three triggers are all in; no fourth comes
            run(sim, 0.01)
            time.sleep(0.002)
        assert len(shots) == 3 and len({m.header.stamp for m in shots}) == 3
        assert np.frombuffer(shots[-1].data, np.uint8).std() > 5.0
    finally:
        manager.close()
        sim.close()
