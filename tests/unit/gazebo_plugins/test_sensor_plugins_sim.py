"""The range, bumper, multicamera and openni_kinect plugins on a real Simulator (PyBullet DIRECT) with
the rospy stand-in of fakes.py: no master. The test robot (tests/fixtures/sensor_plugins)
stands on a ground plane, its front 1 m from a static box."""
import math
from pathlib import Path

import numpy as np
import pybullet as pb
import pytest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.gazebo_plugins.sensor_manager import SensorManager
from racebot_sim_bridge.engine.simulator import Simulator

from racebot_sim_bridge.gazebo_ros_api.performance_metrics import PerformanceMetricsPublisher
from racebot_sim_bridge.engine.pybullet_client import PybulletClient
from racebot_sim_bridge.sensors.contact import NamedShape
from racebot_sim_bridge.sensors.contact_points import read_contacts

from fakes import FakeLog, FakeNames, FakeRospy, NullIO
from sensors_sim import listen, run

ROBOT = Path(__file__).resolve().parents[2] / 'fixtures' / 'sensor_plugins' / 'robot.urdf'
SONAR_X = 0.22      # the sonar's x in the robot (sonar_joint)
BOX_FACE = 1.22     # the box's near face: 1 m ahead of the sonar
BOX_SIZE = 0.4
WORLD = """<sdf version="1.6"><world name="default">
<model name="ground_plane"><static>true</static><link name="link"><collision name="collision"><geometry>
<plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></collision></link></model>
<model name="obstacle"><static>true</static><pose>{x} 0 {h} 0 0 0</pose><link name="link">
<collision name="collision"><geometry><box><size>{s} {s} {s}</size></box></geometry></collision>
<visual name="visual"><geometry><box><size>{s} {s} {s}</size></box></geometry></visual></link></model>
</world></sdf>""".format(x=BOX_FACE + BOX_SIZE / 2, h=BOX_SIZE / 2, s=BOX_SIZE)
BUMPER = 'sensor_robot::base_link::base_link_fixed_joint_lump__bumper_link_collision_1'


def make_world(tmp_path, urdf):
    path = tmp_path / 'box.world'
    path.write_text(WORLD)
    sim = Simulator(sdf_reader.load_world(str(path)), NullIO(), FakeLog(), lambda path: None)
    fake = FakeRospy({'~sensors/report_period': 0, '~sensors/render_budget': 1.0, '~sensors/noise': False,
                      '~sensors/render_worker': False})
    manager = SensorManager(fake, sim)
    robot = sim.spawn_urdf('sensor_robot', urdf, '/', (0.0, 0.0, 0.0))
    frame = robot.body.com_pose_for_frame((0.0, 0.0, 0.0), (0, 0, 0, 1))
    robot.body.set_pose(frame.position, frame.orientation)
    return sim, fake, manager, robot


@pytest.fixture
def world(tmp_path):
    sim, fake, manager, robot = make_world(tmp_path, ROBOT.read_text())
    yield sim, fake, manager, robot
    sim.close()


def push_into_the_box(sim, robot, seconds=1.5):
    body = robot.body.id
    sim.before_physics.append(lambda t: sim.world.client.applyExternalForce(body, -1, (30.0, 0.0, 0.0),
                                                                            (0.0, 0.0, 0.0), pb.LINK_FRAME))
    run(sim, seconds)


def test_topics_and_one_warning_for_the_plugin_not_simulated(world):
    sim, fake, manager, robot = world
    assert sorted(fake.publishers) == sorted([
        '/sonar', '/bumper', '/stereo/left/image_raw', '/stereo/left/camera_info', '/stereo/right/image_raw',
        '/stereo/right/camera_info', '/kinect/rgb/image_raw', '/kinect/rgb/camera_info', '/kinect/depth/image_raw',
        '/kinect/depth/camera_info', '/kinect/depth/points'])
    warned = [msg for level, msg in fake.logs if level == 'warn' and 'liblab_lidar_plugin.so' in msg]
    assert len(warned) == 1
    assert "'lab_lidar'" in warned[0]
    # the docs page by its path in this checkout: a user can open it from the log line
    page = Path(__file__).resolve().parents[3] / 'docs' / 'SUPPORTED.md'
    assert "see the table 'Supported plugins, sensors and controllers' in %s" % page in warned[0]
    assert '# Supported plugins, sensors and controllers' in page.read_text().splitlines()


def test_a_plugin_not_simulated_beside_one_that_is(tmp_path):
    extra = '<plugin name="extra" filename="liblab_sonar_plugin.so"/></sensor>'
    urdf = ROBOT.read_text().replace('</plugin>\n    </sensor>', '</plugin>\n    ' + extra, 1)
    sim, fake, manager, robot = make_world(tmp_path, urdf)
    try:
        warned = [msg for level, msg in fake.logs if level == 'warn' and 'liblab_sonar_plugin.so' in msg]
        assert len(warned) == 1 and "sensor 'sonar'" in warned[0]
        assert '/sonar' in fake.publishers  # gazebo_ros_range beside it still runs
    finally:
        sim.close()


