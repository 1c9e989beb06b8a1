"""make corpus's pure parts (tools/corpus/): the manifest's validation, where a repository comes from (with
real git repositories made here), the sensor expectations read off a URDF, the build and launch log
readers, and the table."""
import copy
import math
import os
import subprocess
from pathlib import Path

import pytest

from corpus import floor, manifest, sensors, sources, table
import git_mirror
from corpus import run as corpus_run

REPO = Path(__file__).resolve().parents[3]

COMMIT = 'e9d809ca8e3bf889c0275e4103b15a341ffab888'


def good_row(**changes):
    row = {'name': 'bot', 'covers': ['differential drive'], 'commands': ['roslaunch bot_gazebo world.launch'],
           'repos': [{'repo': 'owner/bot', 'branch': 'noetic-devel', 'commit': COMMIT, 'packages': ['bot_gazebo']}],
           'checks': [{'kind': 'drive', 'cmd_topic': '/cmd_vel', 'seconds': 5, 'expect_speed': 0.1, 'tolerance': 0.05,
                       'from': 'teleop max 0.2'}]}
    row.update(changes)
    return row


# --- the manifest ----------------------------------------------------------------------------------

def test_the_manifest_is_valid_and_covers_what_the_issue_asks():
    rows = manifest.load()
    assert manifest.validate(rows) == []
    assert len(rows) >= 12
    covers = ' '.join(' '.join(r['covers']) for r in rows).lower()
    for need in ('differential', 'skid-steer', 'omnidirectional', 'ackermann', 'jointtrajectorycontroller',
                 'gripper', 'mobile manipulator', 'depth camera', '3d lidar', 'nested models', 'meshes'):
        assert need in covers, need


def test_every_row_has_a_repo_a_commit_a_command_and_a_numeric_check():
    for row in manifest.load():
        assert row['commands'] and all(c.strip() for c in row['commands'])
        for repo in row['repos']:
            assert manifest.REPO.match(repo['repo']) and manifest.COMMIT.match(repo['commit'])
        assert any(manifest._check_errors(c)[1] for c in row['checks']), row['name']


def test_a_good_row_validates():
    assert manifest.validate([good_row()]) == []


@pytest.mark.parametrize('change, words', [
    (lambda r: r['repos'][0].update(commit='e9d809c'), 'not 40 hex digits'),
    (lambda r: r['repos'][0].update(commit=COMMIT.upper()), 'not 40 hex digits'),
    (lambda r: r['repos'][0].pop('commit'), 'not 40 hex digits'),
    (lambda r: r['repos'][0].update(repo='bot'), 'not owner/name'),
    (lambda r: r['repos'][0].pop('branch'), 'no branch'),
    (lambda r: r['repos'][0].update(packages=[]), 'no packages'),
    (lambda r: r.update(commands=[]), 'no commands'),
    (lambda r: r.update(repos=[]), 'no repos'),
    (lambda r: r.update(checks=[]), 'no checks'),
    (lambda r: r['checks'][0].pop('from'), 'without from'),
    (lambda r: r['checks'][0].update(kind='vibes'), 'no known kind'),
    (lambda r: r['checks'][0].update(tolerance=0), 'positive number'),
    (lambda r: r['checks'][0].update(settle_s=-1), 'settle_s must be'),
    (lambda r: r['checks'][0].update(settle_s='3 s'), 'settle_s must be'),
    (lambda r: r['checks'][0].update(expect_speed='fast', tolerance='some'), 'no check with a number'),
    (lambda r: r.update(blacklist={'bot_plugins': ''}), 'without a reason'),
    (lambda r: r.update(name='Bot-1'), 'lower_case'),
])
def test_a_bad_row_is_refused_with_a_reason(change, words):
    row = good_row()
    change(row)
    errors = manifest.validate([row])
    assert errors and any(words in e for e in errors), errors


