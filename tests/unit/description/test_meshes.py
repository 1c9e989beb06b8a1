"""Meshes, package:// / model:// / file:// resolution, Gazebo materials and SDF includes. No ROS master.

Meshes are written by the tests (tests/integration/mesh_fixtures.py); every test gets its own mesh cache,
model path and ROS package path under tmp_path.
"""
import os
import sys
from pathlib import Path

import numpy as np
import pybullet as pb
import pytest

from racebot_sim_bridge.description import geometry, meshes, model_path, sdf_model, sdf_reader, urdf_assets, urdf_reader
from racebot_sim_bridge.description.materials import GAZEBO_MATERIALS, gazebo_material_rgba
from racebot_sim_bridge.engine.physics import PhysicsWorld

import mesh_fixtures  # tests/integration, shared with the rostest node


@pytest.fixture(autouse=True)
def isolated(tmp_path, monkeypatch):
    """Own mesh cache, empty GAZEBO_MODEL_PATH, a HOME without ~/.gazebo, a package root on ROS_PACKAGE_PATH."""
    monkeypatch.setenv('RACEBOT_MESH_CACHE', str(tmp_path / 'cache'))
    monkeypatch.setenv('HOME', str(tmp_path / 'home'))
    monkeypatch.setenv('GAZEBO_MODEL_PATH', '')
    (tmp_path / 'pkgs').mkdir()
    monkeypatch.setenv('ROS_PACKAGE_PATH', str(tmp_path / 'pkgs'))
    return tmp_path


def read_obj(path):
    """(vertices, number of faces, number of objects) of an OBJ the converter wrote."""
    vertices, faces, objects = [], 0, 0
    with open(path) as f:
        for line in f:
            if line.startswith('v '):
                vertices.append([float(v) for v in line.split()[1:4]])
            elif line.startswith('f '):
                faces += 1
            elif line.startswith('o '):
                objects += 1
    return np.array(vertices), faces, objects


# -- meshes ---------------------------------------------------------------------------------------
@pytest.mark.parametrize('ext', ['.stl', '.obj', '.dae'])
def test_each_format_converts_to_an_obj_of_the_same_shape(tmp_path, ext):
    path = mesh_fixtures.write_mesh(mesh_fixtures.box((0.4, 0.6, 0.8)), str(tmp_path / ('box' + ext)))
    converted = meshes.convert(path)
    assert converted.obj_path.startswith(str(tmp_path / 'cache'))
    vertices, faces, objects = read_obj(converted.obj_path)
    assert faces == converted.triangles == 12 and objects == 1
    np.testing.assert_allclose(vertices.min(axis=0), [-0.2, -0.3, -0.4], atol=1e-6)
    np.testing.assert_allclose(vertices.max(axis=0), [0.2, 0.3, 0.4], atol=1e-6)
    assert meshes.convert(converted.obj_path) == converted  # a cached file is used as it is
    assert meshes.convert(path) == converted  # converted once


def test_a_dae_unit_scales_it_to_metres_as_gazebo_does(tmp_path):
    path = mesh_fixtures.write_mesh(mesh_fixtures.box((10, 20, 30)), str(tmp_path / 'cm.dae'))
    text = Path(path).read_text().replace('<up_axis>', '<unit meter="0.01" name="centimeter"/><up_axis>')
    Path(path).write_text(text)
    vertices, _, _ = read_obj(meshes.convert(path).obj_path)
    np.testing.assert_allclose(vertices.max(axis=0), [0.05, 0.1, 0.15], atol=1e-9)


def test_a_dae_colour_is_the_mesh_colour(tmp_path):
    path = mesh_fixtures.write_mesh(mesh_fixtures.box((1, 1, 1)), str(tmp_path / 'red.dae'), rgba=(1, 0, 0, 1))
    assert meshes.convert(path).rgba == (1.0, 0.0, 0.0, 1.0)


def write_bytes(tmp_path, name, data):
    path = tmp_path / name
    path.write_bytes(data)
    return str(path)


