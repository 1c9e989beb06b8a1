"""make deps's parts (tools/deps/): what a package needs, where sources come from, the walk from needs to the
packages built from source (with stand-in providers and rosinstall_generator/vcstool replaced), the build log's
one-line reasons and the cache keys. rosinstall_generator itself runs once, offline, on deps_fixture's rosdistro."""
import os
from pathlib import Path

import pytest

import deps_fixture
import git_mirror
from deps import index, needs, provide, repos, resolve, underlay
from deps import run as deps_run

REPO = Path(__file__).resolve().parents[3]


def write(root, files):
    deps_fixture.write_files(str(root), files)
    return str(root)


# --- needs ------------------------------------------------------------------------------------------

def test_launch_names_are_node_and_test_packages_and_every_find_outside_comments():
    text = '''<launch>
      <arg name="m" default="$(find map_pkg)/maps/a.yaml"/>
      <include file="$(find nav_pkg)/launch/x.launch"/>
      <node pkg="amcl" type="amcl" name="amcl"/>
      <test pkg="rostest_pkg" type="t" test-name="t"/>
      <node pkg="$(arg driver)" type="d" name="d"/>
      <param name="p" command="$(find xacro)/xacro $(find robot_desc)/urdf/r.xacro"/>
      <rosparam subst_value="true">file: $(find yaml_pkg)/a.yaml</rosparam>
      <!-- <include file="$(find multimaster_launch)/launch/multimaster_robot.launch"/> -->
    </launch>'''
    assert needs.launch_names(text) == {'map_pkg', 'nav_pkg', 'amcl', 'rostest_pkg', 'xacro', 'robot_desc', 'yaml_pkg'}


def test_a_plugin_lookup_name_given_as_a_param_or_arg_value_names_its_package():
    """turtlebot3_navigation's move_base.launch names dwa_local_planner only so; topics, frames and file paths,
    lower case after the slash, are not plugins."""
    text = '''<launch>
      <arg name="global" default="navfn/NavfnROS"/>
      <param name="base_local_planner" value="dwa_local_planner/DWAPlannerROS"/>
      <param name="base_global_planner" value="$(arg global)"/>
      <param name="odom_topic" value="husky_velocity_controller/odom"/>
      <arg name="map" value="maps/Map.yaml"/>
      <param name="frame" value="base_link"/>
    </launch>'''
    assert needs.launch_names(text) == {'dwa_local_planner', 'navfn'}


def test_a_launch_file_that_is_not_xml_still_gives_its_finds():
    assert needs.launch_names('<launch><include file="$(find a_pkg)/x.launch"></launch') == {'a_pkg'}


def test_declared_dependencies_follow_conditions_and_test_flag(tmp_path):
    write(tmp_path / 'p', {'package.xml': '''<?xml version="1.0"?>
<package format="3"><name>p</name><version>1.0.0</version><description>d</description>
<maintainer email="a@example.com">a</maintainer><license>BSD</license>
<buildtool_depend>catkin</buildtool_depend>
<depend>roscpp</depend>
<depend condition="$ROS_VERSION == 2">rclcpp</depend>
<exec_depend condition="$ROS_PYTHON_VERSION == 3">python3-yaml</exec_depend>
<test_depend>rostest</test_depend>
</package>'''})
    (folder, package), = needs.local_packages(str(tmp_path)).values()
    assert folder == str(tmp_path / 'p')
    assert needs.declared(package) == {'catkin', 'roscpp', 'python3-yaml', 'rostest'}
    assert needs.declared(package, tests=False) == {'catkin', 'roscpp', 'python3-yaml'}