def test_two_rows_of_one_name_are_refused():
    assert any('used twice' in e for e in manifest.validate([good_row(), copy.deepcopy(good_row())]))


def test_a_rows_own_files_validate_and_bad_names_or_empty_texts_are_refused():
    spawn = '<launch><node pkg="gazebo_ros" type="spawn_model" name="spawn_urdf"/></launch>'
    assert manifest.validate([good_row(files={'spawn_bot.launch': spawn})]) == []
    for files, words in (({'../spawn.launch': spawn}, 'not a plain name'), ({'a/b.launch': spawn}, 'not a plain name'),
                         ({'.hidden': spawn}, 'not a plain name'), ({'spawn.launch': ' '}, 'has no text'),
                         (['spawn.launch'], 'must map a file name')):
        errors = manifest.validate([good_row(files=files)])
        assert any(words in e for e in errors), (files, errors)


def test_a_rows_own_packages_need_their_manifest_and_cmakelists_and_stay_inside():
    package = {'package.xml': '<package/>', 'CMakeLists.txt': 'project(p)', 'src/p.cpp': 'int x;'}
    assert manifest.validate([good_row(user_packages={'p3d_upstream': package})]) == []
    for packages, words in (({'p': {'package.xml': '<package/>'}}, 'needs at least'),
                            ({'p': dict(package, **{'../x.cpp': 'int y;'})}, 'not a path inside'),
                            ({'p': dict(package, **{'src/q.cpp': ' '})}, 'has no text'),
                            ({'Bad-Name': package}, 'lower_case'), (['p'], 'must map a package name')):
        errors = manifest.validate([good_row(user_packages=packages)])
        assert any(words in e for e in errors), (packages, errors)


def test_a_floor_check_needs_its_world_and_a_tolerance():
    check = {'kind': 'floor', 'world': '$(find w)/worlds/w.world', 'tolerance': 0.01, 'from': 'urdf'}
    assert manifest.validate([good_row(checks=[check])]) == []
    errors = manifest.validate([good_row(checks=[dict(check, tolerance=None), {'kind': 'floor', 'from': 'x'}])])
    assert any('without world' in e for e in errors) and any('no number' in e for e in errors)


def test_world_rows_spawn_a_turtlebot3_from_the_users_own_launch_and_check_the_floor():
    rows = {r['name']: r for r in manifest.load()}
    for name in ('aws_bookstore_turtlebot3', 'aws_small_warehouse_turtlebot3', 'aws_racetrack_turtlebot3_racecar'):
        row = rows[name]
        spawn = row['files']['spawn_turtlebot3.launch']
        assert '-urdf -model turtlebot3_$(arg model)' in spawn and '-param robot_description' in spawn
        assert row['commands'][1].startswith('roslaunch spawn_turtlebot3.launch ')
        kinds = [c['kind'] for c in row['checks']]
        assert kinds[0] == 'world' and 'floor' in kinds and 'drive' in kinds, name
    for row in rows.values():  # a command naming a file of the row's own has it
        for command in row['commands']:
            first = command.split()[1] if command.startswith('roslaunch ') else ''
            if first.endswith('.launch'):
                assert first in (row.get('files') or {}), (row['name'], first)


def test_the_runner_writes_a_rows_files_into_the_folder_its_commands_run_in(tmp_path):
    paths = corpus_run.write_files(good_row(files={'spawn.launch': '<launch/>\n'}), str(tmp_path))
    assert paths == [str(tmp_path / 'spawn.launch')] and (tmp_path / 'spawn.launch').read_text() == '<launch/>\n'
    assert corpus_run.write_files(good_row(), str(tmp_path)) == []


def test_a_sensors_check_without_a_count_has_no_number():
    row = good_row(checks=[{'kind': 'sensors', 'description': '/robot_description', 'from': 'urdf'}])
    errors = manifest.validate([row])
    assert any('without count' in e for e in errors) and any('no check with a number' in e for e in errors)