@pytest.mark.parametrize('name, data, needle', [
    ('empty.stl', b'', 'is an empty file'),
    ('noise.stl', bytes(range(256)) * 3, 'mesh'),
    ('text.obj', b'this is not a mesh\n', 'contains no triangles'),
    ('broken.dae', b'<COLLADA><library_geometries>', 'could not be read as DAE'),
    ('nan.obj', b'v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n', 'not finite'),
    ('bad_index.obj', b'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n', 'mesh'),
    ('model.ply', b'ply\n', "format '.ply' is not supported"),
])
def test_bad_mesh_files_are_refused_with_a_message_naming_them(tmp_path, name, data, needle):
    path = write_bytes(tmp_path, name, data)
    with pytest.raises(meshes.MeshError) as err:
        meshes.convert(path)
    assert path in str(err.value) and needle in str(err.value)


def test_a_missing_mesh_file_is_refused(tmp_path):
    with pytest.raises(meshes.MeshError, match='cannot be read'):
        meshes.convert(str(tmp_path / 'none.stl'))


def test_size_and_triangle_limits(tmp_path, monkeypatch):
    path = mesh_fixtures.write_mesh(mesh_fixtures.cylinder(0.1, 0.1, sections=64), str(tmp_path / 'c.stl'))
    monkeypatch.setattr(meshes, 'MAX_TRIANGLES', 100)
    with pytest.raises(meshes.MeshError, match='more than 100 triangles'):
        meshes.convert(path)
    monkeypatch.setattr(meshes, 'MAX_TRIANGLES', 10 ** 6)
    monkeypatch.setattr(meshes, 'MAX_FILE_BYTES', 1000)
    with pytest.raises(meshes.MeshError, match='simplify it'):
        meshes.convert(path)


# -- URIs -------------------------------------------------------------------------------------------
def test_package_file_model_and_relative_uris_resolve(isolated):
    pkg = mesh_fixtures.write_package(str(isolated / 'pkgs'), 'fixture_pkg')
    stl = mesh_fixtures.write_mesh(mesh_fixtures.box((1, 1, 1)), os.path.join(pkg, 'meshes', 'b.stl'))
    assert model_path.resolve_uri('package://fixture_pkg/meshes/b.stl') == stl
    assert model_path.resolve_uri('file://' + stl) == stl
    assert model_path.resolve_uri(stl) == stl
    assert model_path.resolve_uri('meshes/b.stl', base_dir=pkg) == stl
    models = isolated / 'models'
    folder = mesh_fixtures.write_model(str(models), 'cone', '<model name="cone"/>')
    mesh_fixtures.write_mesh(mesh_fixtures.box((1, 1, 1)), os.path.join(folder, 'meshes', 'cone.dae'))
    assert model_path.resolve_uri('model://cone/meshes/cone.dae', search=[str(models)]) == \
        os.path.join(folder, 'meshes', 'cone.dae')


@pytest.mark.parametrize('uri, needles', [
    ('package://no_such_pkg/m.stl', ["package 'no_such_pkg' is not on the ROS package path"]),
    ('model://cone/meshes/cone.dae', ['model://cone/meshes/cone.dae not found; searched', '/a/cone/meshes/cone.dae',
                                      '/b/cone/meshes/cone.dae', 'GAZEBO_MODEL_PATH']),
    ('http://example.com/m.stl', ["unknown URI scheme 'http'"]),
    ('file:///no/such/m.stl', ['file:///no/such/m.stl not found; searched /no/such/m.stl']),
    ('', ['an empty URI']),
])
def test_unresolvable_uris_name_the_uri_and_every_place_searched(uri, needles):
    with pytest.raises(model_path.ResolveError) as err:
        model_path.resolve_uri(uri, search=['/a', '/b'])
    for needle in needles:
        assert needle in str(err.value)


