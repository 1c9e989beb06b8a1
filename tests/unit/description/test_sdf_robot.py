"""SDF robots: an SDF model with joints, model plugins or sensors, read by sdf_reader, written as a URDF by
sdf_urdf and spawned through the URDF path (Simulator.spawn_sdf_robot, spawn_world_robots) on a real
Simulator. The fixture is tests/fixtures/robots/sdf_diffbot's Gazebo model (a diff-drive base with a caster,
the diff-drive plugin and a laser); the pendulum checks an SDF joint <pose> that moves the axis."""
import math
import pathlib

import pytest
from geometry_msgs.msg import Twist

from racebot_sim_bridge.description import sdf_reader, sdf_urdf, urdf_reader
from racebot_sim_bridge.kinematics.rotations import rotate, yaw_of
from racebot_sim_bridge.engine.simulator import SpawnError

from racebot_sim_bridge.gazebo_plugins.plugin_manager import PluginManager
from racebot_sim_bridge.engine.simulator import Simulator

from model_plugin_sim import GROUND, ROBOTS, PluginRospy, PluginWorld
from fakes import NullIO

MODEL_SDF = ROBOTS / 'sdf_diffbot' / 'models' / 'sdf_diffbot' / 'model.sdf'


def model_of(body):
    """The one sdf_model.SdfModel of a <model> element's text."""
    world = sdf_reader.parse_world('<sdf version="1.6"><world name="w">%s</world></sdf>' % body)
    assert len(world.models) == 1, world.warnings
    return world.models[0]


def diffbot_text():
    text = MODEL_SDF.read_text()
    return text[text.index('<model'):text.rindex('</sdf>')]


def link(name, pose='0 0 0 0 0 0', size='0.1 0.1 0.1', extra=''):
    return ('<link name="%s"><pose>%s</pose><inertial><mass>1</mass></inertial><collision name="c"><geometry>'
            '<box><size>%s</size></box></geometry></collision>%s</link>' % (name, pose, size, extra))


def joint(name, parent, child, kind='revolute', extra=''):
    return ('<joint name="%s" type="%s"><parent>%s</parent><child>%s</child>%s</joint>'
            % (name, kind, parent, child, extra))


def test_the_model_keeps_its_joints_plugins_and_sensors():
    model = model_of(diffbot_text())
    assert model.is_robot
    assert [(j.name, j.type, j.parent, j.child) for j in model.joints] == [
        ('left_wheel_hinge', 'revolute', 'chassis', 'left_wheel'),
        ('right_wheel_hinge', 'revolute', 'chassis', 'right_wheel'),
        ('laser_joint', 'fixed', 'chassis', 'laser_link')]
    right = model.joints[1]
    assert right.axis == (0.0, 1.0, 0.0) and right.axis_in_model
    assert not model.joints[0].axis_in_model
    assert len(model.plugins) == 1 and 'libgazebo_ros_diff_drive.so' in model.plugins[0]
    assert 'libgazebo_ros_laser.so' in model.link('laser_link').sensors[0]
    assert not model_of('<model name="box">%s</model>' % link('l')).is_robot


def test_the_urdf_has_each_joint_origin_and_axis_in_the_child_frame():
    conversion = sdf_urdf.model_urdf(model_of(diffbot_text()))
    assert conversion.warnings == []
    assert conversion.root_pose[0] == pytest.approx((0.0, 0.0, 0.1))
    robot = urdf_reader.parse_urdf(conversion.urdf)
    left, right, laser = (robot.joints[n] for n in ('left_wheel_hinge', 'right_wheel_hinge', 'laser_joint'))
    assert left.type == right.type == 'continuous' and laser.type == 'fixed'
    assert left.origin_xyz == pytest.approx((-0.1, 0.17, 0.0), abs=1e-12)
    assert left.origin_rpy == pytest.approx((-math.pi / 2, 0.0, 0.0), abs=1e-9)
    assert right.origin_xyz == pytest.approx((-0.1, -0.17, 0.0), abs=1e-12)
    assert laser.origin_xyz == pytest.approx((0.1, 0.0, 0.1), abs=1e-12)
    # the wheel frames are turned -90 deg about x: the joint frame's z (left) and the model's y (right) are
    # both the child's z
    assert left.axis == pytest.approx((0.0, 0.0, 1.0), abs=1e-9)
    assert right.axis == pytest.approx((0.0, 0.0, 1.0), abs=1e-9)
    assert left.limit.effort == 0.0 and left.limit.velocity == 0.0  # SDF's -1: no limit (hardware reads 0 so)
    assert robot.gazebo_refs['chassis'] == {'mu1': 0.0, 'mu2': 0.0}  # the caster's, the first with a friction
    assert robot.gazebo_refs['left_wheel'] == {'mu1': 1.0, 'mu2': 1.0}
    assert [p.filename for p in robot.plugins] == ['libgazebo_ros_diff_drive.so']
    assert robot.plugins[0].params['leftJoint'] == 'left_wheel_hinge'
    assert [(s.name, s.reference) for s in robot.sensors] == [('laser', 'laser_link')]
    assert robot.gazebo_refs['laser_joint'] == {'preserveFixedJoint': True}  # Gazebo keeps SDF fixed joints


