"""Gazebo's loader rules (issue 37 item 4), on a real PhysicsWorld (PyBullet DIRECT), no ROS master.

1. A missing mesh: Gazebo 11 keeps the model (common/MeshManager.cc Load logs "Unable to find file", physics/
   MeshShape.cc Init goes on without the mesh): its links, their inertia and other shapes stay; one warning names
   the file and a file of that name in other capitals in its folder.
2. A link with no collision and no visual (sdformat 9's Link::Load asks for neither): the link and its model
   stay, a body with mass, or a static one with no shape.
3. A URDF's <gazebo><static>true</static></gazebo> (no reference) is the model's <static> (sdformat 9
   parser_urdf.cc: ParseSDFExtension, InsertSDFExtensionRobot; the last such block decides): held still.
"""
import os

import pytest

from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.engine.physics import PhysicsWorld

import mesh_fixtures  # tests/integration, shared with the rostest node

INERTIA = '<inertia><ixx>0.1</ixx><iyy>0.2</iyy><izz>0.3</izz></inertia>'


@pytest.fixture(autouse=True)
def isolated(tmp_path, monkeypatch):
    monkeypatch.setenv('RACEBOT_MESH_CACHE', str(tmp_path / 'cache'))
    monkeypatch.setenv('HOME', str(tmp_path / 'home'))
    monkeypatch.setenv('GAZEBO_MODEL_PATH', '')
    return tmp_path


@pytest.fixture
def world():
    w = PhysicsWorld(step_size=0.001)
    yield w
    w.close()


def world_file(folder, models):
    path = os.path.join(str(folder), 'rules.world')
    with open(path, 'w') as f:
        f.write('<sdf version="1.6"><world name="w">%s</world></sdf>' % models)
    return path


def mesh_collision(name, uri):
    return '<collision name="%s"><geometry><mesh><uri>%s</uri></mesh></geometry></collision>' % (name, uri)


def shapes(world, model):
    return world.client.getCollisionShapeData(world.bodies[model].id, -1)


def height(world, model):
    return world.bodies[model].pose().position[2]


def step(world, n=500):
    for _ in range(n):
        world.step()


# -- 1. a missing mesh ------------------------------------------------------------------------------------------
def test_a_model_whose_mesh_is_missing_stays_with_its_inertia_and_other_shapes_and_one_warning(isolated, world):
    on_disk = mesh_fixtures.write_mesh(mesh_fixtures.box((1, 1, 1)),
                                       str(isolated / 'meshes' / 'aws_Spotlight_01_collision.DAE'))
    uri = 'meshes/aws_spotlight_01_collision.DAE'
    spec = sdf_reader.load_world(world_file(isolated, (
        '<model name="spotlight"><pose>0 0 5 0 0 0</pose><link name="link"><inertial><mass>3</mass>%s</inertial>'
        '%s<collision name="base"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>'
        '<visual name="v"><geometry><mesh><uri>%s</uri></mesh></geometry></visual></link></model>'
        '<model name="only_mesh"><pose>3 0 5 0 0 0</pose><link name="link"><inertial><mass>2</mass></inertial>'
        '%s</link></model>') % (INERTIA, mesh_collision('c', uri), uri, mesh_collision('c', uri))))
    assert len(spec.warnings) == 1, spec.warnings  # one file, three elements: one warning
    warning = spec.warnings[0]
    assert '%s not found' % uri in warning and 'did you mean %s?' % on_disk in warning
    assert world.load_world(spec, warn=pytest.fail) == ['spotlight', 'only_mesh']
    mass, _, inertia = world.client.getDynamicsInfo(world.bodies['spotlight'].id, -1)[:3]
    assert mass == 3.0 and inertia == pytest.approx((0.1, 0.2, 0.3))
    assert len(shapes(world, 'spotlight')) == 1  # the box: the link's other collision
    assert world.client.getDynamicsInfo(world.bodies['only_mesh'].id, -1)[0] == 2.0
    assert shapes(world, 'only_mesh') == ()