def test_model_path_order_is_home_then_env_then_package_exports(isolated, monkeypatch):
    """Gazebo 11's SystemPaths puts ~/.gazebo/models first, GAZEBO_MODEL_PATH after it; gazebo_ros_paths_plugin
    adds the packages' exports last (AddModelPaths)."""
    monkeypatch.setenv('GAZEBO_MODEL_PATH', '/first:/second')
    mesh_fixtures.write_package(str(isolated / 'pkgs'), 'exporting_pkg',
                                '<gazebo_ros gazebo_model_path="${prefix}/models"/>')
    assert model_path.model_path() == [str(isolated / 'home' / '.gazebo' / 'models'), '/first', '/second',
                                       str(isolated / 'pkgs' / 'exporting_pkg' / 'models')]


def test_model_config_picks_the_highest_sdf_version(tmp_path):
    folder = tmp_path / 'm'
    folder.mkdir()
    (folder / 'old.sdf').write_text('<sdf/>')
    (folder / 'new.sdf').write_text('<sdf/>')
    (folder / 'model.config').write_text('<model><sdf version="1.4">old.sdf</sdf><sdf version="1.6">new.sdf</sdf>'
                                         '</model>')
    assert model_path.model_sdf_file(str(folder)) == str(folder / 'new.sdf')
    (folder / 'model.config').unlink()
    with pytest.raises(model_path.ResolveError, match='has no SDF file'):
        model_path.model_sdf_file(str(folder))


# -- materials --------------------------------------------------------------------------------------
def test_gazebo_material_names_are_their_script_colours():
    assert gazebo_material_rgba(' Gazebo/Red ') == (1.0, 0.0, 0.0, 1.0)
    assert gazebo_material_rgba('Gazebo/Blue') == (0.0, 0.0, 1.0, 1.0)
    assert gazebo_material_rgba('Gazebo/Orange') == (1.0, 0.5088, 0.0468, 1.0)
    assert gazebo_material_rgba('Gazebo/NoSuchThing') is None
    for name in ('Grey', 'White', 'Black', 'Red', 'Green', 'Blue', 'Yellow', 'Purple', 'Turquoise', 'Orange'):
        assert 'Gazebo/' + name in GAZEBO_MATERIALS


COLOUR_URDF = '''<robot name="r">
  <material name="magenta"><color rgba="1 0 1 1"/></material>
  <link name="a"><visual><geometry><box size="1 1 1"/></geometry><material name="magenta"/></visual></link>
  <link name="b"><visual><geometry><box size="1 1 1"/></geometry>
    <material name="red"><color rgba="1 0 0 1"/></material></visual></link>
  <link name="c"><visual><geometry><mesh filename="{dae}"/></geometry></visual>
    <collision><geometry><mesh filename="package://nowhere_pkg/m.stl"/></geometry></collision>
    <collision><geometry><mesh filename="{dae}" scale="1 0 1"/></geometry></collision></link>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="ac" type="fixed"><parent link="a"/><child link="c"/></joint>
  <gazebo reference="b"><material>Gazebo/Green</material></gazebo>
</robot>'''


def test_urdf_colours_gazebo_material_wins_then_urdf_then_mesh_and_a_missing_mesh_is_left_out(tmp_path):
    dae = mesh_fixtures.write_mesh(mesh_fixtures.box((1, 1, 1)), str(tmp_path / 'y.dae'), rgba=(1, 1, 0, 1))
    xml = COLOUR_URDF.format(dae=dae)
    model = urdf_reader.parse_urdf(xml)
    warnings = []
    resolved = urdf_assets.resolve_assets(xml, model, warnings.append)
    assert model.links['a'].visuals[0].rgba == (1.0, 0.0, 1.0, 1.0)  # URDF colour, named at robot level
    assert model.links['b'].visuals[0].rgba == (0.0, 1.0, 0.0, 1.0)  # <gazebo> material wins over URDF red
    assert model.links['c'].visuals[0].rgba == (1.0, 1.0, 0.0, 1.0)  # the DAE's own colour
    assert model.links['c'].visuals[0].filename.startswith(str(tmp_path / 'cache'))
    assert model.links['c'].collisions == []
    assert len(warnings) == 2 and 'package://nowhere_pkg/m.stl' in warnings[0] and 'left out' in warnings[0]
    assert 'scale 1 0 1 has a zero factor' in warnings[1]
    assert 'package://' not in resolved and '<color rgba="0 1 0 1"' in resolved
    assert urdf_assets.resolve_assets(resolved, urdf_reader.parse_urdf(resolved)) == resolved  # idempotent



