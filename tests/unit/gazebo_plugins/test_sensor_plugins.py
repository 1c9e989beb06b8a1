"""gazebo_ros_range, gazebo_ros_bumper, gazebo_ros_multicamera and gazebo_ros_openni_kinect as their
noetic-devel sources read their parameters and fill their messages: pure logic, no master, no physics."""
import math
from pathlib import Path

import numpy as np
import pytest

from racebot_sim_bridge.description import urdf_reader
from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion
from racebot_sim_bridge.sensors import messages as msgs
from racebot_sim_bridge.sensors.camera import PinholeCamera, mask_depth
from racebot_sim_bridge.gazebo_plugins.registry import REGISTRY
from racebot_sim_bridge.gazebo_plugins.sensor_manager import sensor_config
from racebot_sim_bridge.sensors.config_types import SensorConfigError, resolve_frame, tf_resolve
from racebot_sim_bridge.sensors.contact_points import read_contacts
from racebot_sim_bridge.sensors.contact import (CollisionKind, ContactPoint, NamedShape,
                                                friction_reversed, group_contacts,
                                                nearest_shape, surface_distance, urdf_collision_shapes)
from racebot_sim_bridge.sensors.range_reading import INFRARED, ULTRASOUND, radiation_type, range_reading, ray_lengths
from racebot_sim_bridge.sensors.schedule import FrameThrottle

from fakes import FakeNames

ROBOT = Path(__file__).resolve().parents[2] / 'fixtures' / 'sensor_plugins' / 'robot.urdf'


@pytest.fixture(scope='module')
def model():
    return urdf_reader.parse_urdf(ROBOT.read_text())


def configs(model, spawn_ns='/', name='sensor_robot'):
    return {s.name: sensor_config(s, spawn_ns, name) for s in model.sensors}


def _sensor(body, plugin):
    xml = ('<robot name="r"><link name="a"><collision><geometry><box size="1 1 1"/></geometry></collision></link>'
           '<gazebo reference="a">%s</gazebo></robot>' % body.replace('PLUGIN', plugin))
    return urdf_reader.parse_urdf(xml).sensors[0]


RAY = ('<sensor type="ray" name="s"><update_rate>10</update_rate><ray><scan><horizontal><samples>3</samples>'
       '<min_angle>-0.1</min_angle><max_angle>0.1</max_angle></horizontal></scan>'
       '<range><min>0.05</min><max>2</max></range></ray>PLUGIN</sensor>')


# -- gazebo_ros_range ---------------------------------------------------------------------------

def test_range_is_the_shortest_ray_and_a_miss_reads_range_max():
    lengths = ray_lengths([0.5, 0.25, 1.0], [True, True, False], 0.05, 2.05)
    assert lengths.tolist() == pytest.approx([1.05, 0.55, 2.05])
    assert range_reading(lengths, 2.05) == pytest.approx(0.55)
    # nothing hit: range max itself (the ray shape's length), never +inf as a LaserScan says
    assert range_reading(ray_lengths([1.0, 1.0], [False, False], 0.05, 2.0), 2.0) == pytest.approx(2.0)


def test_range_noise_only_below_max_and_clamped_from_above_only():
    assert range_reading([1.0], 2.0, noise_sample=0.1) == pytest.approx(1.1)
    assert range_reading([1.95], 2.0, noise_sample=0.2) == pytest.approx(2.0)   # clamped to max
    assert range_reading([2.0], 2.0, noise_sample=-0.5) == pytest.approx(2.0)   # at max: no noise
    assert range_reading([0.06], 2.0, noise_sample=-0.1) == pytest.approx(-0.04, abs=1e-6)  # no lower clamp


def test_radiation_types_as_upstream():
    assert radiation_type('ultrasound') == ULTRASOUND == 0
    assert radiation_type('infrared') == INFRARED == 1
    assert radiation_type('sonar') == INFRARED  # upstream: anything but 'ultrasound'