def test_needs_of_a_workspace_name_their_needers_and_leave_out_its_own_packages(tmp_path):
    write(tmp_path, {'a/package.xml': deps_fixture.package_xml('a', ['b', 'std_msgs']),
                     'a/launch/a.launch': '<launch><node pkg="teleop_twist_keyboard" type="t" name="t"/></launch>',
                     'b/package.xml': deps_fixture.package_xml('b', ['std_msgs']),
                     'c/CATKIN_IGNORE': '', 'c/package.xml': deps_fixture.package_xml('c', ['hidden'])})
    found = needs.needs_of(needs.local_packages(str(tmp_path)))
    assert found == {'catkin': {'a', 'b'}, 'std_msgs': {'a', 'b'}, 'teleop_twist_keyboard': {'a'}}


def test_every_stand_in_that_gives_way_is_a_racebot_stand_in():
    assert all((REPO / 'upstream_compat' / name / 'package.xml').is_file() for name in needs.GIVE_WAY)


# --- where sources come from -------------------------------------------------------------------------

def test_github_urls_map_to_owner_and_name():
    assert repos.github_repo('https://github.com/ros-planning/navigation.git') == 'ros-planning/navigation'
    assert repos.github_repo('https://github.com/ros/roslint') == 'ros/roslint'
    assert repos.github_repo('https://gitlab.com/x/y.git') is None


def test_local_copies_are_found_as_make_corpus_finds_them(tmp_path):
    (tmp_path / 'clones' / 'roslint' / '.git').mkdir(parents=True)
    mirror = tmp_path / 'mirrors' / 'ros-planning+navigation' / 'repo'
    mirror.mkdir(parents=True)
    (mirror / 'HEAD').write_text('ref: refs/heads/noetic-devel\n')
    clones, mirrors = str(tmp_path / 'clones'), str(tmp_path / 'mirrors')
    assert repos.local_copy('https://github.com/ros/roslint.git', clones, mirrors) == str(tmp_path / 'clones' /
                                                                                          'roslint')
    assert repos.local_copy('https://github.com/ros-planning/navigation.git', clones, mirrors) == str(mirror)
    assert repos.local_copy('https://github.com/ros/other.git', clones, mirrors) is None


def test_vcs_import_output_gives_each_repository_its_first_error():
    output = ('=== src/a (git) ===\nCloning into \'.\'...\n=== src/b (git) ===\n'
              'Could not checkout ref \'9.9\': error: pathspec \'9.9\' did not match\nmore\n'
              '=== src/c (git) ===\nCould not clone repository \'/m\': Cloning into \'.\'...\ndone.\n'
              'error: unable to read sha1 file of x.stl (ab12)\nfatal: unable to checkout working tree\n')
    assert repos._vcs_errors(output) == {
        'b': "Could not checkout ref '9.9': error: pathspec '9.9' did not match",
        'c': "Could not clone repository '/m': error: unable to read sha1 file of x.stl (ab12)"}


def test_the_error_of_a_release_repositorys_package_is_found_by_its_local_name():
    """vcs import prints each repository's path as given, absolute under the underlay's src, and a release
    repository's local name has two parts: its error was looked up by the last part only and never found (the row
    then said only "see vcs-import.log")."""
    sha = '6e139cbd0e1a942d90deec82427ae99a039932e1'
    output = ('=== /ws/src/robot_localization-release/robot_localization (git) ===\n'
              'remote: fatal: unable to read %s\n'
              '=== /ws/src/joy (git) ===\nCould not checkout ref \'1.15.1\': error: pathspec\n' % sha)
    assert repos._vcs_errors(output, '/ws/src') == {
        'robot_localization-release/robot_localization': 'fatal: unable to read ' + sha,
        'joy': "Could not checkout ref '1.15.1': error: pathspec"}


@pytest.mark.parametrize('remote_first', [True, False])
def test_a_shallow_fetch_of_a_copy_lacking_an_object_names_the_object_in_either_order_of_gits_lines(remote_first):
    """git's remote side (pack-objects) and its local side write to one stream: either line may come first
    (1 run in 8 of the same fetch put the local side's first); the error is the object, not the dying process."""
    sha = '8b0c466f4d55057173c2d9ac96438ddca22930d6'
    remote = 'remote: fatal: unable to read %s' % sha
    local = 'error: git upload-pack: git-pack-objects died with error.'
    lines = [remote, local] if remote_first else [local, remote]
    output = '=== src/models (git) ===\n%s\nfatal: protocol error: bad pack header\n' % '\n'.join(lines)
    assert repos._vcs_errors(output) == {'models': 'fatal: unable to read %s' % sha}


