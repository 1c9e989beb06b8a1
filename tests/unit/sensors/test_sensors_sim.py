"""SensorManager on a real Simulator (PyBullet DIRECT, the room world, the racebot from its xacro)
with a stand-in for rospy: no master. Checks what the sensors publish against the world's
geometry, the pinhole model and physics, and that sensors nobody listens to cost nothing."""
import math

import numpy as np
import pytest

from racebot_sim_bridge.kinematics import rotations
from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.gazebo_plugins import gazebo_ros_laser, gazebo_ros_range
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_imu_sensor import ImuSensor
from racebot_sim_bridge.sensors import render
from racebot_sim_bridge.gazebo_plugins.sensor_manager import SensorManager
from racebot_sim_bridge.engine.simulator import Simulator

from sensors_sim import ROOM, add_red_box, listen, make_world, run, sensor_of
from fakes import FakeLog, FakeRospy, NullIO
import sensors_geometry  # tests/integration: the rostest's own geometry, shared


@pytest.fixture
def world(racebot_xml):
    sim, fake, manager, robot = make_world(racebot_xml)
    yield sim, fake, manager, robot
    sim.close()


def test_every_sensor_block_becomes_its_topics(world):
    sim, fake, manager, robot = world
    assert sorted(fake.publishers) == sorted([
        '/scan', '/imu', '/rrbot/camera1/image_raw', '/rrbot/camera1/camera_info',
        '/real_sense/rgb/image_raw', '/real_sense/rgb/camera_info', '/real_sense/depth/image_raw',
        '/real_sense/depth/camera_info', '/real_sense/depth/points'])


def test_nobody_listening_costs_nothing(world, monkeypatch):
    sim, fake, manager, robot = world
    calls = []
    for plugin in (gazebo_ros_laser, gazebo_ros_range):
        monkeypatch.setattr(plugin, 'cast_rays', lambda *a: calls.append('ray'))
    monkeypatch.setattr(render, 'render', lambda *a: calls.append('render'))
    run(sim, 0.5)
    assert calls == []
    assert all(not p.messages for p in fake.publishers.values())
    assert manager.worker is None  # no render worker started either


def test_scan_matches_the_room_geometry(world):
    sim, fake, manager, robot = world
    listen(fake, '/scan')
    run(sim, 1.0)
    scans = fake.publishers['/scan'].messages
    assert len(scans) == pytest.approx(40, abs=1)  # 40 Hz of sim time
    scan = scans[-1]
    assert len(scan.ranges) == 1081 and scan.header.frame_id == 'lidar'
    assert scan.angle_increment == pytest.approx((scan.angle_max - scan.angle_min) / 1080)
    assert (scan.time_increment, scan.scan_time) == (0.0, 0.0)
    assert scan.header.stamp.to_sec() == pytest.approx(1.0, abs=1e-6)  # the sim time it was taken at
    position, orientation = sensor_of(manager, 'laser').mount.pose()
    yaw = math.atan2(2 * (orientation[3] * orientation[2] + orientation[0] * orientation[1]),
                     1 - 2 * (orientation[1] ** 2 + orientation[2] ** 2))
    expected = sensors_geometry.expected_scan(str(ROOM), position, yaw, scan.angle_min, scan.angle_increment, 1081)
    checked, bad = sensors_geometry.compare(scan.ranges, expected, scan.range_min, scan.range_max, 0.03)
    assert checked > 1000 and not bad, bad[:10]


def test_set_camera_info_replaces_the_published_camera_info(world):
    """camera_info_manager's set_camera_info, as gazebo_ros_camera offers it under the camera's namespace."""
    from sensor_msgs.msg import CameraInfo
    from sensor_msgs.srv import SetCameraInfoRequest
    sim, fake, manager, robot = world
    handler = fake.services['/rrbot/camera1/set_camera_info']
    service = '/rrbot/camera1/set_camera_info'
    camera = next(s for s in manager._active if s.config.params.get('set_camera_info') == service)
    calibrated = CameraInfo(width=camera.camera.width, height=camera.camera.height, distortion_model='plumb_bob',
                            D=[0.1, 0.0, 0.0, 0.0, 0.0], K=[500.0, 0, 400.0, 0, 500.0, 400.0, 0, 0, 1])
    calibrated.header.frame_id = 'camera'
    assert handler(SetCameraInfoRequest(calibrated)).success
    listen(fake, '/rrbot/camera1/camera_info')
    run(sim, 0.1)
    info = fake.publishers['/rrbot/camera1/camera_info'].messages[-1]
    assert list(info.K) == [500.0, 0, 400.0, 0, 500.0, 400.0, 0, 0, 1] and list(info.D) == [0.1, 0, 0, 0, 0]
    assert info.header.stamp.to_sec() > 0
    wrong = CameraInfo(width=10, height=10)
    response = handler(SetCameraInfoRequest(wrong))
    assert not response.success and '10 x 10' in response.status_message