def test_range_parameters_and_defaults():
    c = sensor_config(_sensor(RAY, '<plugin name="p" filename="libgazebo_ros_range.so"/>'), '', 'r')
    assert c.kind == 'range' and c.topics == {'range': '/range'} and c.frame_id == 'world'
    assert (c.params['radiation'], c.params['fov'], c.params['gaussian_noise'], c.params['update_rate']) == \
        ('ultrasound', 0.05, 0.0, 0.0)
    assert any('<radiation>' in w for w in c.warnings) and any('<fov>' in w for w in c.warnings)
    c = sensor_config(_sensor(RAY, '<plugin name="p" filename="libgazebo_ros_range.so"><topicName>ir</topicName>'
                                   '<frameName>/ir_link</frameName><radiation>infrared</radiation><fov>0.3</fov>'
                                   '<robotNamespace>bot</robotNamespace></plugin>'), '/fleet', 'r')
    assert c.topics == {'range': '/bot/ir'} and c.frame_id == 'ir_link' and c.params['fov'] == 0.3
    assert not c.warnings
    # spawn_model's robot_namespace for a plugin without its own; none at all: the node's namespace
    plugin = '<plugin name="p" filename="libgazebo_ros_range.so"><topicName>ir</topicName></plugin>'
    assert sensor_config(_sensor(RAY, plugin), '/fleet', 'r').topics == {'range': '/fleet/ir'}
    assert sensor_config(_sensor(RAY, plugin), '', 'r').topics == {'range': '/ir'}
    # an empty <robotNamespace>: its text + '/' is the root (a laser would take the model name)
    plugin = ('<plugin name="p" filename="libgazebo_ros_range.so"><topicName>ir</topicName><robotNamespace>'
              '</robotNamespace></plugin>')
    assert sensor_config(_sensor(RAY, plugin), '/fleet', 'r').topics == {'range': '/ir'}
    with pytest.raises(SensorConfigError, match="type 'gpu_ray'"):  # upstream needs a RaySensor
        sensor_config(_sensor(RAY.replace('"ray"', '"gpu_ray"'), plugin), '', 'r')
    # an empty <topicName>: gazebo_ros_range advertises nothing
    assert sensor_config(_sensor(RAY, '<plugin name="p" filename="libgazebo_ros_range.so"><topicName>'
                                      '</topicName></plugin>'), '', 'r') is None


def test_frames_resolved_with_tf_prefix_as_tf_does():
    assert tf_resolve('', '/world') == 'world' and tf_resolve('', 'sonar') == 'sonar'
    assert tf_resolve('robot1', 'sonar') == 'robot1/sonar' and tf_resolve('/robot1', 'sonar') == 'robot1/sonar'
    assert tf_resolve('robot1', '/sonar') == 'sonar'  # an absolute frame ignores the prefix
    plugin = ('<plugin name="p" filename="libgazebo_ros_range.so"><frameName>sonar</frameName>'
              '<robotNamespace>bot</robotNamespace></plugin>')
    c = sensor_config(_sensor(RAY, plugin), '', 'r')
    assert c.frame_id == 'sonar' and c.params['tf_prefix_param'] == '/bot/tf_prefix'  # NodeHandle('bot/')
    resolve_frame(c, 'bot')
    assert c.frame_id == 'bot/sonar'
    contact = ('<sensor type="contact" name="s"><contact><collision>a_collision</collision></contact>PLUGIN'
               '</sensor>')
    c = sensor_config(_sensor(contact, '<plugin name="p" filename="libgazebo_ros_bumper.so"/>'), '/fleet', 'r')
    assert c.params['tf_prefix_param'] == '/fleet/tf_prefix'
    resolve_frame(c, '/fleet')
    assert c.frame_id == 'fleet/world'  # upstream's default frame, prefixed like any other


def test_plugin_throttle_drops_whole_updates():
    throttle = FrameThrottle(15.0)
    sensor_updates = [i * 0.05 for i in range(21)]  # a 20 Hz sensor for 1 s
    passed = [t for t in sensor_updates if throttle.passes(t)]
    assert len(passed) == 11  # every other update: 10 Hz (+ the first)
    assert all(FrameThrottle(0.0).passes(t) for t in sensor_updates)
    assert throttle.passes(0.0)  # time sent back (a reset) starts over


