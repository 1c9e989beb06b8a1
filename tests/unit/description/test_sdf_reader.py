"""Unit tests of racebot_sim_bridge.description.sdf_reader (SDF 1.6 worlds) and its sdf_elements."""

import math

import pytest
from hypothesis import given, settings, strategies as st

from racebot_sim_bridge.kinematics.rotations import quaternion_to_rpy
from racebot_sim_bridge.description.sdf_model import Physics
from racebot_sim_bridge.description.sdf_reader import WorldError, load_world, parse_world

HALF_PI = math.pi / 2

FIXTURE = """<?xml version="1.0"?>
<sdf version="1.6">
  <world name="arena">
    <gravity>0 0 -9.81</gravity>
    <physics name="fast" type="bullet"><max_step_size>0.002</max_step_size></physics>
    <physics name="main" default="1" type="ode">
      <max_step_size>0.004</max_step_size>
      <real_time_factor>0.5</real_time_factor>
      <real_time_update_rate>250</real_time_update_rate>
    </physics>
    <light name="sun_light" type="directional"/>
    <include><uri>model://sun</uri></include>
    <include><uri>model://ground_plane</uri><name>floor</name><pose>0 0 -0.1 0 0 0</pose></include>
    <model name="room">
      <static>true</static>
      <pose>1 2 0 0 0 1.5707963267948966</pose>
      <link name="wall">
        <pose>3 0 1.25 0 0 1.5707963267948966</pose>
        <collision name="wall_collision">
          <pose>0 0 0.5 0 0 0</pose>
          <geometry><box><size>6 0.15 2.5</size></box></geometry>
          <surface><friction><ode><mu>0.8</mu><mu2>0.6</mu2></ode></friction></surface>
        </collision>
        <visual name="wall_visual">
          <geometry><box><size>6 0.15 2.5</size></box></geometry>
          <material><ambient>0.1 0.1 0.1 1</ambient><diffuse>0.5 0.6 0.7 1</diffuse></material>
        </visual>
      </link>
      <link name="post">
        <collision name="c"><geometry><cylinder><radius>0.15</radius><length>1</length></cylinder></geometry>
        </collision>
        <visual name="v"><geometry><cylinder><radius>0.15</radius><length>1</length></cylinder></geometry>
          <material><ambient>0.2 0.3 0.4 1</ambient></material></visual>
      </link>
    </model>
    <model name="ball">
      <pose>-1 0 0.127 0 0 0</pose>
      <link name="link">
        <inertial><mass>0.3</mass><pose>0 0 0.01 0 0 0</pose>
          <inertia><ixx>0.002</ixx><iyy>0.002</iyy><izz>0.003</izz></inertia></inertial>
        <collision name="c"><geometry><sphere><radius>0.127</radius></sphere></geometry></collision>
        <visual name="v"><geometry><sphere><radius>0.127</radius></sphere></geometry>
          <material><script><name>Gazebo/Blue</name></script></material></visual>
      </link>
    </model>
  </world>
</sdf>
"""


def world_with(body, header=''):
    return '<sdf version="1.6"><world name="w">%s%s</world></sdf>' % (header, body)


def box_model(name='box', geometry='<box><size>1 1 1</size></box>', extra='', link_extra=''):
    return ('<model name="%s">%s<link name="link">%s<collision name="c"><geometry>%s</geometry>'
            '</collision></link></model>' % (name, extra, link_extra, geometry))


def one_warning(world, *needles):
    """Exactly one warning, containing every needle."""
    assert len(world.warnings) == 1, world.warnings
    for needle in needles:
        assert needle in world.warnings[0], world.warnings[0]
    return world.warnings[0]


@pytest.fixture(scope='module')
def world():
    return parse_world(FIXTURE)


def test_names_physics_and_gravity(world):
    assert world.name == 'arena'
    assert world.warnings == []
    physics = world.physics
    assert (physics.type, physics.max_step_size, physics.real_time_factor,
            physics.real_time_update_rate) == ('ode', 0.004, 0.5, 250.0)
    assert physics.gravity == (0.0, 0.0, -9.81)