@pytest.mark.parametrize('limit, kind, bounds', [
    ('', 'continuous', None),
    ('<limit><lower>-1e16</lower><upper>1e16</upper></limit>', 'continuous', None),
    ('<limit><lower>-0.5</lower><upper>0.7</upper><effort>3</effort><velocity>2</velocity></limit>',
     'revolute', (-0.5, 0.7, 3.0, 2.0)),
])
def test_revolute_limits(limit, kind, bounds):
    body = '<model name="m">%s%s%s</model>' % (link('a'), link('b', '0 0 1 0 0 0'),
                                                joint('j', 'a', 'b', extra='<axis><xyz>1 0 0</xyz>%s</axis>' % limit))
    j = urdf_reader.parse_urdf(sdf_urdf.model_urdf(model_of(body)).urdf).joints['j']
    assert j.type == kind
    if bounds:
        assert (j.limit.lower, j.limit.upper, j.limit.effort, j.limit.velocity) == bounds


def test_prismatic_joint_and_dynamics():
    body = '<model name="m">%s%s%s</model>' % (link('a'), link('b', '0 0 1 0 0 0'), joint(
        'slide', 'a', 'b', 'prismatic', '<axis><xyz>0 0 2</xyz><limit><lower>0</lower><upper>0.3</upper></limit>'
        '<dynamics><damping>0.5</damping><friction>0.2</friction></dynamics></axis>'))
    j = urdf_reader.parse_urdf(sdf_urdf.model_urdf(model_of(body)).urdf).joints['slide']
    assert (j.type, j.axis, j.limit.lower, j.limit.upper) == ('prismatic', (0.0, 0.0, 1.0), 0.0, 0.3)
    assert (j.dynamics.damping, j.dynamics.friction) == (0.5, 0.2)


@pytest.mark.parametrize('joints, said', [
    ('', 'not all joined: a, b hang from no joint'),
    (joint('j', 'a', 'c'), "joint 'j' names child link 'c', which model 'm' does not have"),
    (joint('j', 'x', 'b'), "joint 'j' names parent link 'x'"),
    (joint('j1', 'a', 'b') + joint('j2', 'world', 'b'), "link 'b' is the child of two joints ('j1' and 'j2')"),
    (joint('j1', 'a', 'b') + joint('j2', 'b', 'a'), 'form a loop'),
    (joint('j', 'a', 'a'), "joins link 'a' to itself"),
])
def test_links_not_in_one_tree_are_refused_with_the_reason(joints, said):
    model = model_of('<model name="m">%s%s%s</model>' % (link('a'), link('b', '0 0 1 0 0 0'), joints))
    with pytest.raises(sdf_urdf.ConversionError, match=None) as err:
        sdf_urdf.model_urdf(model)
    assert said in str(err.value)


@pytest.fixture
def world(tmp_path):
    w = PluginWorld(tmp_path)
    yield w
    w.close()


def axle_twist(robot):
    """(forward speed, yaw rate) of the wheel axle's midpoint (0.1 m behind the chassis origin)."""
    frame = robot.body.frame_pose()
    linear, angular = robot.body.twist()  # of the chassis' centre of mass, its origin
    arm = rotate(frame.orientation, (-0.1, 0.0, 0.0))
    v = [linear[i] + (angular[(i + 1) % 3] * arm[(i + 2) % 3] - angular[(i + 2) % 3] * arm[(i + 1) % 3])
         for i in range(3)]
    heading = yaw_of(frame.orientation)
    return v[0] * math.cos(heading) + v[1] * math.sin(heading), angular[2]


def test_the_sdf_diffbot_drives_at_the_commanded_speed_and_yaw_rate(world):
    robot = world.sim.spawn_sdf_robot(model_of(diffbot_text()), '/')
    assert world.warnings() == [] and world.errors() == []
    assert sorted(robot.body.link_index) == ['chassis', 'laser_link', 'left_wheel', 'right_wheel']
    assert robot.body.frame_pose().position[2] == pytest.approx(0.1, abs=1e-6)
    msg = Twist()
    msg.linear.x, msg.angular.z = 0.3, 0.5
    world.fake.subscribers['/cmd_vel'](msg)
    world.run(1.5)
    speeds, rates = [], []
    for _ in range(10):
        world.run(0.1)
        speed, rate = axle_twist(robot)
        speeds.append(speed)
        rates.append(rate)
    assert sum(speeds) / 10 == pytest.approx(0.3, rel=0.05)
    assert sum(rates) / 10 == pytest.approx(0.5, rel=0.05)


