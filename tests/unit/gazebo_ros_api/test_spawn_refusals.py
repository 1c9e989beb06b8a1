"""No robot or world description takes the world down or leaves part of itself in it (issue 29 item 2).

A spawn is answered with a SpawnModelResponse, spawned or refused with the reason after upstream's status
words; a refused model leaves no PyBullet body behind and the world steps on. Through gazebo_ros_api's
spawn services with real rospy (no master), gazebo_ros_control and model plugins attached, as in the world
server. The hypothesis test mutates a real-shaped arm (URDF) and a real-shaped SDF model.
"""
import math
import os
import xml.etree.ElementTree as ET

import pytest
import rospy
from gazebo_msgs.srv import DeleteModelRequest, SpawnModelRequest
from geometry_msgs.msg import Pose, Quaternion
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.urdf_spawn import MAX_BULLET_LINKS
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_plugins.plugin_manager import PluginManager
from racebot_sim_bridge.gazebo_ros_api.services import GazeboServices
from racebot_sim_bridge.gazebo_ros_api.spawn_services import SPAWN_NOT_LOADED
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from fakes import FakeLog

WORLD = ('<sdf version="1.6"><world name="w"><physics type="ode"><max_step_size>0.001</max_step_size></physics>'
         '<model name="ground_plane"><static>true</static><link name="link"><collision name="c"><geometry><plane>'
         '<normal>0 0 1</normal><size>100 100</size></plane></geometry></collision></link></model>'
         '<model name="crate"><pose>3 0 0.5 0 0 0</pose><link name="link"><inertial><mass>1</mass></inertial>'
         '<collision name="c"><geometry><box><size>0.5 0.5 0.5</size></box></geometry></collision></link></model>'
         '</world></sdf>')
INERTIA = '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>'


def _link(name, mass='1', geometry='<box size="0.1 0.1 0.3"/>'):
    return ('<link name="%s"><inertial><origin xyz="0 0 0.1"/><mass value="%s"/>%s</inertial>'
            '<visual><origin xyz="0 0 0.1"/><geometry>%s</geometry></visual>'
            '<collision><origin xyz="0 0 0.1"/><geometry>%s</geometry></collision></link>\n'
            % (name, mass, INERTIA, geometry, geometry))


def _joint(name, parent, child, kind='revolute', z='0.3', extra=''):
    return ('<joint name="%s" type="%s"><parent link="%s"/><child link="%s"/><origin xyz="0 0 %s" rpy="0 0 0"/>'
            '<axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="50" velocity="2"/>'
            '<dynamics damping="0.1" friction="0.01"/>%s</joint>\n' % (name, kind, parent, child, z, extra))


def chain(links):
    """A fixed-base chain of `links` links, root first."""
    body = '<link name="world"/>\n' + ''.join(_link('l%d' % i) for i in range(links))
    body += _joint('j0', 'world', 'l0', 'fixed')
    body += ''.join(_joint('j%d' % i, 'l%d' % (i - 1), 'l%d' % i, z='0.05') for i in range(1, links))
    return '<robot name="chain">\n%s</robot>' % body


# A real-shaped arm, as an arm package's xacro writes it: the world link last, a lumped tool flange, a gripper
# whose second finger mimics the first, transmissions, gazebo_ros_control, <gazebo reference> friction.
ARM = ('<robot name="arm">\n' + _link('base_link', '4', '<cylinder radius="0.08" length="0.1"/>')
       + _link('shoulder') + _link('upper_arm') + _link('forearm')
       + '<link name="tool0"/>\n' + _link('finger_l', '0.05', '<box size="0.01 0.02 0.05"/>')
       + _link('finger_r', '0.05', '<box size="0.01 0.02 0.05"/>')
       + _joint('base_joint', 'world', 'base_link', 'fixed', '0')
       + _joint('shoulder_pan', 'base_link', 'shoulder', z='0.1')
       + _joint('shoulder_lift', 'shoulder', 'upper_arm')
       + _joint('elbow', 'upper_arm', 'forearm')
       + _joint('flange', 'forearm', 'tool0', 'fixed')
       + _joint('finger_l_joint', 'forearm', 'finger_l', 'prismatic', '0.35')
       + _joint('finger_r_joint', 'forearm', 'finger_r', 'prismatic', '0.35',
                '<mimic joint="finger_l_joint" multiplier="-1" offset="0"/>')
       + ''.join('<transmission name="t_%s"><type>transmission_interface/SimpleTransmission</type>'
                 '<joint name="%s"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>'
                 '</joint><actuator name="m_%s"><mechanicalReduction>1</mechanicalReduction></actuator>'
                 '</transmission>\n' % (j, j, j) for j in ('shoulder_pan', 'shoulder_lift', 'elbow'))
       + '<gazebo reference="forearm"><mu1>0.8</mu1><mu2>0.8</mu2></gazebo>\n'
       + '<gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>\n'
       + '<link name="world"/>\n</robot>')