# -- gazebo_ros_bumper --------------------------------------------------------------------------

def test_collision_names_as_sdformat_gives_them(model):
    assert [s.name for s in urdf_collision_shapes(model, 'base_link')] == [
        'base_link_collision', 'base_link_fixed_joint_lump__bumper_link_collision_1']
    bumper = urdf_collision_shapes(model, 'base_link')[1]
    assert bumper.position == pytest.approx((0.21, 0.0, 0.05)) and bumper.size == (0.02, 0.28, 0.06)
    xml = ('<robot name="r"><link name="b"><collision name="shell"><geometry><sphere radius="1"/></geometry>'
           '</collision><collision><geometry><sphere radius="1"/></geometry></collision></link>'
           '<link name="c"><collision><geometry><sphere radius="1"/></geometry></collision></link>'
           '<link name="bb"><collision name="tip"><geometry><sphere radius="1"/></geometry></collision></link>'
           '<joint name="z" type="fixed"><parent link="b"/><child link="c"/></joint>'
           '<joint name="a" type="fixed"><parent link="b"/><child link="bb"/></joint></robot>')
    m = urdf_reader.parse_urdf(xml)
    # own first, then lumped children in joint-name order ('a' before 'z'); a name starting with the
    # link's own keeps no prefix
    assert [s.name for s in urdf_collision_shapes(m, 'b')] == [
        'b_fixed_joint_lump__shell_collision', 'b_collision_1', 'b_fixed_joint_lump__tip_collision_2',
        'b_fixed_joint_lump__c_collision_3']


def test_a_lumped_links_own_collision_name_is_the_one_sdformat_writes(model):
    # the bumper sensor sits on bumper_link, lumped into base_link; it names the lumped collision in full,
    # which sdformat leaves as written (test_sdf_reduction has the renaming rule)
    (bumper,) = [s for s in model.sensors if s.name == 'bumper']
    assert bumper.reference == 'base_link'
    assert bumper.contact_collisions == ['base_link_fixed_joint_lump__bumper_link_collision_1']


def test_bumper_parameters_and_defaults():
    contact = ('<sensor type="contact" name="s"><contact><collision>a_collision</collision></contact>PLUGIN'
               '</sensor>')
    c = sensor_config(_sensor(contact, '<plugin name="p" filename="libgazebo_ros_bumper.so"/>'), '', 'r')
    assert c.kind == 'bumper' and c.topics == {'bumper': '/bumper_states'} and c.frame_id == 'world'
    assert c.params['collisions'] == ['a_collision']
    c = sensor_config(_sensor(contact, '<plugin name="p" filename="libgazebo_ros_bumper.so"><bumperTopicName>'
                                       'hit</bumperTopicName><frameName>a</frameName></plugin>'), '/fleet', 'r')
    assert c.topics == {'bumper': '/fleet/hit'} and c.frame_id == 'a'
    with pytest.raises(SensorConfigError, match='<contact><collision>'):
        sensor_config(_sensor('<sensor type="contact" name="s">PLUGIN</sensor>',
                              '<plugin name="p" filename="libgazebo_ros_bumper.so"/>'), '', 'r')


def test_contact_points_go_to_the_nearest_collision():
    base = NamedShape('base', 'box', size=(0.4, 0.3, 0.1), position=(0.0, 0.0, 0.05))
    bumper = NamedShape('bumper', 'box', size=(0.02, 0.28, 0.06), position=(0.21, 0.0, 0.05))
    assert surface_distance(base, (0.0, 0.0, 0.0)) == pytest.approx(0.0)
    assert surface_distance(base, (0.0, 0.0, 0.05)) == pytest.approx(-0.05)  # inside: negative
    assert surface_distance(bumper, (0.3, 0.0, 0.05)) == pytest.approx(0.08)
    assert nearest_shape([base, bumper], (0.2, 0.15, 0.0)).name == 'base'     # a ground contact corner
    assert nearest_shape([base, bumper], (0.22, 0.05, 0.05)).name == 'bumper'  # its front face
    turned = NamedShape('c', 'cylinder', radius=0.1, length=0.4, orientation=rpy_to_quaternion(0, math.pi / 2, 0))
    assert surface_distance(turned, (0.2, 0.0, 0.0)) == pytest.approx(0.0, abs=1e-9)  # its end cap, along x
    assert surface_distance(NamedShape('s', 'sphere', radius=0.5), (0.0, 0.0, 2.0)) == pytest.approx(1.5)


