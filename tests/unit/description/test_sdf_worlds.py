"""World files as sdformat 9 and Gazebo 11 read them (issue 29, item 3): nested models (<include> and <model>
inside a <model>), a blank line before <?xml ...?>, worlds and files found through the resource path
(GAZEBO_RESOURCE_PATH and packages' gazebo_media_path exports), relative file:// URIs as SystemPaths finds them.

The fixtures are written as the community writes them: a model library (model.config + model.sdf per model) on
GAZEBO_MODEL_PATH, a catkin package exporting its media and model folders to gazebo_ros. No master; PyBullet for
the one test that checks what a body is built as.
"""
import math
import textwrap

import pytest

from racebot_sim_bridge import world_server
from racebot_sim_bridge.description import model_path, sdf_reader, sdf_urdf, spawn_xml, xml_document
from racebot_sim_bridge.engine.physics import PhysicsWorld

from sdf_models import ROOM, TABLE, WHEEL, model_config, world, write_model

import mesh_fixtures  # tests/integration, shared with the rostest node

HALF_PI = math.pi / 2


@pytest.fixture(autouse=True)
def library(tmp_path, monkeypatch):
    """A model library on GAZEBO_MODEL_PATH (table, wheel), an empty ROS package path, no resource path, an own
    mesh cache and HOME; the working directory is a folder of its own."""
    models = tmp_path / 'models'
    write_model(models, 'table', TABLE)
    write_model(models, 'wheel', WHEEL)
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(models))
    monkeypatch.setenv('GAZEBO_RESOURCE_PATH', '')
    monkeypatch.setenv('RACEBOT_MESH_CACHE', str(tmp_path / 'cache'))
    monkeypatch.setenv('HOME', str(tmp_path / 'home'))
    (tmp_path / 'pkgs').mkdir()
    monkeypatch.setenv('ROS_PACKAGE_PATH', str(tmp_path / 'pkgs'))
    (tmp_path / 'cwd').mkdir()
    monkeypatch.chdir(tmp_path / 'cwd')
    return models


def rounded(pose):
    return tuple(round(v, 9) + 0.0 for v in pose)


# -- <include> and <model> inside a <model> ---------------------------------------------------------

def test_a_model_holding_includes_and_a_nested_model_is_one_model_with_scoped_links():
    parsed = sdf_reader.parse_world(ROOM)
    assert parsed.warnings == []
    assert [m.name for m in parsed.models] == ['ground_plane', 'room']
    room = parsed.model('room')
    # Gazebo's order: the model's own links (an include's where it stood), then the nested models' depth first
    assert [link.name for link in room.links] == ['floor', 'table_a::link', 'table_b::link', 'shelf::board',
                                                  'shelf::box::link']
    assert rounded(room.link('table_b::link').pose) == rounded((-1, 0, 0.5, 0, 0, HALF_PI))


def test_poses_are_composed_through_every_level():
    room = sdf_reader.parse_world(ROOM).model('room')
    # room at (10, 0) turned 90 degrees: its x is the world's y
    for link, expected in (('table_a::link', (10.0, 1.0, 0.5)), ('shelf::board', (8.0, 0.0, 1.0)),
                           # shelf (0, 2) -> box (0.2, 0, yaw 90) -> link (0.1, 0, 1.1): (0.2, 2.1, 1.1) in room
                           ('shelf::box::link', (7.9, 0.2, 1.1))):
        xyz, _ = room.world_pose_of(link)
        assert xyz == pytest.approx(expected, abs=1e-9), link


def test_a_nested_model_is_static_by_its_own_static_and_an_included_one_by_the_model(tmp_path):
    """Gazebo 11: Model::Load sets a nested model's static from its own <static> (default false), whatever the
    model around it says; an included model's links are the model's own (sdformat flattens them into it)."""
    room = sdf_reader.parse_world(ROOM).model('room')
    assert room.static
    assert [link.is_static(room) for link in room.links] == [True, True, True, True, False]
    physics = PhysicsWorld()
    try:
        body = physics.add_sdf_model(room)
        masses = {name: physics.client.getDynamicsInfo(body_id, -1)[0] for name, body_id in body.extra_bodies}
        assert masses['shelf::board'] == 0.0 and masses['table_a::link'] == 0.0
        assert masses['shelf::box::link'] == 1.0  # SDF's default mass: it falls, as in Gazebo
    finally:
        physics.close()