def test_sonar_reads_the_distance_to_the_box(world):
    sim, fake, manager, robot = world
    listen(fake, '/sonar')
    run(sim, 0.3)
    messages = fake.publishers['/sonar'].messages
    assert 5 <= len(messages) <= 7  # 20 Hz over 0.3 s
    m = messages[-1]
    assert m.header.frame_id == 'sonar_link' and m.radiation_type == m.ULTRASOUND
    assert (m.field_of_view, m.min_range, m.max_range) == pytest.approx((0.5, 0.02, 4.0))
    assert m.range == pytest.approx(BOX_FACE - SONAR_X, abs=0.01)


def test_range_and_bumper_frames_take_the_tf_prefix_of_their_namespace(tmp_path):
    path = tmp_path / 'box.world'
    path.write_text(WORLD)
    sim = Simulator(sdf_reader.load_world(str(path)), NullIO(), FakeLog(), lambda path: None)
    try:
        fake = FakeRospy({'~sensors/report_period': 0, '~sensors/render_worker': False, '/fleet/tf_prefix': 'bot1'})
        SensorManager(fake, sim)
        sim.spawn_urdf('sensor_robot', ROBOT.read_text(), '/fleet', (0.0, 0.0, 0.0))
        listen(fake, '/fleet/sonar', '/fleet/bumper')
        run(sim, 0.06)
        assert fake.publishers['/fleet/sonar'].messages[-1].header.frame_id == 'bot1/sonar_link'
        assert fake.publishers['/fleet/bumper'].messages[-1].header.frame_id == 'bot1/bumper_link'
    finally:
        sim.close()


def test_sonar_reads_range_max_when_nothing_is_ahead(world):
    sim, fake, manager, robot = world
    sim.world.remove('obstacle')
    listen(fake, '/sonar')
    run(sim, 0.1)
    assert fake.publishers['/sonar'].messages[-1].range == pytest.approx(4.0)


def test_bumper_free_then_pushed_into_the_box(world):
    sim, fake, manager, robot = world
    listen(fake, '/bumper')
    run(sim, 0.2)
    free = fake.publishers['/bumper'].messages
    assert len(free) >= 9 and all(m.states == [] for m in free)  # the base rests on the ground: not the bumper
    assert free[-1].header.frame_id == 'bumper_link'
    push_into_the_box(sim, robot)
    m = fake.publishers['/bumper'].messages[-1]
    # as Gazebo's ContactSensor: a state per step since the last update (the sensor's 50 Hz: 20 steps of 1 ms)
    pairs = [(s.collision1_name, s.collision2_name) for s in m.states]
    assert pairs == [(BUMPER, 'obstacle::link::collision')] * 20
    s = m.states[-1]
    assert all(n.x < -0.99 for n in s.contact_normals)               # out of the box, into the bumper
    assert all(abs(p.x - BOX_FACE) < 0.01 for p in s.contact_positions)
    assert all(d >= 0.0 for d in s.depths) and len(s.wrenches) == len(s.depths)
    # at rest, pushed with 30 N: the box and the ground's static friction (at most mu m g ~ 10 N) hold it,
    # so the box pushes back (-x, in base_link's frame, which is the world's here) with 20 to 30 N
    assert -31.0 < s.total_wrench.force.x < -19.0


def test_stereo_pair_both_images_and_the_baseline(world):
    sim, fake, manager, robot = world
    listen(fake, '/stereo/left/image_raw', '/stereo/right/image_raw')
    run(sim, 0.25)
    infos = {side: fake.publishers['/stereo/%s/camera_info' % side].messages for side in ('left', 'right')}
    images = {side: fake.publishers['/stereo/%s/image_raw' % side].messages for side in ('left', 'right')}
    assert all(len(images[side]) >= 2 and len(infos[side]) >= 2 for side in ('left', 'right'))
    f = 64 / (2 * math.tan(0.5))
    assert infos['left'][-1].P[3] == 0.0 and infos['right'][-1].P[3] == pytest.approx(-f * 0.07)
    left, right = (np.frombuffer(images[s][-1].data, np.uint8).reshape(48, 64, 3) for s in ('left', 'right'))
    assert images['left'][-1].header.frame_id == 'stereo_link'
    assert not np.array_equal(left, right)  # 7 cm apart, they see the box from two places