# A real-shaped SDF model: a table (static, one link) and a robot (two links, a joint: the URDF path).
SDF = ('<sdf version="1.6"><model name="thing"><pose>0 0 0.5 0 0 0</pose>'
       '<link name="base"><inertial><mass>2</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia>'
       '</inertial><collision name="c"><geometry><box><size>0.4 0.4 0.1</size></box></geometry></collision>'
       '<visual name="v"><geometry><box><size>0.4 0.4 0.1</size></box></geometry></visual></link>'
       '<link name="top"><pose>0 0 0.2 0 0 0</pose><inertial><mass>0.5</mass></inertial>'
       '<collision name="c"><geometry><cylinder><radius>0.05</radius><length>0.2</length></cylinder></geometry>'
       '</collision></link>'
       '<joint name="yaw" type="revolute"><parent>base</parent><child>top</child><axis><xyz>0 0 1</xyz>'
       '<limit><lower>-1</lower><upper>1</upper></limit></axis></joint></model></sdf>')


@pytest.fixture(scope='module')
def world():
    sim = Simulator(sdf_reader.parse_world(WORLD), None, FakeLog(), lambda path: None)
    plugins = PluginManager(rospy, sim)
    GazeboRosControlPlugin.attach(sim, rospy)
    services = GazeboServices(rospy, sim, '/gazebo')
    yield sim, services
    services.shutdown()
    plugins.close()
    sim.close()


def _request(name, xml):
    return SpawnModelRequest(model_name=name, model_xml=xml, robot_namespace='',
                             initial_pose=Pose(orientation=Quaternion(0, 0, 0, 1)), reference_frame='')


def _snapshot(sim):
    return sim.world.client.getNumBodies(), sorted(sim.world.bodies), sorted(sim.robots)


def spawn_and_check(sim, services, spawn, name, xml):
    """Spawns through the service `spawn`; checks the answer and that a refusal left nothing behind, deletes
    a spawned model, steps the world; returns the response."""
    before = _snapshot(sim)
    res = spawn(_request(name, xml))
    assert isinstance(res.success, bool) and res.status_message
    if res.success:
        assert name in sim.world.bodies
        assert services.delete_model(DeleteModelRequest(model_name=name)).success
    else:
        assert res.status_message.count(':') >= 1 and len(res.status_message) > 40, res.status_message
    assert _snapshot(sim) == before, res.status_message  # nothing of it stays behind
    t = sim.time
    for _ in range(5):
        sim.step()
    assert sim.time > t
    for body in sim.world.bodies.values():  # the world's own bodies still answer, with finite states
        assert all(math.isfinite(v) for v in body.pose().position)
    return res


def test_the_real_shaped_arm_with_its_world_link_last_spawns(world):
    sim, services = world
    res = services.spawn_urdf_model(_request('arm', ARM))
    assert res.success, res.status_message
    assert {'shoulder_pan', 'shoulder_lift', 'elbow', 'finger_l_joint'} <= set(sim.body('arm').joints)
    assert services.delete_model(DeleteModelRequest(model_name='arm')).success


def test_a_chain_pybullet_cannot_report_is_refused_and_leaves_nothing(world):
    sim, services = world
    assert spawn_and_check(sim, services, services.spawn_urdf_model, 'chain', chain(MAX_BULLET_LINKS - 1)).success
    res = spawn_and_check(sim, services, services.spawn_urdf_model, 'chain', chain(200))
    assert not res.success
    assert "'chain' has 200 links" in res.status_message  # l0 is merged into world
    assert 'more than %d' % MAX_BULLET_LINKS in res.status_message


def test_a_refusal_keeps_upstreams_words_and_gives_the_reason(world):
    sim, services = world
    res = spawn_and_check(sim, services, services.spawn_urdf_model, 'ghost', '<robot name="x"/>')
    assert res.status_message.startswith(SPAWN_NOT_LOADED % 'ghost' + ': the URDF is not valid: ')
    assert 'no links' in res.status_message


# -- the hypothesis test: mutated descriptions -------------------------------------------------------------
BAD_NUMBERS = ['nan', 'inf', '-inf', '1e308', '-1e308', '0', '-1', '1e-300', 'x']