def test_physics_defaults_are_gazebos():
    physics = parse_world(world_with('')).physics
    assert (physics.type, physics.max_step_size, physics.real_time_factor,
            physics.real_time_update_rate, physics.gravity) == \
        ('ode', 0.001, 1.0, 1000.0, (0.0, 0.0, -9.8))
    assert physics.friction_model == 'pyramid_model'  # sdformat's physics.sdf: <ode><solver><friction_model>


def test_an_unusable_ode_setting_keeps_sdformats_default_with_one_warning():
    world = parse_world(world_with('', header='<physics type="ode"><ode><solver><iters>12.5</iters><sor>-1</sor>'
                                              '</solver></ode></physics>'))
    assert (world.physics.ode['sor_pgs_iters'], world.physics.ode['sor_pgs_w']) == (50, 1.3)
    assert world.warnings == [
        'physics: ode/solver/iters must be a whole number >= 1, got 12.5; using the default 50',
        'physics: ode/solver/sor must be a number >= 0, got -1; using the default 1.3']
    none = parse_world(world_with('', header='<physics type="ode"><ode><solver><iters>0</iters></solver></ode>'
                                             '</physics>'))
    assert none.physics.ode['sor_pgs_iters'] == 50 and none.warnings == [
        'physics: ode/solver/iters must be a whole number >= 1, got 0; using the default 50']


@pytest.mark.parametrize('written, read, warning', [
    ('cone_model', 'cone_model', None),
    ('pyramid_model', 'pyramid_model', None),
    ('box_model', 'pyramid_model', "physics: friction_model 'box_model' is not simulated (racebot has pyramid_model "
                                   "and cone_model); using the default pyramid_model"),
])
def test_the_friction_model_is_read_from_odes_solver(written, read, warning):
    world = parse_world(world_with('', header='<physics type="ode"><ode><solver><friction_model>%s</friction_model>'
                                              '</solver></ode></physics>' % written))
    assert world.physics.friction_model == read
    assert world.warnings == ([warning] if warning else [])


def test_models_links_and_shapes(world):
    assert [m.name for m in world.models] == ['floor', 'room', 'ball']
    room = world.model('room')
    assert room.static is True and room.pose[:3] == (1.0, 2.0, 0.0)
    wall = room.link('wall')
    collision = wall.collisions[0]
    assert collision.name == 'wall_collision' and collision.pose == (0, 0, 0.5, 0, 0, 0)
    assert (collision.shape.kind, collision.shape.size) == ('box', (6.0, 0.15, 2.5))
    assert (collision.mu, collision.mu2) == (0.8, 0.6)
    assert wall.visuals[0].rgba == (0.5, 0.6, 0.7, 1.0)  # diffuse wins over ambient
    post = room.link('post')
    assert (post.collisions[0].shape.radius, post.collisions[0].shape.length) == (0.15, 1.0)
    assert (post.collisions[0].mu, post.collisions[0].mu2) == (None, None)
    assert post.visuals[0].rgba == (0.2, 0.3, 0.4, 1.0)  # ambient when no diffuse
    assert post.mass == 1.0 and post.inertia is None
    ball = world.model('ball').link('link')
    assert ball.mass == 0.3 and ball.inertia == (0.002, 0.0, 0.0, 0.002, 0.0, 0.003)
    assert ball.inertial_pose == (0, 0, 0.01, 0, 0, 0)
    assert ball.collisions[0].shape.radius == 0.127
    assert ball.visuals[0].rgba == (0.0, 0.0, 1.0, 1.0)
    assert world.model('ball').static is False


def test_poses_are_composed_into_world_frame(world):
    room = world.model('room')
    wall = room.link('wall')
    xyz, quat = room.world_pose_of(wall)
    # Model at (1, 2) turned 90 deg: the link's +3 in x lands on +3 in world y.
    assert xyz == pytest.approx((1.0, 5.0, 1.25))
    assert quaternion_to_rpy(quat) == pytest.approx((0.0, 0.0, math.pi))
    xyz, _ = room.world_pose_of('wall', wall.collisions[0])
    assert xyz == pytest.approx((1.0, 5.0, 1.75))