def test_contacts_grouped_per_pair_with_wrenches_in_the_link_frame():
    yaw90 = rpy_to_quaternion(0.0, 0.0, math.pi / 2)
    points = [ContactPoint('m::l::a', 'box::link::collision', (1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), 0.001,
                           (-10.0, 0.0, 0.0)),
              ContactPoint('m::l::a', 'ground::link::collision', (0.0, 0.0, -1.0), (0.0, 0.0, 1.0), 0.0,
                           (0.0, 0.0, 5.0)),
              ContactPoint('m::l::a', 'box::link::collision', (1.0, 0.0, 1.0), (-1.0, 0.0, 0.0), 0.002,
                           (-10.0, 0.0, 0.0))]
    groups = group_contacts(points, (0.0, 0.0, 0.0), yaw90)
    assert [(g.collision1, g.collision2) for g in groups] == [('m::l::a', 'box::link::collision'),
                                                             ('m::l::a', 'ground::link::collision')]
    box = groups[0]
    assert box.positions == [(1.0, 0.0, 0.0), (1.0, 0.0, 1.0)] and box.depths == [0.001, 0.002]
    assert box.normals[0] == (-1.0, 0.0, 0.0)  # world frame, into our collision
    # the link is turned 90 deg about z: world -x is the link's +y
    assert box.forces[0] == pytest.approx((0.0, 10.0, 0.0), abs=1e-9)
    # torque about the centre of mass: (0, 0, 1) x (-10, 0, 0) = (0, -10, 0) in the world, (-10, 0, 0) in the link
    assert box.torques[1] == pytest.approx((-10.0, 0.0, 0.0), abs=1e-9)
    assert box.total_force == pytest.approx((0.0, 20.0, 0.0), abs=1e-9)
    msg = msgs.contacts_state(None, 'bumper_link', groups, 12.5)
    assert msg.header.frame_id == 'bumper_link' and len(msg.states) == 2
    s = msg.states[0]
    assert (s.collision1_name, s.collision2_name) == ('m::l::a', 'box::link::collision')
    assert 'my geom:m::l::a' in s.info and 'other geom:box::link::collision' in s.info
    assert s.total_wrench.force.y == pytest.approx(20.0) and len(s.wrenches) == 2
    assert (s.contact_positions[1].z, s.contact_normals[0].x, s.depths[1]) == (1.0, -1.0, 0.002)