def test_the_first_static_after_flattening_is_the_models():
    """sdformat keeps every <static> of a flattened include and Gazebo reads the first: a model that says nothing
    before including a static model is static; one that says false first is not."""
    link = '<link name="own"><collision name="c"><geometry><sphere><radius>1</radius></sphere></geometry>' \
           '</collision></link>'
    parsed = sdf_reader.parse_world(world(
        '<model name="quiet"><include><uri>model://table</uri></include>%s</model>'
        '<model name="dynamic"><static>false</static><include><uri>model://table</uri></include>%s</model>'
        '<model name="overridden"><include><uri>model://table</uri><static>false</static></include>%s</model>'
        % (link, link, link)))
    assert parsed.warnings == []
    assert [m.static for m in parsed.models] == [True, False, False]


def test_an_included_models_joints_and_plugins_follow_its_new_names():
    parsed = sdf_reader.parse_world(world("""
      <model name="cart">
        <pose>0 5 0.2 0 0 0</pose>
        <link name="chassis">
          <collision name="c"><geometry><box><size>1 0.5 0.1</size></box></geometry></collision>
        </link>
        <include>
          <uri>model://wheel</uri>
          <name>front</name>
          <pose>0.5 0 0 0 0 1.5707963267948966</pose>
        </include>
        <joint name="axle" type="revolute">
          <parent>chassis</parent>
          <child>front::rim</child>
          <axis><xyz>0 0 1</xyz></axis>
        </joint>
      </model>"""))
    assert parsed.warnings == []
    cart = parsed.model('cart')
    assert [link.name for link in cart.links] == ['chassis', 'front::rim', 'front::hub']
    spin, axle = cart.joints
    assert (spin.name, spin.parent, spin.child) == ('front::spin', 'front::rim', 'front::hub')
    assert (axle.parent, axle.child) == ('chassis', 'front::rim')
    # the wheel's x axis, in the cart's frame: the include turned the wheel by 90 degrees
    assert spin.axis_in_model and spin.axis == pytest.approx((0.0, 1.0, 0.0), abs=1e-12)
    (plugin,) = cart.plugins
    assert '<jointName>front::spin</jointName>' in plugin  # sdformat renames the plugin's reference too
    conversion = sdf_urdf.model_urdf(cart)  # one tree: the URDF path can simulate it
    assert sorted(j.get('name') for j in conversion.root.findall('joint')) == ['axle', 'front::spin']


def test_joints_of_nested_models_find_their_links_as_gazebo_does():
    """Joint::Load: a link name is looked for in the joint's own model, then in each model around it."""
    sphere = '<collision name="c"><geometry><sphere><radius>0.1</radius></sphere></geometry></collision>'
    parsed = sdf_reader.parse_world(world("""
      <model name="arm">
        <link name="base">%(s)s</link>
        <model name="elbow">
          <pose>0 0 1 0 0 1.5707963267948966</pose>
          <link name="upper">%(s)s</link>
          <link name="lower"><pose>0 0 0.5 0 0 0</pose>%(s)s</link>
          <joint name="bend" type="revolute">
            <parent>upper</parent><child>lower</child>
            <axis><xyz>1 0 0</xyz><use_parent_model_frame>true</use_parent_model_frame></axis>
          </joint>
          <joint name="mount" type="fixed"><parent>base</parent><child>upper</child></joint>
        </model>
      </model>""" % {'s': sphere}))
    assert parsed.warnings == []
    arm = parsed.model('arm')
    bend, mount = arm.joints
    assert (bend.name, bend.parent, bend.child) == ('elbow::bend', 'elbow::upper', 'elbow::lower')
    assert (mount.name, mount.parent, mount.child) == ('elbow::mount', 'base', 'elbow::upper')
    assert bend.axis == pytest.approx((0.0, 1.0, 0.0), abs=1e-12)  # the elbow's x, turned into the arm's frame
    sdf_urdf.model_urdf(arm)