def test_urdf_attribute_style_gazebo_material_and_a_model_uri_with_a_path(isolated, monkeypatch):
    """<material value="Gazebo/Red"/> (the old attribute style) colours the link as <material>Gazebo/Red</material>
    does; a URDF mesh at model://PKG/models/NAME/... resolves under the model folder holding PKG/."""
    mesh_fixtures.write_mesh(mesh_fixtures.box((1, 1, 1)),
                             str(isolated / 'share' / 'track_pkg' / 'models' / 'track' / 'meshes' / 'wall.stl'))
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(isolated / 'share'))
    xml = ('<robot name="r"><link name="a"><visual><geometry><box size="1 1 1"/></geometry></visual>'
           '<collision><geometry><mesh filename="model://track_pkg/models/track/meshes/wall.stl"/></geometry>'
           '</collision></link><gazebo reference="a"><material value="Gazebo/Red"/></gazebo></robot>')
    model = urdf_reader.parse_urdf(xml)
    warnings = []
    urdf_assets.resolve_assets(xml, model, warnings.append)
    assert warnings == []
    assert model.links['a'].visuals[0].rgba == (1.0, 0.0, 0.0, 1.0)
    assert model.links['a'].collisions[0].filename.startswith(str(isolated / 'cache'))


# -- SDF ------------------------------------------------------------------------------------------------
WALL_MODEL = '''<model name="wall"><static>true</static><pose>9 9 9 0 0 0</pose><link name="link">
  <collision name="c"><geometry><mesh><uri>model://wall/meshes/wall.stl</uri><scale>2 1 1</scale></mesh></geometry>
  </collision>
  <visual name="v"><geometry><mesh><uri>meshes/wall.dae</uri></mesh></geometry></visual></link></model>'''


def world_with(body):
    return '<sdf version="1.6"><world name="default">%s</world></sdf>' % body


def write_wall_model(models_dir):
    folder = mesh_fixtures.write_model(str(models_dir), 'wall', WALL_MODEL)
    mesh_fixtures.write_mesh(mesh_fixtures.box((0.2, 1.0, 0.6)), os.path.join(folder, 'meshes', 'wall.stl'))
    mesh_fixtures.write_mesh(mesh_fixtures.box((0.2, 1.0, 0.6)), os.path.join(folder, 'meshes', 'wall.dae'),
                             rgba=(0, 0, 1, 1))
    return folder


def test_include_of_a_model_from_the_model_path_with_overrides(isolated, monkeypatch):
    write_wall_model(isolated / 'models')
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(isolated / 'models'))
    world = sdf_reader.parse_world(world_with(
        '<include><uri>model://wall</uri><name>wall_1</name><pose>2 0 0.3 0 0 1.5708</pose>'
        '<static>false</static></include><include><uri>model://wall</uri></include>'))
    assert world.warnings == []
    first, second = world.models
    assert (first.name, first.pose, first.static) == ('wall_1', (2.0, 0.0, 0.3, 0.0, 0.0, 1.5708), False)
    assert (second.name, second.pose, second.static) == ('wall', (9.0, 9.0, 9.0, 0.0, 0.0, 0.0), True)
    collision, visual = first.links[0].collisions[0].shape, first.links[0].visuals[0].shape
    assert collision.kind == visual.kind == 'mesh' and collision.scale == (2.0, 1.0, 1.0)
    assert collision.filename.startswith(str(isolated / 'cache'))
    assert first.links[0].visuals[0].rgba == (0.0, 0.0, 1.0, 1.0)  # the DAE's colour: no SDF material