def _copy_lacking(tmp_path, lacking):
    """A mirror of a repository tagged 0.5.2 (small.txt, mesh.stl, test/data/run.bag) whose objects of the paths
    `lacking` (files: their blobs; folders: their trees) were left out, as a snapshot that leaves large files out."""
    mirror = tmp_path / 'mirror.git'
    git_mirror.mirror_lacking(tmp_path / 'source', {'small.txt': b'a\n', 'mesh.stl': b'solid x\n' * 100,
                                                    'test/data/run.bag': b'#ROSBAG\n' * 100},
                              mirror, lacking, tag='0.5.2')
    (tmp_path / 'build').mkdir()
    return mirror


def test_a_copy_lacking_some_files_is_checked_out_without_them_and_says_which(tmp_path):
    """ridgeback's EKF: the snapshot of robot_localization's release repository lacks test/test3.bag, which its
    build (tests off) never reads; vcstool's clone fails on it, so the release is checked out without it."""
    mirror = _copy_lacking(tmp_path, ['mesh.stl', 'test/data/run.bag'])
    said = []
    failed = repos.checkout({'models': {'type': 'git', 'url': str(mirror), 'version': '0.5.2'}},
                            str(tmp_path / 'src'), str(tmp_path / 'build'), say=said.append)
    assert failed == {}
    checkout = tmp_path / 'src' / 'models'
    assert repos.at_version(str(checkout), '0.5.2')
    assert (checkout / 'small.txt').read_text() == 'a\n'
    assert not (checkout / 'mesh.stl').exists() and not (checkout / 'test' / 'data' / 'run.bag').exists()
    assert len(said) == 1 and 'without mesh.stl, test/data/run.bag' in said[0], said
    # a second run finds it at its version and checks nothing out
    assert repos.checkout({'models': {'type': 'git', 'url': str(mirror), 'version': '0.5.2'}},
                          str(tmp_path / 'src'), str(tmp_path / 'build'), say=said.append) == {}
    assert len(said) == 1


def test_a_copy_lacking_a_folder_is_reported_with_gits_error_not_vcstools_retry(tmp_path):
    """A copy lacking a tree cannot say which files it lacks, so it is not checked out: the error is git's (vcstool's
    retry cloned into the half-written folder and said only "destination path '.' already exists")."""
    mirror = _copy_lacking(tmp_path, ['test'])
    failed = repos.checkout({'models': {'type': 'git', 'url': str(mirror), 'version': '0.5.2'}},
                            str(tmp_path / 'src'), str(tmp_path / 'build'), say=lambda line: None)
    assert list(failed) == ['models']
    assert 'bad tree object' in failed['models'] and '(test)' in failed['models'], failed  # the folder, named
    assert 'already exists' not in failed['models']
    assert not (tmp_path / 'src' / 'models').exists()  # nothing half checked out is left to build