RETRO_BOX = """<sdf version="1.6"><world name="w"><model name="reflector"><static>true</static>
<pose>1.0 0 0.25 0 0 0</pose><link name="link"><collision name="c"><laser_retro>150</laser_retro>
<geometry><box><size>0.1 0.6 0.5</size></box></geometry></collision></link></model></world></sdf>"""


def test_scan_intensities_are_the_laser_retro_of_what_each_ray_hits(world):
    """Row k of issue 17's audit: Gazebo's ray sensor reports the hit collision's laser_retro as intensity (SDF
    <laser_retro>, URDF <gazebo reference><laserRetro>), 0 elsewhere."""
    sim, fake, manager, robot = world
    model = sdf_reader.parse_world(RETRO_BOX).models[0]
    with sim.lock:
        sim.world.add_sdf_model(model)
    listen(fake, '/scan')
    run(sim, 0.1)
    scan = fake.publishers['/scan'].messages[-1]
    ahead = len(scan.ranges) // 2  # the beam straight ahead (the scan spans -pi..pi around x)
    assert scan.ranges[ahead] < 1.0 and scan.intensities[ahead] == 150.0
    assert scan.intensities[0] == 0.0 and len(scan.intensities) == len(scan.ranges)
    assert sum(1 for v in scan.intensities if v == 150.0) < len(scan.ranges) / 4  # only the box's rays
    urdf = ('<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" '
            'ixz="0" iyz="0"/></inertial><collision><geometry><box size="1 1 1"/></geometry></collision></link>'
            '<gazebo reference="a"><laserRetro>80</laserRetro></gazebo></robot>')
    with sim.lock:
        body = sim.world.spawn_urdf('retro', urdf_reader.parse_urdf(urdf), urdf)
    assert sim.world.laser_retro[(body.id, -1)] == 80.0
    with sim.lock:
        sim.world.remove('retro')
    assert (body.id, -1) not in sim.world.laser_retro


def test_scan_noise_as_declared_unless_switched_off(racebot_xml):
    sim, fake, manager, robot = make_world(racebot_xml, {'~sensors/noise': True})
    try:
        listen(fake, '/scan')
        run(sim, 0.3)
        a, b = (np.array(m.ranges) for m in fake.publishers['/scan'].messages[-2:])
        both = np.isfinite(a) & np.isfinite(b)
        spread = np.std(a[both] - b[both]) / math.sqrt(2)
        assert spread == pytest.approx(0.01, rel=0.2)  # the URDF's stddev 0.01 m
    finally:
        sim.close()


def test_imu_at_rest(world):
    sim, fake, manager, robot = world
    run(sim, 2.5)  # let the car settle on its free wheels (no controllers hold them here)
    listen(fake, '/imu')
    run(sim, 1.0)
    msgs = fake.publishers['/imu'].messages
    assert len(msgs) == pytest.approx(100, abs=2)  # 100 Hz
    assert msgs[-1].header.frame_id == 'imu'
    acc = np.array([[m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z] for m in msgs])
    gyro = np.array([[m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z] for m in msgs])
    assert acc.mean(axis=0) == pytest.approx([0.0, 0.0, 9.8], abs=0.02)  # the world's gravity, pointing up
    assert np.abs(gyro).max() < 0.01
    assert msgs[-1].orientation.w == pytest.approx(1.0, abs=1e-3)


def test_imu_acceleration_is_the_velocitys_change_since_the_previous_measurement(world):
    """As Gazebo's ImuSensor::UpdateImpl differences the velocity since its previous measurement (at the sensor's
    100 Hz here), an upward push on the chassis during one step shows spread over the 10 ms between two
    measurements, and the measurement after that one reads nothing of it."""
    sim, fake, manager, robot = world
    run(sim, 2.5)
    listen(fake, '/imu')
    run(sim, 0.0495)  # sensor updates every 10 ms; stop just after one (sim time ~2.55)
    body = robot.body
    mass = sum(link.dynamics().mass for link in body.links.values())
    imu = next(s for s in manager._active if isinstance(s, ImuSensor))
    due = imu.schedule.next
    force = 5.0 * 9.8 * mass  # 5 g upwards on the whole car, for one step

    def push(t_end):
        if abs(t_end - due) < 1e-9:
            sim.world.client.applyExternalForce(body.id, -1, (0.0, 0.0, force), body.pose().position,
                                                1)  # WORLD_FRAME
    sim.before_physics.append(push)
    while sim.time < due + 1e-9:
        sim.step()
    m = fake.publishers['/imu'].messages[-1]
    assert m.header.stamp.to_sec() == pytest.approx(due)
    # the push acts on the chassis alone, which also tips: over one step it reads about 4 g more than at rest
    # (48.7 m/s^2, measured when racebot read the last step); a tenth of that over the 10 ms since the last update
    assert 9.8 + 0.05 * 5.0 * 9.8 < m.linear_acceleration.z < 9.8 + 0.25 * 5.0 * 9.8