def test_a_joint_deep_in_nested_models_finds_a_link_of_the_outer_model():
    sphere = '<collision name="c"><geometry><sphere><radius>0.1</radius></sphere></geometry></collision>'
    parsed = sdf_reader.parse_world(world(
        '<model name="m"><link name="base">%(s)s</link><model name="a"><model name="b"><link name="tip">%(s)s</link>'
        '<joint name="hold" type="fixed"><parent>base</parent><child>tip</child></joint></model></model></model>'
        % {'s': sphere}))
    (hold,) = parsed.model('m').joints
    assert (hold.name, hold.parent, hold.child) == ('a::b::hold', 'base', 'a::b::tip')


def test_a_saved_state_poses_a_nested_models_links_in_the_world():
    sphere = '<collision name="c"><geometry><sphere><radius>0.1</radius></sphere></geometry></collision>'
    parsed = sdf_reader.parse_world(world(
        '<model name="m"><pose>1 0 0 0 0 0</pose><link name="base">%(s)s</link>'
        '<model name="inner"><link name="l">%(s)s</link></model></model>'
        '<state world_name="default"><model name="m"><pose>2 0 0 0 0 0</pose>'
        '<model name="inner"><link name="l"><pose>3 4 5 0 0 0</pose></link></model></model></state>'
        % {'s': sphere}))
    assert parsed.warnings == []
    m = parsed.model('m')
    assert m.world_pose_of('inner::l')[0] == pytest.approx((3.0, 4.0, 5.0))
    assert m.world_pose_of('base')[0] == pytest.approx((2.0, 0.0, 0.0))


def test_a_plugin_of_a_nested_model_runs_with_the_outer_model_with_one_warning():
    parsed = sdf_reader.parse_world(world(
        '<model name="outer"><model name="inner"><link name="l"><collision name="c"><geometry><sphere>'
        '<radius>1</radius></sphere></geometry></collision></link>'
        '<plugin name="p" filename="libgazebo_ros_p3d.so"><bodyName>l</bodyName></plugin></model></model>'))
    assert len(parsed.warnings) == 1 and "<plugin> 'p' runs with model 'outer'" in parsed.warnings[0]
    assert "inner::NAME" in parsed.warnings[0]
    assert parsed.model('outer').plugins and parsed.model('outer').is_robot


def test_a_static_model_whose_includes_hold_a_sensor_fixes_each_unjoined_link_to_the_world(library):
    """A static room with a camera in one of its included models is a robot here (sensors run on the URDF path);
    its links hang from no joint, and each is held by the world as Gazebo holds a static model's links."""
    camera = TABLE.replace('</visual>', '</visual><sensor name="cam" type="camera"><camera><image><width>8'
                                        '</width><height>6</height></image></camera></sensor>')
    write_model(library, 'camera_table', camera)
    text = ROOM.replace('model://table</uri>\n      <name>table_b', 'model://camera_table</uri>\n      <name>table_b')
    room = sdf_reader.parse_world(text).model('room')
    assert room.is_robot
    # the nested box is not static (its own <static>): it would hang free, which one URDF tree cannot hold
    with pytest.raises(sdf_urdf.ConversionError, match='shelf::box::link'):
        sdf_urdf.model_urdf(room)
    room = sdf_reader.parse_world(text.replace('<model name="box">', '<model name="box"><static>1</static>'))
    room = room.model('room')
    joints = sdf_urdf.model_urdf(room).root.findall('joint')
    fixed_to_world = sorted(j.find('child').get('link') for j in joints if j.find('parent').get('link') == 'world')
    assert fixed_to_world == ['floor', 'shelf::board', 'shelf::box::link', 'table_a::link', 'table_b::link']