def _numeric_attributes(root):
    """(element, attribute) of every number-holding attribute: origins, limits, inertia, mass, dynamics."""
    found = []
    for elem in root.iter():
        for attr in ('xyz', 'rpy', 'value', 'lower', 'upper', 'effort', 'velocity', 'damping', 'friction',
                     'ixx', 'iyy', 'izz', 'ixy', 'radius', 'length', 'size', 'multiplier'):
            if elem.get(attr) is not None:
                found.append((elem, attr))
    return found


def _mutate_urdf(root, op, pick, number, mesh_dir):
    links = root.findall('link')
    joints = root.findall('joint')
    if op == 'shuffle':
        for link in links:
            root.remove(link)
        order = sorted(links, key=lambda e: (hash(e.get('name')) * (pick + 1)) % 9973)
        for i, link in enumerate(order):
            root.insert(i, link)
    elif op == 'no_inertial':
        link = links[pick % len(links)]
        for el in link.findall('inertial'):
            link.remove(el)
    elif op == 'zero_inertia':
        for el in root.iter('inertia'):
            for key in ('ixx', 'iyy', 'izz'):
                el.set(key, '0')
        for el in root.iter('mass'):
            el.set('value', '0')
    elif op == 'bad_number':
        elem, attr = _numeric_attributes(root)[pick % len(_numeric_attributes(root))]
        parts = (elem.get(attr) or '0').split()
        parts[pick % len(parts)] = number
        elem.set(attr, ' '.join(parts))
    elif op == 'two_roots':
        root.append(ET.fromstring(_link('orphan')))
    elif op == 'cycle':
        joint = joints[pick % len(joints)]
        child = joint.find('child').get('link')
        root.append(ET.fromstring(_joint('back', child, 'world' if pick % 2 else 'base_link')))
    elif op == 'duplicate':
        root.append(ET.fromstring(ET.tostring(links[pick % len(links)] if pick % 2 else joints[pick % len(joints)])))
    elif op == 'long_chain':
        parent = 'forearm'
        for i in range(pick % 100):
            root.append(ET.fromstring(_link('c%d' % i, geometry='<sphere radius="0.01"/>')))
            root.append(ET.fromstring(_joint('cj%d' % i, parent, 'c%d' % i, z='0.02')))
            parent = 'c%d' % i
    elif op == 'mimic_loop':
        for joint in joints:
            if joint.get('name') == 'finger_l_joint':
                joint.append(ET.fromstring('<mimic joint="finger_r_joint"/>'))
            if joint.get('name') == 'elbow':
                joint.append(ET.fromstring('<mimic joint="elbow" multiplier="%s"/>' % number))
    elif op == 'mesh':
        kinds = {0: ('empty.stl', b''), 1: ('garbage.stl', b'\xff\x00 not a mesh' * 7), 2: ('missing.dae', None),
                 3: ('flat.obj', b'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n'), 4: ('nan.obj', b'v nan 0 0\nv 1 0 0\n'
                                                                             b'v 0 1 0\nf 1 2 3\n')}
        filename, data = kinds[pick % len(kinds)]
        path = os.path.join(mesh_dir, filename)
        if data is not None:
            with open(path, 'wb') as f:
                f.write(data)
        geometry = links[pick % len(links)].find('collision/geometry')
        if geometry is not None:
            for child in list(geometry):
                geometry.remove(child)
            geometry.append(ET.fromstring('<mesh filename="file://%s" scale="1 1 %s"/>' % (path, number)))
    elif op == 'rename_non_utf8':
        links[pick % len(links)].set('name', 'l\udcff\x7f')  # bytes that were not UTF-8, as surrogateescape reads
    elif op == 'truncate':
        return ET.tostring(root, encoding='unicode')[:-(pick % 40 + 1)]
    return None


URDF_OPS = ['shuffle', 'no_inertial', 'zero_inertia', 'bad_number', 'two_roots', 'cycle', 'duplicate',
            'long_chain', 'mimic_loop', 'mesh', 'rename_non_utf8', 'truncate']
SDF_OPS = ['bad_number', 'no_inertial', 'zero_inertia', 'duplicate', 'two_roots', 'truncate', 'mesh']