def test_a_missing_model_warns_once_naming_the_places_searched_and_the_world_loads(isolated, monkeypatch):
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(isolated / 'models'))
    world = sdf_reader.parse_world(world_with(
        '<include><uri>model://ground_plane</uri></include><include><uri>model://construction_cone</uri></include>'))
    assert [m.name for m in world.models] == ['ground_plane']
    assert len(world.warnings) == 1
    for needle in ("model 'construction_cone' not found; searched", str(isolated / 'models'),
                   str(isolated / 'home' / '.gazebo' / 'models'), 'GAZEBO_MODEL_PATH'):
        assert needle in world.warnings[0]


def test_six_includes_of_a_missing_model_are_one_warning_listing_them(isolated, monkeypatch):
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(isolated / 'models'))
    includes = ''.join('<include><uri>model://construction_cone</uri><name>cone_%d</name></include>' % i
                       for i in range(6))
    world = sdf_reader.parse_world(world_with(includes + '<include><uri>model://ground_plane</uri></include>'))
    assert [m.name for m in world.models] == ['ground_plane']
    assert len(world.warnings) == 1, world.warnings
    assert 'searched' in world.warnings[0] and 'all 6 includes of it: cone_0, cone_1' in world.warnings[0]


def test_a_missing_mesh_used_by_many_models_is_one_warning_naming_it(isolated, monkeypatch, physics):
    folder = mesh_fixtures.write_model(str(isolated / 'models'), 'cone', WALL_MODEL.replace('wall', 'cone'))
    assert not os.path.exists(os.path.join(folder, 'meshes'))
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(isolated / 'models'))
    world = sdf_reader.parse_world(world_with(''.join(
        '<include><uri>model://cone</uri><name>cone_%d</name></include>' % i for i in range(3))))
    assert len(world.warnings) == 2, world.warnings  # the collision's mesh and the visual's, once each
    assert 'model://cone/meshes/cone.stl not found; searched' in world.warnings[0]
    skipped = []
    # Gazebo keeps a model whose meshes are missing (MeshManager::Load logs, the link loads without the shape)
    assert physics().load_world(world, warn=skipped.append) == ['cone_0', 'cone_1', 'cone_2']
    assert skipped == []


@pytest.mark.parametrize('sdf, needle', [
    ('<sdf version="1.6"><model name="x"><link', 'cannot be read as XML'),
    ('<sdf version="1.6"><world name="w"/></sdf>', 'has no <model> (only models can be included)'),
])
def test_an_included_model_file_that_cannot_be_used_is_one_warning(isolated, monkeypatch, sdf, needle):
    folder = mesh_fixtures.write_model(str(isolated / 'models'), 'odd', '')
    Path(folder, 'model.sdf').write_text(sdf)
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(isolated / 'models'))
    world = sdf_reader.parse_world(world_with('<include><uri>model://odd</uri></include>'))
    assert world.models == [] and len(world.warnings) == 1, world.warnings
    assert needle in world.warnings[0] and world.warnings[0].endswith('; skipped')
    assert 'skipped; skipped' not in world.warnings[0]


def test_a_broken_mesh_in_a_model_warns_and_the_rest_loads(isolated, monkeypatch):
    folder = write_wall_model(isolated / 'models')
    Path(folder, 'meshes', 'wall.stl').write_bytes(b'')
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(isolated / 'models'))
    world = sdf_reader.parse_world(world_with('<include><uri>model://wall</uri></include>'))
    assert len(world.warnings) == 1 and 'is an empty file' in world.warnings[0]
    assert world.models[0].links[0].collisions == [] and len(world.models[0].links[0].visuals) == 1