def test_ground_plane_include(world):
    floor = world.model('floor')
    assert floor.static is True and floor.pose == (0, 0, -0.1, 0, 0, 0)
    (link,) = floor.links
    (collision,) = link.collisions
    assert collision.shape.kind == 'plane' and collision.shape.normal == (0.0, 0.0, 1.0)
    assert collision.shape.size == (100.0, 100.0)
    assert (collision.mu, collision.mu2) == (100.0, 50.0)


def test_ground_plane_include_default_name_and_sun_is_silent():
    world = parse_world(world_with('<include><uri>model://ground_plane</uri></include>'
                                   '<include><uri>model://sun</uri></include>'))
    assert [m.name for m in world.models] == ['ground_plane'] and world.warnings == []


def test_saved_state_poses_are_applied():
    world = parse_world(world_with(
        box_model('crate', extra='<pose>1 0 0 0 0 0</pose>'),
        header='<state world_name="w"><model name="crate"><pose>5 5 0 0 0 1.5707963267948966'
               '</pose><scale>1 1 1</scale><link name="link"><pose>5 6 0 0 0 1.5707963267948966'
               '</pose></link></model><model name="elsewhere"/></state>'))
    crate = world.model('crate')
    assert crate.pose == (5, 5, 0, 0, 0, HALF_PI)
    assert crate.link('link').pose == pytest.approx((1.0, 0.0, 0.0, 0.0, 0.0, 0.0), abs=1e-12)
    xyz, _ = crate.world_pose_of('link')
    assert xyz == pytest.approx((5.0, 6.0, 0.0))
    assert world.warnings == []


# -- warnings: one each, element skipped, world still loads --------------------------------

@pytest.mark.parametrize('body, needles', [
    (box_model(geometry='<mesh><uri>model://cube/meshes/cube.dae</uri></mesh>'),
     ("model 'box' link 'link' collision 'c'", 'model://cube/meshes/cube.dae not found; searched')),
    (box_model(geometry='<heightmap><uri>h.png</uri></heightmap>'), ('heightmap',)),
    (box_model(geometry='<polyline><height>1</height></polyline>'), ('polyline',)),
    (box_model(extra='<model><link name="l"/></model>'), ("model 'box'", 'a nested <model> without a name')),
    (box_model(extra='<joint name="hinge" type="revolute"/>'),
     ("model 'box' joint 'hinge'", 'needs <parent> and <child>')),
    (box_model(extra='<joint name="j" type="hinge"><parent>link</parent><child>link</child></joint>'),
     ("model 'box' joint 'j'", "unknown joint type 'hinge'")),
    (box_model(extra='<joint name="j" type="ball"><parent>world</parent><child>link</child></joint>'),
     ("model 'box' joint 'j'", 'ball joints are not supported; made fixed')),
    (box_model(extra='<joint name="j" type="revolute"><parent>world</parent><child>link</child>'
                     '<axis><xyz>0 0 0</xyz></axis></joint>'),
     ("model 'box' joint 'j'", 'axis xyz is the zero vector')),
    (box_model(extra='<joint name="j" type="prismatic"><parent>world</parent><child>link</child>'
                     '<axis><xyz>1 0 0</xyz><limit><lower>1</lower><upper>0</upper></limit></axis></joint>'),
     ("model 'box' joint 'j'", 'limit lower 1 is above upper 0')),
    (box_model(geometry='<box><size>1 0 1</size></box>'),
     ("collision 'c'", 'degenerate geometry: box size must be > 0, got 1 0 1')),
    (box_model(geometry='<box><size>1 inf 1</size></box>'), ("collision 'c'", 'finite')),
    (box_model(geometry='<sphere><radius>-1</radius></sphere>'),
     ("collision 'c'", 'sphere radius must be > 0')),
    (box_model(geometry='<cylinder><radius>1</radius><length>nan</length></cylinder>'),
     ("collision 'c'", 'cylinder length must be finite')),
    (box_model(geometry='<plane><normal>0 0 0</normal></plane>'), ('plane normal',)),
    (box_model(geometry=''), ("collision 'c'", 'empty <geometry>')),
    (box_model(link_extra='<pose>1 2 three 0 0 0</pose>'),
     ("model 'box' link 'link'", 'pose must be numbers', "and so model 'box'")),
    (box_model(link_extra='<inertial><mass>0</mass></inertial>'),
     ("model 'box' link 'link'", 'mass must be > 0, got 0; using 1.0')),
    (box_model(extra='<static>maybe</static>'), ("model 'box'", 'static must be true or false')),
    ('<model name="empty"><pose>0 0 0 0 0 0</pose></model>',
     ("model 'empty'", 'has no links; skipped')),
    (box_model() + box_model(), ("model 'box'", 'a second model with this name')),
    ('<include><uri>model://cafe_table</uri></include>',
     ("'model://cafe_table'", "model 'cafe_table' not found; searched", 'GAZEBO_MODEL_PATH')),
    ('<actor name="walker"/>', ("<actor> 'walker'", 'actors')),
    ('<plugin name="wp"/>', ("<plugin> 'wp' has no filename",)),
    ('<physics type="ode"><max_step_size>0</max_step_size></physics>',
     ('physics', 'max_step_size must be > 0', 'default 0.001')),
])
def test_unsupported_or_degenerate_elements_warn_once_and_are_skipped(body, needles):
    world = parse_world(world_with(body + '<include><uri>model://ground_plane</uri></include>'))
    one_warning(world, *needles)
    assert 'ground_plane' in [m.name for m in world.models]