def test_a_copy_missing_objects_only_outside_the_release_still_checks_the_release_out(tmp_path):
    """hector_models' snapshot lacks meshes its default branch added after 0.5.2: a full clone checks that branch
    out first and fails; the shallow import takes the tag's commit alone."""
    import subprocess

    def git(*args, cwd=None):
        return subprocess.run(['git', '-c', 'user.email=t@t', '-c', 'user.name=t'] + list(args), cwd=cwd,
                              check=True, capture_output=True, text=True).stdout.strip()
    work = tmp_path / 'source'
    work.mkdir()
    (work / 'small.txt').write_text('a\n')
    git('init', '-q', cwd=work)
    git('add', '.', cwd=work)
    git('commit', '-qm', 'one', cwd=work)
    git('tag', '0.5.2', cwd=work)
    (work / 'mesh.stl').write_bytes(b'solid later\n' * 100)
    git('add', '.', cwd=work)
    git('commit', '-qm', 'two', cwd=work)
    mirror = tmp_path / 'mirror.git'
    git('clone', '-q', '--mirror', str(work), str(mirror))
    blob = git('rev-parse', 'HEAD:mesh.stl', cwd=work)
    (mirror / 'objects' / blob[:2] / blob[2:]).unlink()
    (tmp_path / 'build').mkdir()
    failed = repos.checkout({'models': {'type': 'git', 'url': str(mirror), 'version': '0.5.2'}},
                            str(tmp_path / 'src'), str(tmp_path / 'build'))
    assert failed == {}
    assert repos.at_version(str(tmp_path / 'src' / 'models'), '0.5.2')
    assert (tmp_path / 'src' / 'models' / 'small.txt').read_text() == 'a\n'


@pytest.fixture(scope='module')
def world(tmp_path_factory):
    root = tmp_path_factory.mktemp('deps_world')
    return dict(deps_fixture.make_world(str(root)), root=str(root))


def test_rosinstall_generator_names_release_tags_offline_from_a_local_rosdistro(world, tmp_path):
    folder = index.materialise(world['rosdistro'], str(tmp_path))
    assert index.materialise(world['rosdistro'], str(tmp_path)) == folder  # made once
    env = dict(os.environ, ROSDISTRO_INDEX_URL='file://%s/index-v4.yaml' % folder)
    data, unreleased, error = repos.generate(['probe_tools', 'probe_unused', 'nowhere'], env)
    assert (unreleased, error) == ({'nowhere'}, '')
    assert data == {name: {'type': 'git', 'url': 'https://github.com/racebot-fixture/%s.git' % name, 'version': version}
                    for name, version in (('probe_tools', '0.2.0'), ('probe_core', '0.1.0'))}


def test_a_rosdistro_git_directory_is_materialised_from_its_head(world, tmp_path):
    deps_fixture.git_repo(world['rosdistro'], {}, 'v1')
    folder = index.materialise(os.path.join(world['rosdistro'], '.git'), str(tmp_path))
    assert sorted(os.listdir(folder)) == ['index-v4.yaml', 'noetic', 'noetic-cache.yaml', 'rosdep']


def test_a_folder_that_is_no_rosdistro_is_refused_with_a_reason(tmp_path):
    with pytest.raises(index.RosdistroError, match='neither a rosdistro checkout'):
        index.materialise(str(tmp_path), str(tmp_path / 'cache'))


def test_rosdeps_sources_list_has_debians_rules_first_then_the_local_rosdistros(tmp_path):
    write(tmp_path, {'rosdep/base.yaml': '{}', 'rosdep/python.yaml': '{}'})
    lines = index.sources_list(str(tmp_path)).splitlines()[1:]
    expected = ['yaml file://%s/rosdep/%s' % (tmp_path, name) for name in ('base.yaml', 'python.yaml')]
    if os.path.isfile(index.DEBIAN_RULES):
        expected.insert(0, 'yaml file://%s debian' % index.DEBIAN_RULES)
    assert lines == expected


# --- the walk ----------------------------------------------------------------------------------------

class FakeProviders:
    def __init__(self, kinds):
        self.kinds = kinds

    def provider(self, name):
        return provide.Provider(self.kinds.get(name, 'source'))


