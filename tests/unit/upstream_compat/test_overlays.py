"""upstream_compat's overlays of pluginlib and class_loader: when they step aside, and what their configs give.

step_aside.cmake with RACEBOT_STEP_ASIDE_BELOW_VERSION: plain CMake projects named pluginlib and class_loader
include it with a prefix holding a package.xml of the version under test, as an underlay would: Noetic's pluginlib
1.13 and class_loader 0.5 make ours step aside, a ROS 2-generation package (Debian's pluginlib 5.2.1) is overlaid.
The configs in racebot's devel space (needs `make build`): `find_package(catkin COMPONENTS nodelet)` brings the
overlays' include folders, the global placeholders' folder first of class_loader's, and Debian's libraries; the
placeholders header makes a bare `_1` compile against Boost 1.74, which it does not without it. No master.
"""
import os
import subprocess
import textwrap
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
STEP_ASIDE = REPO / 'upstream_compat' / 'cmake' / 'step_aside.cmake'
DEVEL = REPO / 'devel'
PLACEHOLDERS = REPO / 'upstream_compat' / 'roscpp' / 'include' / 'boost_global_placeholders'


def configure(tmp_path, name, cmake, prefix, languages='NONE'):
    """(exit code, output, {variable: value} of `probe` lines) of configuring a project `name` with `prefix` as
    the only CMAKE_PREFIX_PATH (a sourced racebot devel space would be an underlay with our own overlays)."""
    src = tmp_path / name
    src.mkdir(parents=True, exist_ok=True)
    (src / 'CMakeLists.txt').write_text('cmake_minimum_required(VERSION 3.0.2)\nproject(%s %s)\n%s'
                                        % (name, languages, cmake))
    command = ['cmake', '-S', str(src), '-B', str(tmp_path / ('build-' + name)), '-DCMAKE_PREFIX_PATH=%s' % prefix]
    env = {key: value for key, value in os.environ.items() if key != 'CMAKE_PREFIX_PATH'}
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120, env=env)
    values = dict(line.split('probe ', 1)[1].split('=', 1) for line in done.stdout.splitlines() if 'probe ' in line)
    return done.returncode, done.stdout, values


def step_aside(tmp_path, name, version):
    """(RACEBOT_STEP_ASIDE, RACEBOT_OVERLAID_PREFIX, output) for an overlay `name` with an underlay of `version`."""
    underlay = tmp_path / 'underlay'
    (underlay / 'share' / name).mkdir(parents=True)
    (underlay / 'share' / name / 'package.xml').write_text(
        '<package format="2">\n  <name>%s</name>\n  <version>%s</version>\n</package>\n' % (name, version))
    code, output, values = configure(tmp_path, name, textwrap.dedent('''
        set(RACEBOT_STEP_ASIDE_BELOW_VERSION 2)
        include(%s)
        message(STATUS "probe aside=${RACEBOT_STEP_ASIDE}")
        message(STATUS "probe overlaid=${RACEBOT_OVERLAID_PREFIX}")
    ''' % STEP_ASIDE), prefix=underlay)
    assert code == 0, output
    return values['aside'], values['overlaid'], output


@pytest.mark.parametrize('name, version', [('pluginlib', '1.13.0'), ('class_loader', '0.5.0')])
def test_the_overlays_step_aside_for_noetics_packages(tmp_path, name, version):
    aside, _, output = step_aside(tmp_path, name, version)
    assert aside == 'TRUE', output
    assert (tmp_path / name / 'CATKIN_IGNORE').is_file()


@pytest.mark.parametrize('name, version', [('pluginlib', '5.2.1'), ('class_loader', '2.4.0')])
def test_the_overlays_hand_on_a_later_generation(tmp_path, name, version):
    aside, overlaid, output = step_aside(tmp_path, name, version)
    assert aside == 'FALSE', output
    assert overlaid == str(tmp_path / 'underlay'), output
    assert 'a later generation than ROS 1\'s; ours overlays it' in output
    assert not (tmp_path / name / 'CATKIN_IGNORE').exists()


def test_a_nodelet_package_gets_both_overlays_and_debians_libraries(tmp_path):
    if not (DEVEL / 'share' / 'pluginlib' / 'cmake' / 'pluginlibConfig.cmake').is_file():
        pytest.fail('racebot\'s pluginlib config is missing from %s: run `make build`' % DEVEL)
    code, output, values = configure(tmp_path, 'probe_nodelet', textwrap.dedent('''
        find_package(catkin REQUIRED COMPONENTS nodelet)
        message(STATUS "probe include=${catkin_INCLUDE_DIRS}")
        message(STATUS "probe libraries=${catkin_LIBRARIES}")
    '''), prefix=DEVEL, languages='CXX')
    assert code == 0, output
    include = values['include'].split(';')
    for folder in (REPO / 'upstream_compat' / 'pluginlib' / 'include', PLACEHOLDERS,
                   REPO / 'upstream_compat' / 'class_loader' / 'include', '/usr/include/pluginlib',
                   '/usr/include/class_loader'):
        assert str(folder) in include, output
    assert include.index(str(PLACEHOLDERS)) < include.index('/usr/include/class_loader')
    libraries = values['libraries'].split(';')
    for library in ('-lclass_loader', '-lroslib', '-ltinyxml2'):
        assert library in libraries, output