def test_camera_shows_a_red_box_where_the_pinhole_says(world):
    sim, fake, manager, robot = world
    add_red_box(sim, 1.2, 0.25, 0.1, 0.1)
    listen(fake, '/rrbot/camera1/image_raw', '/rrbot/camera1/camera_info')
    run(sim, 0.1)
    img = fake.publishers['/rrbot/camera1/image_raw'].messages[-1]
    info = fake.publishers['/rrbot/camera1/camera_info'].messages[-1]
    assert (img.width, img.height, img.encoding, img.step) == (800, 800, 'rgb8', 2400)
    assert (info.width, info.height, info.header.frame_id) == (800, 800, 'camera')
    assert info.header.stamp == img.header.stamp
    rgb = np.frombuffer(img.data, dtype=np.uint8).reshape(800, 800, 3).astype(int)
    red = (rgb[..., 0] > 120) & (rgb[..., 1] < 60) & (rgb[..., 2] < 60)
    assert red.sum() > 200
    vs, us = np.nonzero(red)
    # the box centre in the camera's optical frame, projected with camera_info's K
    position, orientation = sensor_of(manager, 'camera').mount.pose()
    from racebot_sim_bridge.sensors.camera import OPTICAL_FROM_SENSOR
    from racebot_sim_bridge.sensors.imu_reading import quaternion_to_matrix
    p_sensor = quaternion_to_matrix(orientation).T @ (np.array([1.2, 0.25, 0.1]) - position)
    x, y, z = OPTICAL_FROM_SENSOR @ p_sensor
    fx, cx, fy, cy = info.K[0], info.K[2], info.K[4], info.K[5]
    u, v = fx * x / z + cx, fy * y / z + cy
    # the visible faces (front and top) pull the centroid a little off the centre's projection
    assert us.mean() == pytest.approx(u, abs=6) and vs.mean() == pytest.approx(v, abs=12)


def test_depth_of_a_box_in_front(world):
    sim, fake, manager, robot = world
    run(sim, 0.3)
    depth_sensor = sensor_of(manager, 'depth')
    position, _ = depth_sensor.mount.pose()
    face = position[0] + 1.0  # the box's near face 1 m ahead of the depth camera
    add_red_box(sim, face + 0.25, position[1], 0.25, 0.5)
    listen(fake, '/real_sense/depth/image_raw', '/real_sense/depth/points')
    run(sim, 0.1)
    d = fake.publishers['/real_sense/depth/image_raw'].messages[-1]
    assert (d.width, d.height, d.encoding, d.header.frame_id) == (640, 480, '32FC1', 'realsense_depth')
    depth = np.frombuffer(d.data, dtype='<f4').reshape(480, 640)
    assert depth[240, 320] == pytest.approx(1.0, abs=0.02)
    assert np.isnan(depth[479, 320])  # the floor right in front is nearer than the 0.4 m cutoff
    cloud = fake.publishers['/real_sense/depth/points'].messages[-1]
    pts = np.frombuffer(cloud.data, dtype=np.uint8).reshape(480, 640, 32)[:, :, :12].copy().view('<f4')
    assert pts[240, 320] == pytest.approx([0.0, 0.0, 1.0], abs=0.02)
    assert cloud.is_dense is False and cloud.point_step == 32


def test_render_budget_skips_frames_but_keeps_the_stamps_honest(racebot_xml):
    sim, fake, manager, robot = make_world(racebot_xml, {'~sensors/render_budget': 0.05})
    try:
        listen(fake, '/rrbot/camera1/image_raw')
        run(sim, 1.0)
        camera = sensor_of(manager, 'camera')
        frames = fake.publishers['/rrbot/camera1/image_raw'].messages
        assert camera.meter.skipped > 0 and len(frames) + camera.meter.skipped == 31
        stamps = [m.header.stamp.to_sec() for m in frames]
        assert all(abs(s * 30 - round(s * 30)) < 0.04 for s in stamps)  # each on the 30 Hz schedule
    finally:
        sim.close()


def test_delete_closes_the_sensors(world):
    sim, fake, manager, robot = world
    sim.delete_model('racebot')
    assert manager._active == [] and manager.sensors == {}
    run(sim, 0.05)