# --- sources ---------------------------------------------------------------------------------------

def git(*args, cwd):
    return subprocess.run(['git', '-c', 'user.name=t', '-c', 'user.email=t@t', *args], cwd=cwd, check=True,
                          stdout=subprocess.PIPE, text=True).stdout.strip()


@pytest.fixture
def upstream(tmp_path):
    """A real repository with two commits: (path, first commit, second commit)."""
    path = tmp_path / 'upstream'
    path.mkdir()
    git('init', '-q', cwd=path)
    (path / 'package.xml').write_text('<package><name>one</name></package>')
    git('add', '.', cwd=path)
    git('commit', '-qm', 'one', cwd=path)
    first = git('rev-parse', 'HEAD', cwd=path)
    (path / 'package.xml').write_text('<package><name>two</name></package>')
    git('commit', '-qam', 'two', cwd=path)
    return path, first, git('rev-parse', 'HEAD', cwd=path)


def test_without_settings_a_repository_comes_from_github():
    assert sources.resolve('husky/husky', {}) == ('clone', 'https://github.com/husky/husky.git')
    assert sources.resolve('husky/husky', {'RACEBOT_CORPUS_URL': 'https://example.org/{owner}/{name}'}) == (
        'clone', 'https://example.org/husky/husky')


@pytest.mark.parametrize('layout', ['husky', 'husky/husky', 'husky+husky'])
def test_corpus_dir_finds_a_clone_in_each_layout(tmp_path, layout):
    clone = tmp_path / layout
    (clone / '.git').mkdir(parents=True)
    assert sources.resolve('husky/husky', {'RACEBOT_CORPUS_DIR': str(tmp_path)}) == ('dir', str(clone))


def test_corpus_dir_without_the_clone_says_where_it_looked(tmp_path):
    kind, why = sources.resolve('husky/husky', {'RACEBOT_CORPUS_DIR': str(tmp_path)})
    assert kind == 'missing' and 'husky+husky' in why and str(tmp_path) in why


def test_corpus_dir_falls_back_to_mirrors(tmp_path):
    mirror = tmp_path / 'mirrors' / 'husky+husky' / 'repo'
    mirror.mkdir(parents=True)
    (mirror / 'HEAD').write_text('ref: refs/heads/main\n')
    env = {'RACEBOT_CORPUS_DIR': str(tmp_path / 'clones'), 'RACEBOT_CORPUS_MIRRORS': str(tmp_path / 'mirrors')}
    assert sources.resolve('husky/husky', env) == ('clone', str(mirror))


@pytest.mark.parametrize('layout', ['husky+husky/repo/.git', 'husky+husky/repo', 'husky/husky.git'])
def test_mirrors_are_found_in_each_layout(tmp_path, layout):
    mirror = tmp_path / layout
    mirror.mkdir(parents=True)
    (mirror / 'HEAD').write_text('ref: refs/heads/main\n')
    assert sources.resolve('husky/husky', {'RACEBOT_CORPUS_MIRRORS': str(tmp_path)}) == ('clone', str(mirror))


def test_a_mirror_is_cloned_and_checked_out_at_the_pinned_commit(tmp_path, upstream):
    path, first, second = upstream
    mirrors = tmp_path / 'mirrors'
    (mirrors / 'owner+one').mkdir(parents=True)
    os.symlink(path, mirrors / 'owner+one' / 'repo')
    env = {'RACEBOT_CORPUS_MIRRORS': str(mirrors), 'RACEBOT_CORPUS_CACHE': str(tmp_path / 'cache')}
    tree, note = sources.checkout('owner/one', first, env)
    assert note == '' and sources.head_commit(tree) == first
    assert 'one' in (Path(tree) / 'package.xml').read_text()
    tree2, _ = sources.checkout('owner/one', second, env)  # the same clone, another checkout
    assert sources.head_commit(tree2) == second and tree2 != tree
    assert sources.head_commit(tree) == first
    with pytest.raises(sources.SourceError, match='not in'):
        sources.checkout('owner/one', '0' * 40, env)