def test_skipped_collision_keeps_the_rest_of_the_model():
    world = parse_world(world_with(
        '<model name="m"><link name="l">'
        '<collision name="bad"><geometry><mesh><uri>x.dae</uri></mesh></geometry></collision>'
        '<collision name="good"><geometry><box><size>1 1 1</size></box></geometry></collision>'
        '</link></model>'))
    assert [c.name for c in world.model('m').link('l').collisions] == ['good']
    one_warning(world, "collision 'bad'")


def test_model_whose_links_all_fail_is_skipped_with_one_warning():
    world = parse_world(world_with(box_model(link_extra='<pose>x</pose>')))
    assert world.models == []
    one_warning(world, "link 'link': pose needs 6 numbers", "model 'box', which has no usable")


def test_zero_mass_is_kept_quietly_in_a_static_model():
    world = parse_world(world_with(box_model(extra='<static>1</static>',
                                             link_extra='<inertial><mass>0</mass></inertial>')))
    assert world.warnings == [] and world.model('box').link('link').mass == 1.0


# -- errors --------------------------------------------------------------------------------

def test_missing_file_names_path_and_world_name(tmp_path):
    missing = tmp_path / 'nowhere.world'
    with pytest.raises(WorldError, match=r"'%s' not found.*world_name:=" % missing):
        load_world(str(missing))


def test_directory_is_an_error(tmp_path):
    with pytest.raises(WorldError, match='is a directory'):
        load_world(str(tmp_path))


def test_not_xml_gives_line_and_column(tmp_path):
    path = tmp_path / 'broken.world'
    path.write_text('<sdf version="1.6">\n  <world name="w">\n  </wrld>\n</sdf>\n')
    with pytest.raises(WorldError, match=r'broken\.world is not valid XML: mismatched tag: '
                                         r'line 3, column 4'):
        load_world(str(path))


def test_no_world_element():
    with pytest.raises(WorldError, match='has no <world> element'):
        parse_world('<sdf version="1.6"/>')
    with pytest.raises(WorldError, match='looks like a model file'):
        parse_world('<sdf version="1.6"><model name="m"/></sdf>')


@pytest.mark.parametrize('data', [
    '<sdf><world name="\ud800"/></sdf>',  # a lone surrogate cannot be encoded
    b'<?xml version="1.0" encoding="shift_jis"?><sdf/>',  # multi-byte encoding
    b'<?xml version="1.0" encoding="no-such-codec"?><sdf/>',
])
def test_undecodable_input_is_a_world_error(data):
    with pytest.raises(WorldError):
        parse_world(data)