def test_a_sensor_on_a_missing_link_is_refused_with_a_warning(racebot_xml):
    spec = sdf_reader.load_world(str(ROOM))
    sim = Simulator(spec, NullIO(), FakeLog(), lambda path: None)
    try:
        fake = FakeRospy({'~sensors/report_period': 0})
        manager = SensorManager(fake, sim)
        model = urdf_reader.parse_urdf(racebot_xml)
        assert len(model.sensors) == 4
        bad = racebot_xml.replace('<update_rate>40</update_rate>', '<update_rate>40</update_rate>').replace(
            '<min>0.1</min>', '<min>20</min>')  # range min above range max: not simulable
        sim.spawn_urdf('racebot', bad, '/', (0, 0, 0))
        assert '/scan' not in fake.publishers and '/imu' in fake.publishers
        assert any(level == 'warn' and 'hokuyo_sensor' in msg for level, msg in fake.logs)
        assert manager.sensors['racebot']
    finally:
        sim.close()


PRESERVE_LIDAR = '<gazebo reference="lidar_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo></robot>'


def test_a_preserved_fixed_link_is_a_real_frame_with_a_working_sensor(racebot_xml):
    """<gazebo reference="lidar_joint"><preserveFixedJoint>: Gazebo keeps the lidar link. Its state is
    the car's frame moved by the fixed joints' origins, it is among the model's links (link_states),
    and the laser on it scans the room from the same place as on the lumped link."""
    sim, fake, manager, robot = make_world(racebot_xml.replace('</robot>', PRESERVE_LIDAR))
    try:
        body = robot.body
        assert 'lidar' in body.link_names() and 'lidar' not in body.joints  # a fixed link, not a joint
        assert 'camera' not in body.link_names()  # still lumped, as Gazebo does
        listen(fake, '/scan')
        run(sim, 0.5)
        (pose, _), frame = body.links['lidar'].state(), body.frame_pose()
        expected = rotations.compose((frame.position, frame.orientation),
                                     rotations.compose((0.0, 0.0, 0.032, 0.0, 0.0, 0.0),
                                                       (0.093603, 0.0, 0.12377, 0.0, 0.0, 0.0)))
        assert pose.position == pytest.approx(expected[0], abs=1e-6)
        assert pose.orientation == pytest.approx(expected[1], abs=1e-6)
        laser = sensor_of(manager, 'laser')
        assert laser.mount.link == 'lidar' and laser.mount.index == body.link_index['lidar']
        scan = fake.publishers['/scan'].messages[-1]
        assert scan.header.frame_id == 'lidar'
        position, orientation = laser.mount.pose()
        on_link = rotations.compose((pose.position, pose.orientation), laser.spec.pose)  # the <pose> on its link
        assert position == pytest.approx(on_link[0], abs=1e-6)
        yaw = rotations.quaternion_to_rpy(orientation)[2]
        expected_ranges = sensors_geometry.expected_scan(str(ROOM), position, yaw, scan.angle_min,
                                                         scan.angle_increment, 1081)
        checked, bad = sensors_geometry.compare(scan.ranges, expected_ranges, scan.range_min, scan.range_max, 0.03)
        assert checked > 1000 and not bad, bad[:10]
    finally:
        sim.close()



def test_sensors_update_on_their_schedule_and_are_not_asked_in_between(racebot_xml):
    """after_step skips the sensors until the earliest one is due: every sensor publishes at the same
    sim times as when each is asked at every step (including after a reset sends time back), and steps
    with nothing due do not call each sensor."""
    published = []
    for shortcut in (True, False):
        sim, fake, manager, robot = make_world(racebot_xml)
        try:
            listen(fake, '/scan', '/imu')
            calls = []
            for sensor in manager._active:
                def counted(time, step=sensor.step):
                    calls.append(time)
                    step(time)
                sensor.step = counted
            for seconds in (0.5, 0.1):
                for _ in range(int(round(seconds / sim.step_size))):
                    if not shortcut:
                        manager._due_for = None  # as if the sensors had changed: every one is asked
                    sim.step()
                sim.reset_simulation()
            published.append({t: [m.header.stamp.to_sec() for m in fake.publishers[t].messages]
                              for t in ('/scan', '/imu')})
            if shortcut:
                # 40 + 100 + 30 + 20 Hz: at most 190 steps a second have a sensor due; each asks every sensor
                assert 0 < len(calls) <= (190 * 0.6 + 2) * len(manager._active)
            else:
                assert len(calls) == 600 * len(manager._active)
        finally:
            sim.close()
    assert published[0] == published[1]
    assert len(published[0]['/scan']) >= 0.6 * 40 - 2 and len(published[0]['/imu']) >= 0.6 * 100 - 2