def test_a_mirror_lacking_a_file_of_the_commit_is_checked_out_without_it_and_the_note_says_so(tmp_path):
    """ugv_gazebo_sim's snapshot lacks hunter's base_link.STL: the rest is checked out, the row's note names it."""
    mirror = tmp_path / 'mirrors' / 'owner+one' / 'repo'
    commit = git_mirror.mirror_lacking(tmp_path / 'work', {'package.xml': b'<package><name>one</name></package>\n',
                                                           'hunter/meshes/base link.STL': b'solid x\n' * 100},
                                       mirror, ['hunter/meshes/base link.STL'])
    env = {'RACEBOT_CORPUS_MIRRORS': str(tmp_path / 'mirrors'), 'RACEBOT_CORPUS_CACHE': str(tmp_path / 'cache')}
    tree, note = sources.checkout('owner/one', commit, env)
    assert sources.head_commit(tree) == commit and (Path(tree) / 'package.xml').is_file()
    assert not (Path(tree) / 'hunter' / 'meshes' / 'base link.STL').exists()
    assert note.startswith('checked out without hunter/meshes/base link.STL: ') and str(mirror) in note, note
    assert sources.checkout('owner/one', commit, env) == (tree, note)  # from the cache, the same note
    # a row taking other folders hears nothing of files it does not take
    assert sources.checkout('owner/one', commit, env, packages=['scout'])[1] == ''
    assert sources.checkout('owner/one', commit, env, packages=['hunter'])[1] == note


def test_a_users_clone_is_used_as_it_is_and_a_other_head_is_said(tmp_path, upstream):
    path, first, second = upstream
    env = {'RACEBOT_CORPUS_DIR': str(path.parent)}
    (path.parent / 'one').symlink_to(path)
    tree, note = sources.checkout('owner/one', first, env)
    assert tree == str(path.parent / 'one') and first[:12] in note and second[:12] in note
    assert sources.head_commit(tree) == second  # nothing was checked out in the user's clone
    assert sources.checkout('owner/one', second, env)[1] == ''


# --- sensors ---------------------------------------------------------------------------------------

URDF = """<robot name="bot">
  <link name="base_link"/>
  <gazebo reference="base_scan">
    <sensor type="ray" name="lds">
      <ray><scan><horizontal><samples>360</samples><resolution>1</resolution>
        <min_angle>0.0</min_angle><max_angle>6.28319</max_angle></horizontal></scan>
        <range><min>0.12</min><max>3.5</max></range></ray>
      <plugin name="laser" filename="libgazebo_ros_laser.so"><topicName>scan</topicName></plugin>
    </sensor>
  </gazebo>
  <gazebo reference="camera_link">
    <sensor type="camera" name="cam">
      <camera><image><width>800</width><height>600</height><format>B8G8R8</format></image></camera>
      <plugin name="c" filename="libgazebo_ros_camera.so"><cameraName>rrbot/camera1</cameraName></plugin>
    </sensor>
    <sensor type="depth" name="rs">
      <camera><image><width>64</width><height>48</height></image></camera>
      <plugin name="d" filename="libgazebo_ros_openni_kinect.so"><cameraName>camera</cameraName>
        <depthImageTopicName>depth/image_raw</depthImageTopicName></plugin>
    </sensor>
    <sensor type="imu" name="bare_imu"/>
    <sensor type="sonar" name="sonar"><plugin name="s" filename="libgazebo_ros_range.so"/></sensor>
  </gazebo>
  <gazebo reference="velodyne">
    <sensor type="ray" name="vlp">
      <ray><scan><horizontal><samples>440</samples></horizontal><vertical><samples>16</samples></vertical></scan></ray>
      <plugin name="v" filename="libgazebo_ros_velodyne_laser.so"><topicName>/velodyne_points</topicName></plugin>
    </sensor>
  </gazebo>
  <gazebo>
    <plugin name="imu" filename="libhector_gazebo_ros_imu.so"><bodyName>imu_link</bodyName>
      <topicName>imu/data</topicName></plugin>
    <plugin name="ctl" filename="libgazebo_ros_control.so"/>
  </gazebo>
</robot>"""