def test_a_plain_roscpp_package_gets_the_placeholders_and_debians_roscpp(tmp_path):
    """A node that finds only roscpp (interactive_marker_twist_server's marker_server binds with a bare _1)."""
    code, output, values = configure(tmp_path, 'probe_node', textwrap.dedent('''
        find_package(catkin REQUIRED COMPONENTS roscpp)
        message(STATUS "probe include=${catkin_INCLUDE_DIRS}")
        message(STATUS "probe libraries=${catkin_LIBRARIES}")
    '''), prefix=DEVEL, languages='CXX')
    assert code == 0, output
    assert str(PLACEHOLDERS) in values['include'].split(';'), output
    for library in ('-lroscpp', '-lrosconsole', '-lxmlrpcpp', '-lrostime'):
        assert library in values['libraries'].split(';'), output


BARE_PLACEHOLDER = textwrap.dedent('''
    #include <boost/bind/bind.hpp>
    #include <boost/function.hpp>
    int twice(int x) { return 2 * x; }
    int main() { boost::function<int(int)> f = boost::bind(&twice, _1); return f(1) == 2 ? 0 : 1; }
''')


def compile_bare_placeholder(tmp_path, include):
    source = tmp_path / 'bare.cpp'
    source.write_text(BARE_PLACEHOLDER)
    command = ['g++', '-fsyntax-only'] + ['-I%s' % folder for folder in include] + [str(source)]
    return subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)


def test_a_bare_placeholder_compiles_with_the_overlays_header(tmp_path):
    done = compile_bare_placeholder(tmp_path, [PLACEHOLDERS])
    assert done.returncode == 0, done.stdout


def test_without_it_boost_1_74_refuses_a_bare_placeholder(tmp_path):
    """What the header is for: if Boost put _1 in the global namespace again, it would be needed no more."""
    done = compile_bare_placeholder(tmp_path, [])
    assert done.returncode != 0 and "'_1' was not declared" in done.stdout.replace('\u2018', "'").replace(
        '\u2019', "'"), done.stdout


def overlay_debian(tmp_path, prefix):
    """(RACEBOT_STEP_ASIDE, RACEBOT_OVERLAID_PREFIX, output) for a project rosbag_storage with RACEBOT_OVERLAY_DEBIAN
    and `prefix` as its only underlay."""
    code, output, values = configure(tmp_path, 'rosbag_storage', textwrap.dedent('''
        set(RACEBOT_OVERLAY_DEBIAN TRUE)
        include(%s)
        message(STATUS "probe aside=${RACEBOT_STEP_ASIDE}")
        message(STATUS "probe overlaid=${RACEBOT_OVERLAID_PREFIX}")
    ''' % STEP_ASIDE), prefix=prefix)
    assert code == 0, output
    return values['aside'], values['overlaid'], output


def test_the_rosbag_storage_overlay_overlays_debians_and_steps_aside_for_noetics(tmp_path):
    aside, overlaid, output = overlay_debian(tmp_path / 'debian', '/usr')  # Debian's: /usr/share/rosbag_storage
    assert (aside, overlaid) == ('FALSE', '/usr'), output
    noetic = tmp_path / 'opt_ros_noetic'
    (noetic / 'share' / 'rosbag_storage').mkdir(parents=True)
    (noetic / 'share' / 'rosbag_storage' / 'package.xml').write_text(
        '<package format="2">\n  <name>rosbag_storage</name>\n  <version>1.15.15</version>\n</package>\n')
    aside, _, output = overlay_debian(tmp_path / 'noetic', noetic)
    assert aside == 'TRUE', output


def test_a_package_naming_rosbag_storage_gets_the_boost_libraries_noetics_exports(tmp_path):
    """slam_gmapping's slam_gmapping_replay uses boost::program_options and names only rosbag_storage: Noetic's
    config exports Boost's date_time, filesystem, program_options and regex, Debian's boost_filesystem alone."""
    code, output, values = configure(tmp_path, 'probe_bag', textwrap.dedent('''
        find_package(catkin REQUIRED COMPONENTS rosbag_storage)
        message(STATUS "probe libraries=${catkin_LIBRARIES}")
    '''), prefix=DEVEL, languages='CXX')
    assert code == 0, output
    libraries = values['libraries'].split(';')
    assert '-lrosbag_storage' in libraries, output
    assert any('boost_program_options' in library for library in libraries), output