def test_load_world_reads_a_file_and_search_path(tmp_path):
    (tmp_path / 'worlds').mkdir()
    (tmp_path / 'worlds' / 'mine.world').write_text(world_with(box_model()))
    world = load_world('worlds/mine.world', search_path=[str(tmp_path)])
    assert [m.name for m in world.models] == ['box']
    assert world.source == str(tmp_path / 'worlds' / 'mine.world')


def test_empty_world_is_built_in():
    world = load_world('worlds/empty.world')
    assert [m.name for m in world.models] == ['ground_plane'] and world.warnings == []


_xmlish = st.text(alphabet=st.sampled_from(list('<>/="\' abcdefghijklmnoprstuvwxyz0123456789.-'
                                                '\n')) | st.characters(), max_size=300)
_sdf_words = st.lists(st.sampled_from([
    '<sdf version="1.6">', '</sdf>', '<world name="w">', '</world>', '<model name="m">',
    '<model>', '</model>', '<link name="l">', '<link>', '</link>', '<collision name="c">',
    '</collision>', '<visual name="v">', '</visual>', '<geometry>', '</geometry>',
    '<box><size>1 1 1</size></box>', '<box><size>x</size></box>', '<sphere/>', '<plane/>',
    '<plane><normal>0 0 0</normal></plane>', '<mesh/>', '<pose>1 2 3 0 0 0</pose>',
    '<pose>nan</pose>', '<static>true</static>', '<inertial><mass>-1</mass></inertial>',
    '<include><uri>model://ground_plane</uri></include>', '<include/>', '<state>', '</state>',
    '<physics><max_step_size>q</max_step_size></physics>', '<gravity>1</gravity>',
    '<material><diffuse>1 2</diffuse></material>', '<surface><friction><ode><mu>-1</mu>'
    '</ode></friction></surface>', '<scale>2 2 2</scale>']), max_size=25).map(''.join)


@settings(max_examples=300, deadline=None)
@given(st.one_of(st.binary(max_size=300), _xmlish, _sdf_words))
def test_random_input_raises_only_world_error(data):
    try:
        parse_world(data)
    except WorldError:
        pass



# -- the reader's pieces return what they found; only bad values in the file raise ---------------

def reader(tmp_path, monkeypatch, models=()):
    """A _WorldReader with its own mesh cache and a model path of `models` (folders under tmp_path)."""
    from racebot_sim_bridge.description.sdf_reader import _WorldReader
    monkeypatch.setenv('RACEBOT_MESH_CACHE', str(tmp_path / 'cache'))
    return _WorldReader('<test>', search=[str(tmp_path / m) for m in models])


def geometry(text):
    import xml.etree.ElementTree as ET
    return ET.fromstring('<geometry>%s</geometry>' % text)


def test_model_folder_gives_the_folder_or_the_problem_and_never_raises(tmp_path, monkeypatch):
    (tmp_path / 'models' / 'wall').mkdir(parents=True)
    (tmp_path / 'models' / 'a_file').write_text('')
    r = reader(tmp_path, monkeypatch, ['models'])
    found = r.model_folder('model://wall')
    assert (found.path, found.problem, found.missing) == (str(tmp_path / 'models' / 'wall'), None, False)
    assert r.model_folder('file://%s' % (tmp_path / 'models' / 'wall')).path == str(tmp_path / 'models' / 'wall')
    missing = r.model_folder('model://cone')
    assert missing.path is None and missing.missing
    assert "model 'cone' not found; searched %s" % (tmp_path / 'models') in missing.problem
    for target, needle in [('model://', 'names no model'), ('model://a_file', 'is a file, not a model folder'),
                           ('http://example.com/wall', 'unknown URI scheme'),
                           (str(tmp_path / 'nowhere'), 'no model folder at %s' % (tmp_path / 'nowhere'))]:
        result = r.model_folder(target)
        assert result.path is None and not result.missing and needle in result.problem, (target, result)