def by_topic(expects):
    return {e['topic']: e for e in expects}


def test_declared_sensors_give_topics_and_shapes_with_upstreams_defaults():
    expects, unchecked = sensors.declared(URDF)
    topics = by_topic(expects)
    assert set(topics) == {'/scan', '/rrbot/camera1/image_raw', '/rrbot/camera1/camera_info', '/camera/ir/image_raw',
                           '/camera/depth/image_raw', '/camera/points', '/velodyne_points', '/imu/data'}
    assert topics['/scan']['fields'] == {'len(ranges)': 360, 'angle_min': 0.0, 'angle_max': 6.28319, 'range_max': 3.5}
    assert topics['/rrbot/camera1/image_raw']['fields'] == {'width': 800, 'height': 600, 'encoding': 'bgr8'}
    assert topics['/camera/depth/image_raw']['fields']['encoding'] == '32FC1'
    assert topics['/camera/points']['fields'] == {'width': 64, 'height': 48}
    assert topics['/velodyne_points']['fields'] == {'height': 1, '<=width': 440 * 16, 'ring<': 16}
    assert topics['/imu/data']['type'] == 'sensor_msgs/Imu'
    assert unchecked == ['sonar (sonar on camera_link): libgazebo_ros_range.so']  # the bare IMU publishes nothing


def test_a_spawn_namespace_applies_to_plugins_without_their_own():
    expects, _ = sensors.declared(URDF, spawn_namespace='robot1')
    topics = set(by_topic(expects))
    assert '/robot1/scan' in topics and '/robot1/rrbot/camera1/image_raw' in topics
    assert '/velodyne_points' in topics  # absolute names ignore the namespace


def test_name_resolution():
    assert sensors.join('', 'scan') == '/scan'
    assert sensors.join('/rrbot', 'laser/scan') == '/rrbot/laser/scan'
    assert sensors.join('/rrbot/', '/scan') == '/scan'
    assert sensors.join('a//b', 'c') == '/a/b/c'


def test_compare_names_the_first_mismatch():
    fields = {'len(ranges)': 360, 'angle_max': 6.28319, '<=width': 100, 'ring<': 16}
    assert sensors.compare(fields, {'len(ranges)': 360, 'angle_max': 6.2835, 'width': 90, 'ring_max': 15}) is None
    assert 'len(ranges) 359' in sensors.compare(fields, {'len(ranges)': 359, 'angle_max': 6.28319, 'width': 1})
    assert 'angle_max' in sensors.compare(fields, {'len(ranges)': 360, 'angle_max': 3.14, 'width': 1})
    assert 'width 101' in sensors.compare(fields, {'len(ranges)': 360, 'angle_max': 6.28319, 'width': 101})
    assert 'ring max 16' in sensors.compare(fields, {'len(ranges)': 360, 'angle_max': 6.28319, 'width': 1,
                                                     'ring_max': 16})


# --- logs ------------------------------------------------------------------------------------------

BUILD_LOG = """-- ~~  traversing 2 packages in topological order:
-- ~~  - turtlebot3_description
-- ~~  - turtlebot3_gazebo
-- ==> add_subdirectory(turtlebot3_gazebo)
CMake Error at turtlebot3_gazebo/CMakeLists.txt:27 (find_package):
  By not providing "Findgazebo.cmake" in CMAKE_MODULE_PATH this project has
  Could not find a package configuration file provided by "gazebo" with any
"""