def test_the_model_pose_is_the_sdf_model_frame_not_the_root_link(world):
    from racebot_sim_bridge.gazebo_ros_api.entities import WorldEntities
    model = model_of(diffbot_text())
    model.pose = (1.0, 2.0, 0.0, 0.0, 0.0, 0.3)
    robot = world.sim.spawn_sdf_robot(model, '/')
    entities = WorldEntities(world.sim.world)
    pose, _ = entities.model_state(robot.body)
    assert pose.position == pytest.approx((1.0, 2.0, 0.0), abs=1e-6)  # the chassis link is 0.1 m above it
    assert yaw_of(pose.orientation) == pytest.approx(0.3, abs=1e-6)
    chassis, _ = entities.link_state(robot.body, 'chassis')
    assert chassis.position == pytest.approx((1.0, 2.0, 0.1), abs=1e-6)
    entities.set_model_state(robot.body, ((3.0, 4.0, 0.5), (0.0, 0.0, 0.0, 1.0)), ((0, 0, 0), (0, 0, 0)))
    assert entities.model_state(robot.body)[0].position == pytest.approx((3.0, 4.0, 0.5), abs=1e-6)
    assert entities.link_state(robot.body, 'chassis')[0].position == pytest.approx((3.0, 4.0, 0.6), abs=1e-6)


def test_a_joint_pose_off_the_axis_is_where_the_link_swings(world):
    # a 1 m bar lying along y, hinged at its end (the joint <pose>, 0.5 m from its centre) about x, on a post
    # fixed to the world: it swings down about the hinge, its centre 0.5 m from it. Hinged at its centre (the
    # joint pose ignored) it would stay level.
    body = ('<model name="pendulum"><pose>0 0 0 0 0 0</pose>%s%s%s%s</model>' % (
        link('post', '0 0 1 0 0 0', '0.05 0.05 0.05'), link('bar', '0 0.5 2 0 0 0', '0.04 1 0.04'),
        joint('fix', 'world', 'post', 'fixed'),
        joint('hinge', 'post', 'bar', extra='<pose>0 -0.5 0 0 0 0</pose><axis><xyz>1 0 0</xyz></axis>')))
    robot = world.sim.spawn_sdf_robot(model_of(body))
    bar = robot.body.links['bar']
    start = bar.com_position()
    world.run(0.5)
    centre = bar.com_position()
    hinge = (0.0, 0.0, 2.0)
    assert math.dist(centre, hinge) == pytest.approx(0.5, abs=0.01)
    assert centre[2] < start[2] - 0.1


def test_a_static_model_with_a_sensor_holds_still_in_the_air(world):
    camera = ('<sensor name="cam" type="camera"><update_rate>10</update_rate><camera><image><width>8</width>'
              '<height>6</height></image></camera></sensor>')
    body = '<model name="post"><static>true</static><pose>1 2 1 0 0 0.5</pose>%s</model>' % link(
        'pole', extra=camera)
    model = model_of(body)
    assert model.is_robot
    robot = world.sim.spawn_sdf_robot(model)
    assert [s.name for s in robot.model.sensors] == ['cam']
    world.run(0.5)
    frame = robot.body.frame_pose()
    assert frame.position == pytest.approx((1.0, 2.0, 1.0), abs=1e-6)
    assert yaw_of(frame.orientation) == pytest.approx(0.5, abs=1e-6)


def test_a_model_that_cannot_be_built_is_a_spawn_error_and_the_world_goes_on(world):
    model = model_of('<model name="m">%s%s</model>' % (link('a'), link('b')))
    with pytest.raises(SpawnError, match="the SDF model m cannot be simulated: the links of model 'm' are not"):
        world.sim.spawn_sdf_robot(model)
    assert 'm' not in world.sim.world.bodies
    world.run(0.01)


class RecordingLog:
    def __init__(self):
        self.warnings = []

    def info(self, msg):
        pass

    error = info

    def warn(self, msg):
        self.warnings.append(msg)


def test_the_robots_of_a_world_file_are_spawned_with_their_plugins(tmp_path):
    path = tmp_path / 'robot.world'
    broken = '<model name="broken">%s%s%s</model>' % (link('a'), link('b'), joint('j', 'a', 'c'))
    path.write_text(GROUND.replace('</world>', diffbot_text() + broken + '</world>'))
    spec = sdf_reader.load_world(str(path))
    log = RecordingLog()
    sim = Simulator(spec, NullIO(), log, lambda p: None)
    assert sorted(sim.world.bodies) == ['ground_plane']  # the robots wait for the managers
    fake = PluginRospy()
    manager = PluginManager(fake, sim)
    try:
        robots = sim.spawn_world_robots()
        assert [r.name for r in robots] == ['sdf_diffbot']
        assert sorted(sim.world.bodies) == ['ground_plane', 'sdf_diffbot']
        assert '/sdf_diffbot/cmd_vel' in fake.subscribers  # no robotNamespace: under the model's name
        assert any('broken cannot be simulated' in m for m in log.warnings)
    finally:
        manager.close()
        sim.close()


def test_an_sdf_file_spawns_as_spawn_sdf_model_would(world):
    assert pathlib.Path(MODEL_SDF).is_file()
    from racebot_sim_bridge.description.spawn_xml import add_robot_namespace
    model = model_of(add_robot_namespace(diffbot_text(), '/robot1'))
    robot = world.sim.spawn_sdf_robot(model, '/robot1')
    assert robot.model.plugins[0].robot_namespace == '/robot1'
    assert '/robot1/cmd_vel' in world.fake.subscribers