def test_an_include_uri_with_a_path_resolves_the_whole_path_under_each_model_folder(isolated, monkeypatch):
    """model://PKG/models/track, as a package exporting gazebo_model_path="${prefix}/.." writes it: Gazebo
    tries the whole path under each model folder in turn (SystemPaths::FindFileURI), not only the first name."""
    pkg = mesh_fixtures.write_package(str(isolated / 'pkgs'), 'track_pkg',
                                      '<gazebo_ros gazebo_model_path="${prefix}/.."/>')
    folder = mesh_fixtures.write_model(os.path.join(pkg, 'models'), 'track', WALL_MODEL.replace(
        'model://wall/meshes', 'model://track_pkg/models/track/meshes'))
    mesh_fixtures.write_mesh(mesh_fixtures.box((0.2, 1.0, 0.6)), os.path.join(folder, 'meshes', 'wall.stl'))
    mesh_fixtures.write_mesh(mesh_fixtures.box((0.2, 1.0, 0.6)), os.path.join(folder, 'meshes', 'wall.dae'))
    decoy = isolated / 'decoy'
    (decoy / 'track_pkg').mkdir(parents=True)  # a folder of the first name, without models/track below it
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(decoy))
    world = sdf_reader.parse_world(world_with('<include><uri>model://track_pkg/models/track/</uri></include>'))
    assert world.warnings == []
    (model,) = world.models
    assert model.name == 'wall' and model.links[0].collisions[0].shape.kind == 'mesh'
    assert model_path.find_model('track_pkg/models/track')[0] == folder


def test_an_include_uri_naming_a_file_is_one_warning_saying_it_is_no_model_folder(isolated, monkeypatch):
    folder = write_wall_model(isolated / 'models')
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(isolated / 'models'))
    world = sdf_reader.parse_world(world_with('<include><uri>model://wall/model.sdf</uri></include>'))
    assert world.models == [] and len(world.warnings) == 1, world.warnings
    assert os.path.join(folder, 'model.sdf') in world.warnings[0] and 'not a model folder' in world.warnings[0]


# -- physics ----------------------------------------------------------------------------------------------
@pytest.fixture
def physics():
    worlds = []

    def make(**kw):
        worlds.append(PhysicsWorld(**kw))
        return worlds[-1]
    yield make
    for w in worlds:
        w.close()


def test_a_static_mesh_collides_with_its_exact_concave_shape(isolated, physics):
    # A U made of three boxes in one mesh: a ray through the opening passes (a convex hull would stop it).
    parts = [mesh_fixtures.box((0.2, 2.0, 1.0)).apply_translation((x, 0, 0)) for x in (-1.0, 1.0)]
    parts.append(mesh_fixtures.box((2.2, 0.2, 1.0)).apply_translation((0, 1.0, 0)))
    import trimesh
    path = mesh_fixtures.write_mesh(trimesh.util.concatenate(parts), str(isolated / 'u.stl'))
    model = sdf_model.SdfModel('u', pose=(0, 0, 0.5, 0, 0, 0), static=True, links=[sdf_model.SdfLink(
        'link', collisions=[
        sdf_model.Collision('c', sdf_model.ZERO_POSE, geometry.Shape('mesh', filename=path, scale=(1, 1, 1)))])])
    world = physics()
    world.add_sdf_model(model)
    through = world.client.rayTest((0, -3, 0.5), (0, 3, 0.5))[0]
    assert through[0] != -1 and abs(through[3][1] - 0.9) < 1e-3  # stops at the U's closed side, not its opening
    wall = world.client.rayTest((-3, 0, 0.5), (0, 0, 0.5))[0]
    assert abs(wall[3][0] - (-1.1)) < 1e-3


def test_a_robot_with_mesh_wheels_and_body_rests_on_its_wheels(isolated, physics, racebot_xml):
    urdf, replaced = mesh_fixtures.meshify_urdf(racebot_xml, str(isolated / 'pkgs'))
    assert replaced >= 10
    heights = {}
    for label, xml in (('primitives', racebot_xml), ('meshes', urdf)):
        world = physics()
        world.load_world(sdf_reader.parse_world(world_with('<include><uri>model://ground_plane</uri></include>')))
        model = urdf_reader.parse_urdf(xml)
        warnings = []
        body = world.spawn_urdf('car', model, xml, position=(0, 0, 0.05), warn=warnings.append)
        assert warnings == []
        for _ in range(1500):
            world.step()
        heights[label] = body.frame_pose().position[2]
        if label == 'meshes':
            assert 'package://' not in body.source.urdf_xml
            # the body keeps its mesh's hull; a 48-sided wheel rolls as the cylinder it approximates (round_wheels.py)
            assert world.client.getCollisionShapeData(body.id, -1)[0][2] == pb.GEOM_MESH
            shapes = world.client.getCollisionShapeData(body.id, body.link_index['left_rear_wheel'])
            assert shapes[0][2] == pb.GEOM_CYLINDER
    assert abs(heights['meshes'] - heights['primitives']) < 1e-4, heights