def test_build_error_names_the_package_and_what_it_could_not_find():
    assert corpus_run.build_error(BUILD_LOG) == 'turtlebot3_gazebo: find_package(gazebo) found nothing'
    compile_log = '-- ==> add_subdirectory(ur_kinematics)\nfoo.cpp:3:10: fatal error: boost/x.hpp: No such file\n'
    assert corpus_run.build_error(compile_log) == 'ur_kinematics: fatal error: boost/x.hpp: No such file'
    assert corpus_run.build_error('\nsomething odd\n\n') == 'something odd'
    late = ('-- ==> add_subdirectory(racecar_gazebo)\n[ 50%] Building CXX object ackermann_cmd_mux/x.o\n'
            '/ws/src/ackermann_cmd_mux/src/n.cpp:4:10: fatal error: pluginlib/class_list_macros.h: No such file\n')
    assert corpus_run.build_error(late) == 'ackermann_cmd_mux: fatal error: pluginlib/class_list_macros.h: No such file'


def test_launch_notes_read_deaths_missing_packages_and_fatal_errors():
    log = '\n'.join(['[spawn_urdf-4] process has finished cleanly',
                     '\x1b[31m[servo_commands-7] process has died [pid 12, exit code 1, cmd ...]\x1b[0m',
                     "[FATAL] [1795650395.998838, 0.000000]: could not load world: world file 'w' not found",
                     '[gazebo-2] process has died [pid 13, exit code -11, cmd ...]',
                     'ERROR: cannot launch node of type [twist_mux/twist_mux]: twist_mux',
                     'Resource not found: moveit_ros_move_group'])
    notes = corpus_run.launch_notes(log)
    assert notes['died'] == ['gazebo (exit -11)', 'servo_commands (exit 1)']
    assert notes['missing'] == ['twist_mux/twist_mux (twist_mux)']
    assert notes['errors'] == ['Resource not found: moveit_ros_move_group']
    assert notes['fatal'] == ["could not load world: world file 'w' not found"]


# --- the table -------------------------------------------------------------------------------------

def result(name, build='ok', checks=None, **more):
    r = {'name': name, 'covers': ['x'], 'commands': ['roslaunch a b.launch'], 'build': build,
         'repos': [{'repo': 'o/n', 'commit': COMMIT, 'note': ''}], 'checks': checks or []}
    r.update(more)
    r.setdefault('status', table.status(r))
    return r


def test_status_passes_only_with_a_good_build_and_every_check():
    ok = {'kind': 'drive', 'ok': True, 'numbers': '0.11 m/s'}
    bad = {'kind': 'sensors', 'ok': False, 'numbers': '', 'reason': 'no /imu'}
    assert table.status(result('a', checks=[ok])) == 'pass'
    assert table.status(result('a', checks=[ok, bad])) == 'fail'
    assert table.status(result('a', build='failed: x', checks=[ok])) == 'fail'
    assert table.status(result('a', checks=[])) == 'fail'
    assert table.status({'status': 'not run'}) == 'not run'


def test_the_first_reason_is_the_build_then_the_first_failed_check():
    bad1 = {'kind': 'drive', 'ok': False, 'reason': 'speed 0'}
    bad2 = {'kind': 'sensors', 'ok': False, 'reason': 'no /imu'}
    assert table.first_reason(result('a', build='failed: p: find_package(gazebo) found nothing', checks=[bad1])) == (
        'build failed: p: find_package(gazebo) found nothing')
    assert table.first_reason(result('a', checks=[{'kind': 'x', 'ok': True}, bad1, bad2])) == 'drive: speed 0'
    assert table.first_reason(result('a', checks=[{'kind': 'x', 'ok': True}])) == ''