def test_the_walk_fetches_what_nobody_provides_and_follows_the_fetched_package_xml(tmp_path, monkeypatch):
    """`target` needs std_msgs (installed), twist_mux (a stand-in that gives way: fetched), nav (in a repository
    that also holds nav_core, which nav needs) and ghost (released nowhere)."""
    launch = '<launch><node pkg="twist_mux" type="twist_mux" name="m"/><node pkg="ghost" type="g" name="g"/></launch>'
    target = write(tmp_path / 'target', {'t/package.xml': deps_fixture.package_xml('t', ['std_msgs', 'nav']),
                                         't/launch/t.launch': launch})
    released = {'nav': 'navigation', 'nav_core': 'navigation', 'twist_mux': 'twist_mux'}
    asked = []

    def generate(names, env):
        asked.append(sorted(names))
        data = {released[n]: {'type': 'git', 'url': 'https://github.com/o/%s.git' % released[n], 'version': '1.0'}
                for n in names if n in released}
        return data, {n for n in names if n not in released}, ''

    def checkout(wanted, src, work, clones=None, mirrors=None, say=print):
        files = {'navigation/nav/package.xml': deps_fixture.package_xml('nav', ['nav_core', 'roscpp']),
                 'navigation/nav_core/package.xml': deps_fixture.package_xml('nav_core', ['roscpp']),
                 'twist_mux/package.xml': deps_fixture.package_xml('twist_mux', ['roscpp'])}
        write(src, {rel: text for rel, text in files.items() if rel.split('/')[0] in wanted})
        return {}

    monkeypatch.setattr(repos, 'generate', generate)
    monkeypatch.setattr(repos, 'checkout', checkout)
    ws = underlay.Workspace(str(tmp_path / 'ws'))
    providers = FakeProviders({'std_msgs': 'installed', 'roscpp': 'installed', 'catkin': 'installed',
                               'twist_mux': 'source'})
    local, names = resolve.targets([target])
    result, src_packages = resolve.walk(local, names, providers, {'env': {}, 'ws': ws, 'say': lambda line: None})
    assert asked == [['ghost', 'nav', 'twist_mux']]  # nav_core came with nav's repository: not asked for again
    assert result.selected == {'nav': 'navigation', 'nav_core': 'navigation', 'twist_mux': 'twist_mux'}
    assert list(result.unknown) == ['ghost']
    assert result.needed_by['nav_core'] == ['nav']
    assert sorted(src_packages) == ['nav', 'nav_core', 'twist_mux']


def test_a_source_tag_missing_from_its_copy_is_taken_from_the_release_repository_and_failures_stay_apart(
        tmp_path, monkeypatch):
    """`loc`'s source copy lacks its release tag (a stale mirror): its release repository's tag of the same
    release is checked out instead. `cam`'s and `joy`'s source repositories fail for reasons of their own, and
    their release repositories too: each name's reason is its own repository's, not the round's first."""
    target = write(tmp_path / 'target', {'t/package.xml': deps_fixture.package_xml('t', ['loc', 'cam', 'joy'])})
    holders = {'loc': 'robot_localization', 'cam': 'cv_camera', 'joy': 'joystick_drivers'}
    asked = []

    def generate(names, env, upstream=True):
        asked.append((sorted(names), upstream))
        if upstream:
            return {holders[n]: {'type': 'git', 'url': 'https://github.com/o/%s.git' % holders[n], 'version': '2.7.7'}
                    for n in names}, set(), ''
        return {'%s/%s' % (holders[n], n) if n == 'joy' else n: {
            'type': 'git', 'url': 'https://github.com/o/%s-release.git' % holders[n],
            'version': 'release/noetic/%s/2.7.7-1' % n} for n in names}, set(), ''

    def checkout(wanted, src, work, clones=None, mirrors=None, say=print):
        if 'robot_localization-release/loc' in wanted:
            write(src, {'robot_localization-release/loc/package.xml': deps_fixture.package_xml('loc', ['roscpp'])})
        return {name: 'cannot check out %s: %s' % (name, name.split('/')[0]) for name in wanted
                if name != 'robot_localization-release/loc'}

    monkeypatch.setattr(repos, 'generate', generate)
    monkeypatch.setattr(repos, 'checkout', checkout)
    monkeypatch.setattr(repos, 'repositories_of', lambda names, env: {n: holders[n] for n in names})
    ws = underlay.Workspace(str(tmp_path / 'ws'))
    local, names = resolve.targets([target])
    providers = FakeProviders({'roscpp': 'installed', 'catkin': 'installed'})
    result, src_packages = resolve.walk(local, names, providers, {'env': {}, 'ws': ws, 'say': lambda line: None})
    assert asked == [(['cam', 'joy', 'loc'], True), (['cam', 'joy', 'loc'], False)]
    assert result.selected == {'loc': 'robot_localization-release/loc'}
    assert result.repos['robot_localization-release/loc']['version'] == 'release/noetic/loc/2.7.7-1'
    assert result.unknown == {
        'cam': 'cannot check out cv_camera: cv_camera; release repository: cannot check out '
               'cv_camera-release/cam: cv_camera-release',
        'joy': 'cannot check out joystick_drivers: joystick_drivers; release repository: cannot check out '
               'joystick_drivers-release/joy: joystick_drivers-release'}