def test_a_urdf_mesh_missing_from_a_visual_and_a_collision_is_one_warning_and_the_link_keeps_its_inertia(
        isolated, world):
    on_disk = mesh_fixtures.write_mesh(mesh_fixtures.box((1, 1, 1)), str(isolated / 'm' / 'Body.STL'))
    missing = str(isolated / 'm' / 'body.stl')
    geometry = '<geometry><mesh filename="file://%s"/></geometry>' % missing
    xml = ('<robot name="r"><link name="base"><inertial><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" '
           'iyy="0.2" iyz="0" izz="0.3"/></inertial><visual>%s</visual><collision>%s</collision><collision>'
           '<geometry><box size="0.1 0.1 0.1"/></geometry></collision></link></robot>' % (geometry, geometry))
    warnings = []
    body = world.spawn_urdf('r', urdf_reader.parse_urdf(xml), xml, warn=warnings.append)
    assert len(warnings) == 1, warnings
    assert "link 'base' <collision> #1, link 'base' <visual> #1" in warnings[0]
    assert 'did you mean %s?' % on_disk in warnings[0]
    mass, _, inertia = world.client.getDynamicsInfo(body.id, -1)[:3]
    assert mass == 2.0 and inertia == pytest.approx((0.1, 0.2, 0.3))
    assert len(world.client.getCollisionShapeData(body.id, -1)) == 1


# -- 2. a link with no collision and no visual ---------------------------------------------------------------------
def test_links_without_collision_or_visual_are_bodies_and_their_models_stay(world):
    spec = sdf_reader.parse_world(
        '<sdf version="1.6"><world name="w">'
        '<model name="ground_plane"><static>true</static><link name="link"/></model>'
        '<model name="weight"><pose>0 0 2 0 0 0</pose><link name="link"><inertial><mass>4</mass>%s</inertial>'
        '</link></model></world></sdf>' % INERTIA)
    assert spec.warnings == []
    assert world.load_world(spec, warn=pytest.fail) == ['ground_plane', 'weight']
    assert world.bodies['ground_plane'].static and shapes(world, 'ground_plane') == ()
    mass, _, inertia = world.client.getDynamicsInfo(world.bodies['weight'].id, -1)[:3]
    assert mass == 4.0 and inertia == pytest.approx((0.1, 0.2, 0.3))
    step(world)
    assert height(world, 'ground_plane') == 0.0
    assert height(world, 'weight') < 1.0  # nothing to land on: it falls, as in Gazebo


def test_a_urdf_link_with_only_an_inertial_is_spawned(world):
    xml = ('<robot name="r"><link name="base"><inertial><mass value="1.5"/><inertia ixx="0.1" ixy="0" ixz="0" '
           'iyy="0.1" iyz="0" izz="0.1"/></inertial></link></robot>')
    body = world.spawn_urdf('r', urdf_reader.parse_urdf(xml), xml, position=(0, 0, 1))
    assert world.client.getDynamicsInfo(body.id, -1)[0] == 1.5 and 'r' in world.bodies


# -- 3. <gazebo><static>true</static></gazebo> ---------------------------------------------------------------------
BUILDING = ('<link name="walls"><inertial><mass value="500"/><inertia ixx="100" ixy="0" ixz="0" iyy="100" iyz="0" '
            'izz="100"/></inertial><collision><geometry><box size="4 4 3"/></geometry></collision></link>')


@pytest.mark.parametrize('blocks, static', [
    ('<gazebo><static>true</static></gazebo>', True),
    ('<gazebo>\n  <static>\n    true\n  </static>\n</gazebo>', True),
    ('<gazebo><static>1</static></gazebo><gazebo reference="walls"><mu1>0.5</mu1></gazebo>', True),
    ('', False),
    ('<gazebo><static>false</static></gazebo>', False),
    # every block without reference writes its <static> (false without one) into the model: the last decides
    ('<gazebo><static>true</static></gazebo><gazebo><plugin name="p" filename="libgazebo_ros_template.so"/>'
     '</gazebo>', False),
])
def test_a_urdf_gazebo_static_holds_the_model_where_it_is_spawned(world, blocks, static):
    xml = '<robot name="building">%s%s</robot>' % (BUILDING, blocks)
    model = urdf_reader.parse_urdf(xml)
    assert model.static is static
    assert any('the last <gazebo> block' in w for w in model.warnings) is ('plugin' in blocks)
    body = world.spawn_urdf('building', model, xml, position=(0, 0, 5))
    assert body.static is static
    step(world)
    assert (height(world, 'building') == pytest.approx(5.0)) is static