def test_an_include_inside_a_model_of_a_missing_model_is_one_warning_and_the_rest_loads():
    parsed = sdf_reader.parse_world(world(
        '<model name="m"><link name="l"><collision name="c"><geometry><sphere><radius>1</radius></sphere>'
        '</geometry></collision></link><include><uri>model://no_such_chair</uri></include>'
        '<include><uri>model://no_such_chair</uri><name>chair_2</name></include></model>'))
    assert len(parsed.warnings) == 1
    assert "model 'no_such_chair' not found" in parsed.warnings[0] and 'chair_2' in parsed.warnings[0]
    assert [link.name for link in parsed.model('m').links] == ['l']


# -- a blank line before <?xml ...?> ---------------------------------------------------------------

def test_a_blank_line_before_the_xml_declaration_is_read_as_tinyxml_reads_it(tmp_path, library):
    write_model(library, 'blank_table', '\n' + TABLE, config='\n   \n' + model_config('blank_table'))
    path = tmp_path / 'blank.world'
    path.write_text('\n' + world('<include><uri>model://blank_table</uri></include>'))
    parsed = sdf_reader.load_world(str(path))
    assert parsed.warnings == [] and [m.name for m in parsed.models] == ['table']
    assert xml_document.fromstring(b'\r\n  <!-- saved by hand -->\n<?xml version="1.0"?><sdf/>').tag == 'sdf'
    with pytest.raises(sdf_reader.WorldError, match='not valid XML'):
        sdf_reader.parse_world('\n<?xml version="1.0"?><sdf><world name="w"></sdf>')


def test_a_spawn_request_drops_its_xml_declaration_as_gazebo_ros_does():
    assert spawn_xml.parse('\n  <?xml version="1.0"?>\n<robot name="r"/>').tag == 'robot'
    assert spawn_xml.strip_xml_declaration('<!-- c --><?xml version="1.0"?><sdf/>') == '<!-- c --><sdf/>'


# -- the resource path: worlds and relative file:// URIs ---------------------------------------------

def write_media_package(root, name='my_worlds'):
    """A catkin package exporting its folder as media path and models/ as model path, as gazebo_ros documents."""
    folder = root / name
    (folder / 'worlds').mkdir(parents=True)
    (folder / 'models').mkdir()
    (folder / 'package.xml').write_text(textwrap.dedent("""\
        <?xml version="1.0"?>
        <package format="2">
          <name>%s</name>
          <version>0.1.0</version>
          <description>Worlds for the robot.</description>
          <maintainer email="someone@example.com">someone</maintainer>
          <license>BSD</license>
          <buildtool_depend>catkin</buildtool_depend>
          <exec_depend>gazebo_ros</exec_depend>
          <export>
            <gazebo_ros gazebo_media_path="${prefix}" gazebo_model_path="${prefix}/models"/>
          </export>
        </package>
        """) % name)
    return folder


def test_a_world_name_is_found_through_a_packages_gazebo_media_path(tmp_path):
    package = write_media_package(tmp_path / 'pkgs')
    (package / 'worlds' / 'shop.world').write_text(world('<include><uri>model://shelf_unit</uri></include>'))
    write_model(package / 'models', 'shelf_unit', TABLE.replace('name="table"', 'name="shelf_unit"'))
    assert model_path.resource_path() == [str(package)]
    found = world_server.resolve_world('worlds/shop.world')
    assert found == str(package / 'worlds' / 'shop.world')
    parsed = sdf_reader.load_world(found)
    assert parsed.warnings == [] and [m.name for m in parsed.models] == ['shelf_unit']


def test_the_resource_path_is_the_environment_then_the_exports_each_with_its_model_suffixes(tmp_path, monkeypatch):
    package = write_media_package(tmp_path / 'pkgs')
    first = tmp_path / 'share' / 'gazebo-11'
    (first / 'worlds').mkdir(parents=True)
    monkeypatch.setenv('GAZEBO_RESOURCE_PATH', str(first))
    assert model_path.resource_path() == [str(first), str(package)]
    (first / 'worlds' / 'x.world').write_text(world(''))
    (package / 'worlds' / 'x.world').write_text(world(''))
    assert world_server.resolve_world('worlds/x.world') == str(first / 'worlds' / 'x.world')
    (tmp_path / 'cwd' / 'worlds').mkdir()
    (tmp_path / 'cwd' / 'worlds' / 'x.world').write_text(world(''))  # the working directory comes first
    assert world_server.resolve_world('worlds/x.world') == str(tmp_path / 'cwd' / 'worlds' / 'x.world')
    (package / 'media' / 'models').mkdir(parents=True)
    (package / 'media' / 'models' / 'y.world').write_text(world(''))
    assert world_server.resolve_world('y.world') == str(package / 'media' / 'models' / 'y.world')