def test_release_entries_get_a_folder_of_their_own_named_after_the_release_repository():
    data = {'navigation/amcl': {'type': 'git', 'url': 'https://github.com/ros-gbp/navigation-release.git',
                                'version': 'release/noetic/amcl/1.17.3-1'},
            'robot_localization': {'type': 'git', 'url': 'https://github.com/cra-ros-pkg/robot_localization-release.git',
                                   'version': 'release/noetic/robot_localization/2.7.7-1'}}
    assert sorted(repos.release_entries(data)) == ['navigation-release/amcl',
                                                   'robot_localization-release/robot_localization']


def test_a_stand_in_that_gives_way_is_built_from_source_and_the_others_are_provided(tmp_path):
    providers = provide.Providers.__new__(provide.Providers)
    providers.give_way = set(needs.GIVE_WAY)
    assert providers.provider('twist_mux').kind == 'source'


# --- the build: one-line reasons, who is skipped, the keys ---------------------------------------------

def test_the_first_error_of_a_package_build_is_one_line():
    missing = ('CMake Warning at /usr/share/catkin/cmake/catkinConfig.cmake:82 (find_package):\n'
               '  Could not find a package configuration file provided by "pluginlib" with any\n')
    assert underlay.first_error(missing) == 'find_package(pluginlib) found nothing'
    compiled = ('[ 50%] Building CXX object\n/ws/src/nav/amcl/src/amcl.cpp:31:10: fatal error: '
                'pluginlib/class_list_macros.h: No such file or directory\n   31 | #include\n')
    assert underlay.first_error(compiled, '/ws/src/nav/amcl') == \
        'src/amcl.cpp:31: fatal error: pluginlib/class_list_macros.h: No such file or directory'
    cmake = 'CMake Error at CMakeLists.txt:5 (message):\n  something is wrong\n\n'
    assert underlay.first_error(cmake) == 'CMake Error at CMakeLists.txt:5 (message): something is wrong'
    refused = ('CMake Error at /x/gazebo_dev-extras.cmake:5 (find_package):\n  Found package configuration file:\n\n'
               '    /x/gazebo-config.cmake\n\n'
               '  but it set gazebo_FOUND to FALSE so package "gazebo" is considered to be\n'
               '  NOT FOUND.  Reason given by package:\n\n'
               '  racebot: package \'cam\' includes a Gazebo header\n'
               '  that racebot does not have.\n\nCall Stack (most recent call first):\n')
    assert underlay.first_error(refused) == ('CMake Error at /x/gazebo_dev-extras.cmake:5 (find_package): racebot: '
                                             "package 'cam' includes a Gazebo header that racebot does not have.")


def test_the_log_section_of_a_package_starts_at_its_processing_line():
    log = "==> Processing catkin package: 'a'\nok\n==> Processing catkin package: 'b'\nerror: b broke\n"
    assert underlay.section(log, 'b').splitlines()[0] == "==> Processing catkin package: 'b'"


def test_the_packages_needing_a_failed_one_are_skipped_transitively(tmp_path):
    write(tmp_path, {'%s/package.xml' % name: deps_fixture.package_xml(name, depends)
                     for name, depends in (('a', []), ('b', ['a']), ('c', ['b']), ('d', []))})
    packages = needs.local_packages(str(tmp_path))
    assert underlay.dependents('a', packages) == {'b', 'c'}