def test_visuals_false_builds_no_visual_shapes(isolated, physics):
    # (PyBullet's renderer draws the collision shapes of a body without visual shapes, in its default colour)
    path = mesh_fixtures.write_mesh(mesh_fixtures.box((1, 1, 1)), str(isolated / 'b.obj'))
    shape = geometry.Shape('mesh', filename=meshes.convert(path).obj_path, scale=(1, 1, 1))
    model = sdf_model.SdfModel('m', static=True, links=[sdf_model.SdfLink('link', collisions=[
        sdf_model.Collision('c', sdf_model.ZERO_POSE, shape)], visuals=[
        sdf_model.Visual('v', sdf_model.ZERO_POSE, shape, (1, 0, 0, 1))])])
    for visuals, red in ((True, True), (False, False)):
        world = physics(visuals=visuals)
        body = world.add_sdf_model(model)
        data = world.client.getVisualShapeData(body.id)
        assert (tuple(data[0][7]) == (1.0, 0.0, 0.0, 1.0)) is red


COPY_SCRIPT = '''
import pickle, sys
import pybullet as pb
from racebot_sim_bridge.engine.physics import PhysicsWorld
sources = pickle.load(open(sys.argv[1], 'rb'))
world = PhysicsWorld()
for name, source in sources.items():
    body = world.add_copy(name, source)  # as the viewer and the render worker build theirs
    data = world.client.getVisualShapeData(body.id)
    shapes = world.client.getCollisionShapeData(body.id, -1)
    print(name, shapes[0][2] == pb.GEOM_MESH, tuple(round(c, 3) for c in data[0][7]))
'''