def test_shape_gives_the_geometry_or_none_with_one_warning(tmp_path, monkeypatch):
    r = reader(tmp_path, monkeypatch)
    box = r.shape(geometry('<box><size>1 2 3</size></box>'), 'here')
    assert (box.shape.kind, box.shape.size, box.mesh_rgba) == ('box', (1.0, 2.0, 3.0), None)
    assert r.warnings == []
    assert r.shape(geometry('<box><size>1 0 3</size></box>'), 'here') is None
    assert r.shape(geometry('<heightmap/>'), 'there') is None
    assert r.warnings == ['here: degenerate geometry: box size must be > 0, got 1 0 3; skipped',
                          'there: heightmap geometry is not supported; skipped']


def test_a_mesh_is_read_once_and_a_bad_one_warned_about_once(tmp_path, monkeypatch):
    import mesh_fixtures  # tests/integration, shared with the rostest node
    mesh_fixtures.write_mesh(mesh_fixtures.box((1.0, 1.0, 1.0)), str(tmp_path / 'red.dae'), rgba=(1, 0, 0, 1))
    r = reader(tmp_path, monkeypatch)
    good = '<mesh><uri>%s</uri><scale>2 2 2</scale></mesh>' % (tmp_path / 'red.dae')
    first, again = r.shape(geometry(good), 'a'), r.shape(geometry(good), 'b')
    assert first.shape.kind == 'mesh' and first.shape.scale == (2.0, 2.0, 2.0)
    assert first.shape.filename.startswith(str(tmp_path / 'cache')) and first.mesh_rgba == (1.0, 0.0, 0.0, 1.0)
    assert again == first and r.warnings == []
    bad = '<mesh><uri>%s</uri></mesh>' % (tmp_path / 'missing.stl')
    assert r.shape(geometry(bad), 'collision') is None
    assert r.shape(geometry(bad), 'visual') is None
    assert len(r.warnings) == 1 and r.warnings[0].startswith('collision: %s' % (tmp_path / 'missing.stl'))
    assert r.shape(geometry('<mesh><uri>%s</uri><scale>1 0 1</scale></mesh>' % (tmp_path / 'red.dae')), 'v') is None
    assert r.warnings[-1] == 'v: degenerate geometry: mesh scale must be > 0, got 1 0 1; skipped'


def test_a_model_folder_without_an_sdf_file_is_one_warning(tmp_path, monkeypatch):
    (tmp_path / 'models' / 'hollow').mkdir(parents=True)
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(tmp_path / 'models'))
    world = parse_world(world_with('<include><uri>model://hollow</uri></include>'), search=[str(tmp_path / 'models')])
    assert world.models == []
    one_warning(world, "include 'model://hollow'", 'has no SDF file', '; skipped')


@pytest.mark.parametrize('tag, value, message', [
    ('real_time_update_rate', '-1', 'real_time_update_rate must be >= 0, got -1; using the default 1000'),
    ('real_time_factor', '0', 'real_time_factor must be > 0, got 0; using the default 1'),
    ('max_step_size', 'fast', "max_step_size must be numbers, got 'fast'; using the default 0.001"),
])
def test_an_unusable_physics_value_keeps_the_default_with_one_warning(tag, value, message):
    world = parse_world(world_with('', header='<physics type="ode"><%s>%s</%s></physics>' % (tag, value, tag)))
    assert one_warning(world) == 'physics: ' + message
    assert getattr(world.physics, tag) == getattr(Physics(), tag)
    assert parse_world(world_with('', header='<physics type="ode"><real_time_update_rate>0'
                                             '</real_time_update_rate></physics>')).physics.real_time_update_rate == 0


def test_a_worlds_plugins_are_kept_as_written_in_order():
    world = parse_world(world_with('<plugin name="a" filename="liba.so"><rate>5</rate></plugin>'
                                   '<include><uri>model://ground_plane</uri></include>'
                                   '<plugin name="b" filename="libb.so"/>'))
    assert [(p.name, p.filename) for p in world.plugins] == [('a', 'liba.so'), ('b', 'libb.so')]
    assert '<rate>5</rate>' in world.plugins[0].xml
    assert world.warnings == []