def test_the_build_key_changes_with_a_version_and_with_the_workspace_below():
    repos_ = {'navigation': {'url': 'u', 'version': '1.17.3'}}
    key = underlay.build_key(repos_, ['amcl'], [['/r/devel', ['a']]])
    assert key == underlay.build_key(dict(repos_), ['amcl'], [['/r/devel', ['a']]])
    assert key != underlay.build_key({'navigation': {'url': 'u', 'version': '1.17.4'}}, ['amcl'], [['/r/devel', ['a']]])
    assert key != underlay.build_key(repos_, ['amcl'], [['/r/devel', ['a', 'pluginlib']]])


def test_the_resolution_key_changes_when_a_launch_file_names_something_new(tmp_path):
    target = write(tmp_path, {'t/package.xml': deps_fixture.package_xml('t'),
                              't/launch/a.launch': '<launch/>'})
    local = needs.local_packages(target)
    key = deps_run.resolution_key(local, [], {})
    assert key == deps_run.resolution_key(local, [], {})
    (tmp_path / 't' / 'launch' / 'a.launch').write_text('<launch><node pkg="amcl" type="amcl" name="a"/></launch>')
    assert key != deps_run.resolution_key(local, [], {})


def test_the_build_ignores_the_fetched_packages_others_provide(tmp_path):
    # hector_gazebo brings hector_gazebo_plugins (racebot's) beside hector_sensors_gazebo (taken): only-pkg-with-deps
    # alone would build the source copy of the former, which needs Gazebo's removed gazebo/math headers
    ws = underlay.Workspace(str(tmp_path / 'ws'))
    cmd = underlay.cmi_command(ws, {'hector_sensors_gazebo'}, {'hector_sensors_gazebo': None,
                                                               'hector_gazebo_plugins': None})
    at = cmd.index('--only-pkg-with-deps')
    assert cmd[at + 1:at + 4] == ['hector_sensors_gazebo', '--ignore-pkg', 'hector_gazebo_plugins']
    assert '--ignore-pkg' not in underlay.cmi_command(ws, {'a'}, {'a': None})


def test_a_cmake_package_racebot_configures_is_racebots(tmp_path, monkeypatch):
    # `gazebo` (hector_quadrotor_gazebo_plugins' <depend>gazebo</depend>) is no ROS package and has no Debian rule:
    # racebot's devel space answers its find_package
    root = tmp_path / 'racebot'
    config = root / 'devel' / 'lib' / 'cmake' / 'gazebo' / 'gazebo-config.cmake'
    config.parent.mkdir(parents=True)
    config.write_text('set(gazebo_FOUND TRUE)\n')
    providers = provide.Providers.__new__(provide.Providers)
    providers.racebot_root = os.path.realpath(str(root))
    monkeypatch.setenv('CMAKE_PREFIX_PATH', os.pathsep.join(['/opt/other', str(root / 'devel')]))
    assert providers.cmake_config('gazebo') == str(config)
    assert providers.cmake_config('ignition-math6') is None
    # the rosdep keys of Gazebo 11's development files (ridgeback_gazebo_plugins names libgazebo11-dev) are the same
    providers.give_way = set()
    providers.rospack = type('NoPackages', (), {'get_path': lambda self, name: (_ for _ in ()).throw(KeyError(name))})()
    for key in ('libgazebo11-dev', 'gazebo11'):
        assert (providers.provider(key).kind, providers.provider(key).where) == ('racebot', str(config))


def test_a_failed_exec_dependency_leaves_a_package_buildable(tmp_path):
    write(tmp_path, {'a/package.xml': deps_fixture.package_xml('a'),
                     'b/package.xml': deps_fixture.package_xml('b', exec_depends=['a']),
                     'c/package.xml': deps_fixture.package_xml('c', ['a'])})
    assert underlay.dependents('a', needs.local_packages(str(tmp_path))) == {'c'}