class FakeClient:
    """getContactPoints' answer for read_contacts, and a link frame at the origin."""

    def __init__(self, points):
        self.points = points

    def getContactPoints(self, bodyA, linkIndexA):
        return self.points

    def getCollisionShapeData(self, body, link):
        return [(body, link, 3)]  # one box: a plain convex shape

    def getDynamicsInfo(self, body, link):
        return (1.0,)

    def getLinkState(self, body, link, computeForwardKinematics=0):
        return ((0.0, 0.0, 0.0), (0, 0, 0, 1), None, None, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def _bullet_point(on_a, distance, normal_force, friction1=0.0, friction2=0.0, body_b=7):
    """A getContactPoints tuple: the normal on B points +z (into A, above it)."""
    return (0, 1, body_b, 0, -1, on_a, on_a, (0.0, 0.0, 1.0), distance, normal_force,
            friction1, (1.0, 0.0, 0.0), friction2, (0.0, 1.0, 0.0))


def test_pybullet_contact_points_converted():
    class World:
        client = FakeClient([
            _bullet_point((0.0, 0.0, 0.0), -0.002, 5.0, friction1=-1.0, friction2=0.5),  # touching the base
            _bullet_point((0.22, 0.0, 0.05), -0.001, 2.0),                              # on the bumper
            _bullet_point((0.0, 0.1, 0.0), 0.003, 0.0),                                 # near, not touching
        ])
    base = NamedShape('base_collision', 'box', size=(0.4, 0.3, 0.1), position=(0.0, 0.0, 0.05))
    bumper = NamedShape('bumper_collision', 'box', size=(0.02, 0.28, 0.06), position=(0.21, 0.0, 0.05))
    points = read_contacts(World(), FakeNames(), 1, 0, [base, bumper], 'm', 'l', {'base_collision'})
    assert len(points) == 1  # the bumper's point is not wanted; the near one does not touch
    p = points[0]
    assert (p.collision1, p.collision2) == ('m::l::base_collision', 'other7::link-1::collision')
    assert p.depth == pytest.approx(0.002) and p.normal == (0.0, 0.0, 1.0)
    assert p.force == pytest.approx((-1.0, 0.5, 5.0))  # normal force along the normal + the two frictions
    both = read_contacts(World(), FakeNames(), 1, 0, [base, bumper], 'm', 'l', {'base_collision', 'bumper_collision'})
    assert [q.collision1 for q in both] == ['m::l::base_collision', 'm::l::bumper_collision']


def test_which_way_round_bullet_keeps_a_pair():
    def kind(order, compound=False, concave=False):
        return CollisionKind(order, compound, concave)
    ours = kind((5, 0))
    assert friction_reversed(ours, kind((1, -1)))                       # convex pair: the older one first
    assert not friction_reversed(ours, kind((9, -1)))
    assert not friction_reversed(ours, kind((1, -1), concave=True))     # a plane or static mesh: never first
    assert friction_reversed(ours, kind((9, -1), compound=True))        # a compound before a convex
    assert not friction_reversed(kind((5, 0), compound=True), kind((1, -1)))
    assert friction_reversed(kind((5, 0), compound=True), kind((1, -1), compound=True))
    assert friction_reversed(ours, kind((5, -1)))                       # the same body: its base first


# -- gazebo_ros_multicamera ---------------------------------------------------------------------

def test_stereo_pair_topics_poses_and_baseline(model):
    c = configs(model)['stereo_camera']
    assert c.kind == 'multicamera'
    parts = {spec.camera.name: (spec, part) for spec, part in c.params['parts']}
    left, right = parts['left'], parts['right']
    assert left[1].topics == {'image': '/stereo/left/image_raw', 'info': '/stereo/left/camera_info'}
    assert right[1].topics == {'image': '/stereo/right/image_raw', 'info': '/stereo/right/camera_info'}
    # each <camera><pose> on the sensor's, which sdformat moved from stereo_link to base_link (joint 0.15 0 0.2)
    assert left[0].pose == pytest.approx((0.15, 0.035, 0.2, 0.0, 0.0, 0.0))
    assert right[0].pose == pytest.approx((0.15, -0.035, 0.2, 0.0, 0.0, 0.0))
    assert left[1].frame_id == right[1].frame_id == 'stereo_link'  # upstream: one frameName for both
    assert (left[1].params['baseline'], right[1].params['baseline']) == (0.0, 0.07)
    cam = PinholeCamera(64, 48, 1.0, 0.05, 20.0)
    f = 64 / (2 * math.tan(0.5))
    assert msgs.camera_info(None, 'stereo_link', cam, left[1].params['baseline']).P[3] == 0.0
    assert msgs.camera_info(None, 'stereo_link', cam, right[1].params['baseline']).P[3] == pytest.approx(-f * 0.07)


def test_multicamera_names_without_a_side_and_without_a_camera_name():
    body = ('<sensor type="multicamera" name="s"><camera name="cam_left"><image><width>8</width><height>6</height>'
            '</image></camera><camera name="middle"><image><width>8</width><height>6</height></image></camera>'
            'PLUGIN</sensor>')
    c = sensor_config(_sensor(body, '<plugin name="p" filename="libgazebo_ros_multicamera.so"><hackBaseline>0.1'
                                    '</hackBaseline><frameName>f</frameName></plugin>'), '', 'r')
    assert [spec.camera.name for spec, _ in c.params['parts']] == ['cam_left']
    assert c.params['parts'][0][1].topics['image'] == '/left/image_raw'  # no <cameraName>: /left
    assert c.params['parts'][0][1].params['baseline'] == 0.0
    assert any("'middle'" in w for w in c.warnings)
    pair = body.replace('"middle"', '"cam_right"')
    c = sensor_config(_sensor(pair, '<plugin name="p" filename="libgazebo_ros_multicamera.so"><updateRate>fast'
                                    '</updateRate><frameName>f</frameName></plugin>'), '', 'r')
    assert len(c.params['parts']) == 2
    assert len(c.warnings) == len(set(c.warnings)) and c.warnings  # one plugin, each warning once


# -- gazebo_ros_openni_kinect -------------------------------------------------------------------

def test_kinect_topics_and_cutoffs_as_declared(model):
    c = configs(model)['kinect']
    assert c.kind == 'depth' and c.frame_id == 'kinect_link' and c.rate == 10.0
    assert c.topics == {'image': '/kinect/rgb/image_raw', 'info': '/kinect/rgb/camera_info',
                        'depth': '/kinect/depth/image_raw', 'depth_info': '/kinect/depth/camera_info',
                        'points': '/kinect/depth/points'}
    assert (c.params['cutoff'], c.params['cutoff_max']) == (0.5, 3.0)


def test_kinect_defaults_and_a_misspelt_info_topic():
    depth = ('<sensor type="depth" name="k"><camera><image><width>8</width><height>6</height></image></camera>'
             'PLUGIN</sensor>')
    c = sensor_config(_sensor(depth, '<plugin name="p" filename="libgazebo_ros_openni_kinect.so"><cameraName>cam'
                                     '</cameraName><frameName>f</frameName><depthImageInfoTopicName>d/info'
                                     '</depthImageInfoTopicName></plugin>'), '', 'r')
    assert c.topics == {'image': '/cam/ir/image_raw', 'info': '/cam/ir/camera_info',
                        'depth': '/cam/depth/image_raw', 'depth_info': '/cam/depth/camera_info',
                        'points': '/cam/points'}
    assert (c.params['cutoff'], c.params['cutoff_max']) == (0.4, 5.0)
    assert any('<depthImageInfoTopicName>' in w for w in c.warnings)


def test_kinect_cutoff_is_strict_on_both_sides():
    depth = np.array([[0.5, 0.50001, 2.9999, 3.0]], dtype=np.float32)
    out = mask_depth(depth, 0.5, 3.0)
    assert np.isnan(out[0, 0]) and np.isnan(out[0, 3])
    assert out[0, 1] == pytest.approx(0.50001) and out[0, 2] == pytest.approx(2.9999)


# -- parsing and what racebot does not simulate -------------------------------------------------

def test_urdf_reads_every_camera_and_the_contact_collisions(model):
    specs = {s.name: s for s in model.sensors}
    stereo = specs['stereo_camera']
    assert [c.name for c in stereo.cameras] == ['left', 'right'] and stereo.camera is stereo.cameras[0]
    assert stereo.cameras[1].pose == (0.0, -0.035, 0.0, 0.0, 0.0, 0.0)
    assert specs['bumper'].contact_collisions == ['base_link_fixed_joint_lump__bumper_link_collision_1']


def test_a_plugin_racebot_does_not_simulate_is_named(model):
    specs = {s.name: s for s in model.sensors}
    assert sensor_config(specs['lab_lidar'], '/', 'sensor_robot') is None
    warning, = (REGISTRY.not_simulated('sensor_robot', p, specs['lab_lidar']) for p in specs['lab_lidar'].plugins)
    assert "sensor 'lab_lidar' (type ray): plugin 'lab_lidar_controller' (liblab_lidar_plugin.so)" in warning
    assert [REGISTRY.not_simulated('sensor_robot', p, specs['sonar']) for p in specs['sonar'].plugins] == [None]