def test_the_stereo_pair_is_one_sensor_in_performance_metrics(world):
    sim, fake, manager, robot = world
    names = [name for name, _, _ in PerformanceMetricsPublisher(fake, sim, manager, '/gazebo').sensors()]
    assert len(names) == len(set(names))
    assert [n for n in names if 'stereo' in n] == ['default::sensor_robot::base_link::stereo_camera']


def test_kinect_point_cloud_of_the_box(world):
    sim, fake, manager, robot = world
    listen(fake, '/kinect/depth/points', '/kinect/depth/image_raw')
    run(sim, 0.15)
    cloud = fake.publishers['/kinect/depth/points'].messages[-1]
    points = np.frombuffer(cloud.data, np.uint8).reshape(-1, cloud.point_step)[:, :12].copy().view('<f4')
    finite = points[np.isfinite(points).all(axis=1)]
    assert len(finite) > 100 and not cloud.is_dense
    centre = points.reshape(48, 64, 3)[23:25, 31:33].reshape(-1, 3)
    assert centre[:, 2] == pytest.approx(BOX_FACE - 0.1, abs=0.02)  # the kinect is at x 0.1
    assert (finite[:, 2] > 0.5).all() and (finite[:, 2] < 3.0).all()  # pointCloudCutoff .. pointCloudCutoffMax


def test_a_bumper_naming_its_lumped_links_own_collision_reports_nothing_with_a_warning(tmp_path):
    lumped = 'base_link_fixed_joint_lump__bumper_link_collision_1'
    sim, fake, manager, robot = make_world(tmp_path, ROBOT.read_text().replace(lumped, 'bumper_link_collision'))
    try:
        warned = [msg for level, msg in fake.logs if level == 'warn' and "sensor 'bumper'" in msg]
        assert len(warned) == 1
        assert "'base_link_collision_bumper_link'" in warned[0] and repr(lumped) in warned[0]
        assert "'bumper_link_collision' (which sdformat rewrites to" in warned[0]  # the name as written, too
        listen(fake, '/bumper')
        push_into_the_box(sim, robot)
        messages = fake.publishers['/bumper'].messages
        assert len(messages) > 50 and all(m.states == [] for m in messages)  # as Gazebo's: nothing matches
    finally:
        sim.close()


def _box_urdf(tmp_path, collisions):
    """A 1 kg link of 0.2 m boxes, the first at its origin, any others stacked on top."""
    cols = ''.join('<collision><origin xyz="0 0 %g"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision>'
                   % (0.3 * i) for i in range(collisions))
    path = tmp_path / ('slider%d.urdf' % collisions)
    path.write_text('<robot name="r"><link name="b"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" '
                    'ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>%s</link></robot>' % cols)
    return str(path)


@pytest.mark.parametrize('ground', ['box', 'compound', 'plane'])
@pytest.mark.parametrize('collisions', [1, 2])
@pytest.mark.parametrize('ground_first', [True, False])
def test_friction_on_a_sliding_link_opposes_its_motion(tmp_path, ground, collisions, ground_first):
    """read_contacts on real PyBullet: a link sliding +x over the ground feels friction along -x,
    whichever way round Bullet keeps the pair."""
    class World:
        client = PybulletClient()
    world = World()
    c = world.client
    try:
        def make_ground():
            if ground == 'plane':
                return c.createMultiBody(0, c.createCollisionShape(pb.GEOM_PLANE))
            if ground == 'box':
                shape = c.createCollisionShape(pb.GEOM_BOX, halfExtents=[5, 5, 0.1])
            else:
                shape = c.createCollisionShapeArray([pb.GEOM_BOX, pb.GEOM_BOX], halfExtents=[[5, 5, 0.1], [0.1] * 3],
                                                    collisionFramePositions=[[0, 0, 0], [3, 3, 0.5]])
            return c.createMultiBody(0, shape, basePosition=[0, 0, -0.1])
        if ground_first:
            make_ground()
        body = c.loadURDF(_box_urdf(tmp_path, collisions), [0, 0, 0.1])
        if not ground_first:
            make_ground()
        c.setGravity(0, 0, -9.8)
        for _ in range(100):
            c.stepSimulation()
        c.resetBaseVelocity(body, [1.0, 0.0, 0.0])
        c.stepSimulation()
        shape = NamedShape('b_collision', 'box', size=(0.2, 0.2, 0.2))
        points = read_contacts(world, FakeNames(), body, -1, [shape], 'r', 'b', {'b_collision'})
        assert points
        force = np.sum([p.force for p in points], axis=0)
        assert force[2] == pytest.approx(9.8, rel=0.3)    # the ground holds it up
        # sliding friction backwards: mu m g = 0.25 x 9.8 N (PyBullet's default 0.5 on each side, multiplied)
        assert force[0] == pytest.approx(-0.25 * 9.8, rel=0.2)
    finally:
        c.close()