def test_markdown_has_one_table_row_per_result_with_cells_escaped():
    results = [result('bot_a', checks=[{'kind': 'drive', 'ok': True, 'numbers': '0.11 m/s'}]),
               result('bot_b', checks=[{'kind': 'sensors', 'ok': False, 'numbers': 'a | b', 'reason': 'x|y\nz'}])]
    text = table.markdown(results, ['# corpus', 'run 2024-01-01 on abc'])
    rows = [line for line in text.splitlines() if line.startswith('| bot_')]
    assert len(rows) == 2 and '**pass**' in rows[0] and '**fail**' in rows[1]
    assert 'x\\|y z' in rows[1] and rows[1].count(' | ') == 6
    assert '1 of 2 rows pass, 1 fail.' in text and 'run 2024-01-01 on abc' in text
    assert '### bot_b (fail)' in text and 'FAIL **sensors**' in text


def test_a_long_cell_is_cut():
    assert len(table.cell('x' * 500)) == table.CELL_LIMIT and table.cell('x' * 500).endswith('...')


def test_console_and_json():
    results = [result('bot_a', checks=[{'kind': 'drive', 'ok': False, 'reason': 'speed 0'}])]
    assert 'bot_a  fail' in table.console(results) and 'drive: speed 0' in table.console(results)
    assert '"racebot_commit": "abc"' in table.to_json(results, {'racebot_commit': 'abc'})


# --- the floor under a point, read from a world file -------------------------------------------------

DAE = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="0.01" name="centimeter"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="slab" name="slab"><mesh>
    <source id="slab-pos"><float_array id="slab-pos-array" count="12">-100 -100 0 100 -100 0 100 100 0 -100 100 0
      </float_array><technique_common><accessor source="#slab-pos-array" count="4" stride="3">
      <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor>
      </technique_common></source>
    <vertices id="slab-vtx"><input semantic="POSITION" source="#slab-pos"/></vertices>
    <triangles count="2"><input semantic="VERTEX" source="#slab-vtx" offset="0"/><p>0 1 2 0 2 3</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="top">
    <matrix>1 0 0 0 0 1 0 0 0 0 1 20 0 0 0 1</matrix>
    <instance_geometry url="#slab"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
"""


def write_floor_world(root):
    """A world as the AWS packages write them: a <model> holding an <include> of a model whose mesh URI is a
    relative file:// (found on the resource path), a box, and Gazebo's ground plane (not on the model path)."""
    model = root / 'models' / 'slab_floor'
    (model / 'meshes').mkdir(parents=True)
    (model / 'meshes' / 'slab.DAE').write_text(DAE)
    (model / 'model.config').write_text('<model><name>slab</name><sdf version="1.6">model.sdf</sdf></model>')
    (model / 'model.sdf').write_text(
        '<sdf version="1.6"><model name="slab_floor"><static>1</static><link name="link"><collision name="c">'
        '<geometry><mesh><uri>file://models/slab_floor/meshes/slab.DAE</uri><scale>1 1 2</scale></mesh></geometry>'
        '</collision></link></model></sdf>')
    world = root / 'test.world'
    world.write_text(
        '<?xml version="1.0"?>\n<sdf version="1.6"><world name="default">'
        '<include><uri>model://sun</uri></include><include><uri>model://ground_plane</uri></include>'
        '<model name="Floor_001"><include><uri>model://slab_floor</uri></include><pose>0 0 -0.3 0 0 0</pose></model>'
        '<model name="crate"><static>1</static><pose>5 0 0 0 0 0.5</pose><link name="l"><pose>0 0 0.25 0 0 0</pose>'
        '<collision name="c"><geometry><box><size>1 1 0.5</size></box></geometry></collision></link></model>'
        '</world></sdf>')
    return world