def test_a_copy_built_from_body_source_in_another_process_needs_no_search_path(isolated, physics, monkeypatch):
    """What the viewer (and a render process) do: rebuild bodies from Body.source alone."""
    import pickle
    import subprocess
    folder = write_wall_model(isolated / 'models')
    pkg = mesh_fixtures.write_package(str(isolated / 'pkgs'), 'fixture_pkg')
    mesh_fixtures.write_mesh(mesh_fixtures.box((0.3, 0.3, 0.3)), os.path.join(pkg, 'm', 'b.stl'))
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(isolated / 'models'))
    world = physics()
    wall = sdf_reader.parse_world(world_with('<include><uri>model://wall</uri></include>')).models[0]
    urdf = ('<robot name="r"><link name="l"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" '
            'ixz="0" iyz="0"/></inertial><visual><geometry><mesh filename="package://fixture_pkg/m/b.stl"/></geometry>'
            '</visual><collision><geometry><mesh filename="package://fixture_pkg/m/b.stl"/></geometry></collision>'
            '</link><gazebo reference="l"><material>Gazebo/Red</material></gazebo></robot>')
    sources = {'wall': world.add_sdf_model(wall).source,
               'robot': world.spawn_urdf('robot', urdf_reader.parse_urdf(urdf), urdf).source}
    path = isolated / 'sources.pickle'
    path.write_bytes(pickle.dumps(sources))
    import shutil
    shutil.rmtree(folder)  # the copy reads only the mesh cache
    shutil.rmtree(pkg)
    clean_env = {k: v for k, v in os.environ.items() if k not in ('GAZEBO_MODEL_PATH', 'ROS_PACKAGE_PATH')}
    out = subprocess.run([sys.executable, '-c', COPY_SCRIPT, str(path)], env=clean_env, capture_output=True,
                         text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    lines = {line.split()[0]: line for line in out.stdout.splitlines() if line.split()[0] in sources}
    assert lines['wall'] == 'wall True (0.0, 0.0, 1.0, 1.0)'  # the DAE's blue
    assert lines['robot'] == 'robot True (1.0, 0.0, 0.0, 1.0)'  # Gazebo/Red


def test_each_visual_of_a_link_keeps_its_colour_in_a_camera_image(isolated, physics):
    """A red box and a blue mesh in one link, seen through the cameras' renderer (after SceneColours)."""
    from racebot_sim_bridge.sensors.render import render
    from racebot_sim_bridge.sensors.scene import SceneColours
    path = mesh_fixtures.write_mesh(mesh_fixtures.box((0.5, 0.5, 0.5)), str(isolated / 'b.stl'))
    mesh = geometry.Shape('mesh', filename=meshes.convert(path).obj_path, scale=(1, 1, 1))
    link = sdf_model.SdfLink('link', visuals=[
        sdf_model.Visual('red', (0, 0.4, 0, 0, 0, 0), geometry.Shape('box', size=(0.5, 0.5, 0.5)), (1, 0, 0, 1)),
        sdf_model.Visual('blue', (0, -0.4, 0, 0, 0, 0), mesh, (0, 0, 1, 1))],
        collisions=[sdf_model.Collision('c', sdf_model.ZERO_POSE, geometry.Shape('box', size=(0.5, 1.3, 0.5)))])
    world = physics()
    world.add_sdf_model(sdf_model.SdfModel('two', pose=(2, 0, 0, 0, 0, 0), static=True, links=[link]))
    SceneColours(world).refresh()
    view = world.client.computeViewMatrix([0, 0, 0], [1, 0, 0], [0, 0, 1])
    proj = world.client.computeProjectionMatrixFOV(60, 1, 0.05, 10)
    rgb, _ = render(world, 64, 64, view, proj)
    left, right = rgb[32, 20].astype(int), rgb[32, 44].astype(int)  # +y (the red box) is on the image's left
    assert left[0] > 100 and left[2] < 60, left
    assert right[2] > 100 and right[0] < 60, right


def test_a_world_of_included_dynamic_mesh_cones_stands_on_the_ground(isolated, monkeypatch, physics):
    """As the tutorial's race_with_cone.world with Gazebo's construction_cone: a non-static model without
    <inertial>, a DAE mesh scaled by 10, included six times; the cones stand and rays hit their surface."""
    import trimesh
    cone_sdf = '''<model name="Construction Cone"><link name="link">
      <collision name="collision"><geometry><mesh><scale>10 10 10</scale>
        <uri>model://construction_cone/meshes/construction_cone.dae</uri></mesh></geometry></collision>
      <visual name="visual"><geometry><mesh><scale>10 10 10</scale>
        <uri>model://construction_cone/meshes/construction_cone.dae</uri></mesh></geometry></visual></link></model>'''
    folder = mesh_fixtures.write_model(str(isolated / 'models'), 'construction_cone', cone_sdf)
    cone = trimesh.creation.cone(radius=0.015, height=0.05, sections=32)  # apex up, base at z = 0
    mesh_fixtures.write_mesh(cone, os.path.join(folder, 'meshes', 'construction_cone.dae'), rgba=(1, 0.5, 0, 1))
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(isolated / 'models'))
    includes = ''.join('<include><uri>model://construction_cone</uri><name>cone_%d</name><pose>%g 1 0 0 0 0</pose>'
                       '</include>' % (i, i) for i in range(6))
    spec = sdf_reader.parse_world(world_with('<include><uri>model://ground_plane</uri></include>' + includes))
    assert spec.warnings == []
    world = physics()
    assert world.load_world(spec) == ['ground_plane'] + ['cone_%d' % i for i in range(6)]
    for _ in range(1000):
        world.step()
    for i in range(6):
        body = world.bodies['cone_%d' % i]
        frame = body.frame_pose()
        assert abs(frame.position[2]) < 0.005 and abs(frame.position[0] - i) < 0.005, frame
        hit = world.client.rayTest((i - 0.5, 1, 0.1), (i, 1, 0.1))[0]  # from between two cones
        # the cone's radius at 0.1 m height is 0.15 * (1 - 0.1 / 0.5) = 0.12 m (hull of 32 sides: within 1 cm)
        assert hit[0] == body.id and abs(hit[3][0] - (i - 0.12)) < 0.01, hit