def _mutate_sdf(root, op, pick, number, mesh_dir):
    model = root.find('model')
    links = model.findall('link')
    if op == 'bad_number':
        texts = [e for e in root.iter() if e.text and e.text.strip() and e.tag not in ('parent', 'child')]
        elem = texts[pick % len(texts)]
        parts = elem.text.split()
        parts[pick % len(parts)] = number
        elem.text = ' '.join(parts)
    elif op == 'no_inertial':
        link = links[pick % len(links)]
        for el in link.findall('inertial'):
            link.remove(el)
    elif op == 'zero_inertia':
        for el in root.iter('mass'):
            el.text = '0'
    elif op == 'duplicate':
        model.append(ET.fromstring(ET.tostring(links[pick % len(links)])))
    elif op == 'two_roots':
        joint = model.find('joint')
        joint.find('parent').text = 'top'  # a joint from a link to itself
    elif op == 'truncate':
        return ET.tostring(root, encoding='unicode')[:-(pick % 40 + 1)]
    elif op == 'mesh':
        path = os.path.join(mesh_dir, 'sdf_empty.stl')
        open(path, 'wb').close()
        geometry = links[pick % len(links)].find('collision/geometry')
        for child in list(geometry):
            geometry.remove(child)
        geometry.append(ET.fromstring('<mesh><uri>file://%s</uri></mesh>' % path))
    return None


MUTATION = st.tuples(st.integers(0, 10 ** 6), st.sampled_from(BAD_NUMBERS))


@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(ops=st.lists(st.tuples(st.sampled_from(URDF_OPS), MUTATION), min_size=1, max_size=3))
def test_a_mutated_urdf_is_spawned_or_refused_and_leaves_nothing(world, tmp_path_factory, ops):
    sim, services = world
    root = ET.fromstring(ARM)
    mesh_dir = str(tmp_path_factory.mktemp('meshes'))
    text = None
    for op, (pick, number) in ops:
        text = _mutate_urdf(root, op, pick, number, mesh_dir)
        if text is not None:
            break
    text = text if text is not None else ET.tostring(root, encoding='unicode')
    spawn_and_check(sim, services, services.spawn_urdf_model, 'mutant', text)


@settings(max_examples=20, deadline=None, suppress_health_check=list(HealthCheck))
@given(ops=st.lists(st.tuples(st.sampled_from(SDF_OPS), MUTATION), min_size=1, max_size=3),
       robot=st.booleans())
def test_a_mutated_sdf_is_spawned_or_refused_and_leaves_nothing(world, tmp_path_factory, ops, robot):
    sim, services = world
    root = ET.fromstring(SDF)
    if not robot:  # one link, no joint: built as SDF bodies, not through the URDF path
        model = root.find('model')
        model.remove(model.find('joint'))
    mesh_dir = str(tmp_path_factory.mktemp('meshes'))
    text = None
    for op, (pick, number) in ops:
        if op == 'two_roots' and not robot:
            continue
        text = _mutate_sdf(root, op, pick, number, mesh_dir)
        if text is not None:
            break
    text = text if text is not None else ET.tostring(root, encoding='unicode')
    spawn_and_check(sim, services, services.spawn_sdf_model, 'mutant', text)


@pytest.mark.parametrize('spawn, xml, words, reason', [
    ('spawn_urdf_model', '', 'SpawnModel: Failure - entity format is invalid.', 'The model_xml is empty'),
    ('spawn_urdf_model', '<robot name="x"><link name="a"></robot',
     'SpawnModel: Failure - entity format is invalid.', 'The model_xml is not XML (unclosed token: line 1'),
    ('spawn_urdf_model', '<sdf version="1.6"><model name="m"/></sdf>',
     'SpawnModel: Failure - entity format is invalid.', 'The root element is <sdf>; a URDF has <robot> (for SDF, '
                                                        'call spawn_sdf_model)'),
    ('spawn_sdf_model', '  ', 'GazeboRosApiPlugin SpawnModel Failure: input model_xml not SDF or URDF, or cannot be '
                              'converted to Gazebo compatible format.', 'The model_xml is empty'),
    ('spawn_sdf_model', '<world/>', 'GazeboRosApiPlugin SpawnModel Failure: input model_xml not SDF or URDF, or '
                                    'cannot be converted to Gazebo compatible format.',
     'The root element is <world>; SDF has <sdf> (or <gazebo>), URDF <robot>'),
])
def test_a_document_of_the_wrong_format_is_refused_with_upstreams_words_and_what_it_is(world, spawn, xml, words,
                                                                                        reason):
    sim, services = world
    res = getattr(services, spawn)(_request('ghost', xml))
    assert not res.success
    assert res.status_message.startswith(words + ' ' + reason), res.status_message
    assert 'ghost' not in sim.world.bodies