def test_the_floor_is_the_highest_collision_surface_under_a_point(tmp_path):
    world = floor.WorldCollisions(str(write_floor_world(tmp_path)), [str(tmp_path / 'models')], [str(tmp_path)])
    assert world.notes == []
    # the slab: 0.2 m (20 cm, unit 0.01, node at z 20) scaled by 2 = 0.4, posed at -0.3: its top at 0.1
    z, name = world.height_at(0.2, -0.3, 0.5)
    assert z == pytest.approx(0.1) and name == 'Floor_001::slab_floor::link::c'
    assert world.height_at(1.5, 0.0, 0.5) == (pytest.approx(0.0), 'ground_plane::link::collision')  # off the slab
    assert world.height_at(5.0, 0.0, 1.0) == (pytest.approx(0.5), 'crate::l::c')
    assert world.height_at(5.0, 0.0, 0.4)[1] == 'ground_plane::link::collision'  # the crate's top is above 0.4
    assert world.height_at(5.0, 0.0, -1.0) == (None, None)


def test_a_missing_mesh_is_said_and_the_rest_of_the_world_read(tmp_path):
    path = write_floor_world(tmp_path)
    (tmp_path / 'models' / 'slab_floor' / 'meshes' / 'slab.DAE').unlink()
    world = floor.WorldCollisions(str(path), [str(tmp_path / 'models')], [str(tmp_path)])
    assert any('slab.DAE' in note and 'not found' in note for note in world.notes)
    assert world.height_at(0.2, -0.3, 0.5) == (pytest.approx(0.0), 'ground_plane::link::collision')


def test_pose_matrix_turns_as_sdf_does():
    m = floor.pose_matrix('1 2 3 0 0 1.5707963267948966')
    assert m[:3, 3].tolist() == [1, 2, 3]
    assert (m[:3, :3] @ [1, 0, 0]) == pytest.approx([0, 1, 0])


def test_a_deps_row_runs_in_the_underlay_make_deps_names():
    report = ['racebot deps: from source: joy 1.15.1', '  built    joy (joystick_drivers)',
              'racebot deps: underlay: source /cache/deps/ws/devel_isolated/setup.bash', 'racebot deps: done in 1.0 s']
    assert corpus_run.underlay_of(report) == '/cache/deps/ws/devel_isolated/setup.bash'
    assert corpus_run.underlay_of(['racebot deps: no package.xml at or below x']) is None


# --- plugin_output: a compiled plugin's own words in the commands' output ---------------------------

def test_plugin_output_counts_the_text_in_every_commands_log(tmp_path):
    from corpus.checks import CheckFailed, check_plugin_output
    (tmp_path / 'command-1.log').write_text('[ INFO] [1.2]: Hello World!\nother\n')
    (tmp_path / 'command-2.log').write_text('Hello World! again\n')
    (tmp_path / 'checks.log').write_text('Hello World!\n')  # not a command's output
    row = {'logs_dir': str(tmp_path)}
    numbers = check_plugin_output({'text': 'Hello World!', 'count': 2}, row)
    assert numbers == "'Hello World!' 2 time(s) in the commands' output (command-1.log: 1, command-2.log: 1)"
    with pytest.raises(CheckFailed, match=r"appeared 2 time\(s\), the row expects 3"):
        check_plugin_output({'text': 'Hello World!', 'count': 3, 'timeout': 0}, row)


def test_a_turning_drives_path_is_its_arc_not_its_chord():
    from corpus.drive_path import travelled
    radius, rate, seconds = 1.6, 0.3, 5.0  # the racecar's turn: a chord 7 % short of the arc
    poses = [(radius * math.sin(rate * t), radius * (1 - math.cos(rate * t)), rate * t)
             for t in [seconds * k / 50 for k in range(51)]]
    length, turned = travelled(poses)
    assert length == pytest.approx(radius * rate * seconds, rel=1e-3)
    assert turned == pytest.approx(rate * seconds, rel=1e-9)
    chord = math.hypot(poses[-1][0], poses[-1][1])
    assert chord < 0.95 * length
    # a turn past half a circle is counted whole, segment by segment
    assert travelled([(0, 0, 0.0), (0, 0, 3.0), (0, 0, -3.0)])[1] == pytest.approx(3.0 + 2 * math.pi - 6.0)