def test_a_world_name_found_nowhere_says_where_it_was_looked_for(tmp_path):
    package = write_media_package(tmp_path / 'pkgs')
    with pytest.raises(sdf_reader.WorldError, match='also looked under %s' % package):
        sdf_reader.load_world(world_server.resolve_world('worlds/nowhere.world'), model_path.resource_path())


def mesh_model(folder, uri):
    return write_model(folder, 'crate', TABLE.replace('name="table"', 'name="crate"').replace(
        '<box><size>1.2 0.8 0.04</size></box></geometry>\n      </collision>',
        '<mesh><uri>%s</uri></mesh></geometry>\n      </collision>' % uri))


def write_stl(path):
    mesh_fixtures.write_mesh(mesh_fixtures.box((0.5, 0.5, 0.5)), str(path))


def test_a_relative_file_uri_is_found_in_the_resource_path_not_the_models_folder(tmp_path, library):
    package = write_media_package(tmp_path / 'pkgs')
    folder = mesh_model(library, 'file://meshes/crate.stl')
    write_stl(folder / 'meshes' / 'crate.stl')  # where the model is: Gazebo does not look here
    parsed = sdf_reader.parse_world(world('<include><uri>model://crate</uri></include>'))
    (warning,) = parsed.warnings
    for place in (tmp_path / 'cwd' / 'meshes' / 'crate.stl', package / 'meshes' / 'crate.stl',
                  package / 'models' / 'meshes' / 'crate.stl', package / 'media' / 'models' / 'meshes' / 'crate.stl'):
        assert str(place) in warning
    assert 'write model://NAME/meshes/crate.stl' in warning
    write_stl(package / 'media' / 'models' / 'meshes' / 'crate.stl')
    parsed = sdf_reader.parse_world(world('<include><uri>model://crate</uri></include>'))
    assert parsed.warnings == []
    assert parsed.models[0].links[0].collisions[0].shape.uri == 'file://meshes/crate.stl'


def test_a_relative_file_uri_is_looked_for_in_the_working_directory_first(tmp_path, library):
    mesh_model(library, 'file://meshes/crate.stl')
    write_stl(tmp_path / 'cwd' / 'meshes' / 'crate.stl')
    assert model_path.resolve_uri('file://meshes/crate.stl') == str(tmp_path / 'cwd' / 'meshes' / 'crate.stl')
    assert sdf_reader.parse_world(world('<include><uri>model://crate</uri></include>')).warnings == []


def test_an_absolute_path_that_does_not_exist_is_looked_for_under_the_model_path(library):
    write_stl(library / 'saved' / 'elsewhere' / 'crate.stl')
    assert model_path.resolve_uri('file:///saved/elsewhere/crate.stl') == str(
        library / 'saved' / 'elsewhere' / 'crate.stl')
    with pytest.raises(model_path.ResolveError, match=str(library / 'no' / 'such.stl')):
        model_path.resolve_uri('/no/such.stl')


@pytest.mark.parametrize('sdf, line', [
    (b'\n<?xml version="1.0"?>\n<sdf/>', 'sdf'),
    (b'\xef\xbb\xbf\n  <?xml version="1.0" encoding="UTF-8"?><sdf/>', 'sdf'),
    ('<!-- a comment -->\n<?xml version="1.0"?>\n<world/>', 'world'),
    ('<?xml version="1.0"?>\n<model/>', 'model'),
])
def test_xml_documents_are_read_as_tinyxml_reads_them(sdf, line):
    assert xml_document.fromstring(sdf).tag == line
