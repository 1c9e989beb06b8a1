"""Every launch file of the repository passes roslaunch's file check, as catkin's
`roslaunch_add_file_check(launch)` would run it (roslaunch.rlutil.check_roslaunch: XML, args, includes,
packages and node executables resolvable, `command=` params run). One test per file, found at
collection time. Uses ROS_PACKAGE_PATH of the sourced devel space (the repository is prepended if
missing). No ROS master.

racebot_gazebo's gmapping.launch starts gmapping, which Debian 12 does not have (make deps builds it), and
racebot_gazebo does not declare it in its package.xml (as turtlebot3_slam does not): the check's lines about that one
package are expected (where rospack does not find it, its node too); every other line still fails the test.
"""
import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
EXCLUDED = {'build', 'devel', '.venv', 'install', 'out', '.git', 'node_modules'}
EXAMPLE_PACKAGE = REPO / 'examples' / 'demo_diffbot'  # hidden from catkin and rospack by examples/CATKIN_IGNORE
ROBOT_FIXTURES = REPO / 'tests' / 'fixtures' / 'robots'  # the issue-17 test robots' packages
STANDIN_FIXTURES = REPO / 'tests' / 'fixtures' / 'standin_workspace'  # a workspace naming the stand-ins
PLUGIN_FIXTURES = REPO / 'tests' / 'fixtures' / 'gazebo_plugin_workspace'  # a compiled plugin package's
FROM_DEPS = {REPO / 'racebot_gazebo' / 'launch' / 'gmapping.launch': 'gmapping'}  # launch file: the package it needs


def launch_files():
    found = []
    for root, dirs, files in os.walk(REPO):
        dirs[:] = sorted(d for d in dirs if d not in EXCLUDED)
        found.extend(Path(root) / f for f in sorted(files) if f.endswith('.launch'))
    return found


LAUNCH_FILES = launch_files()


@pytest.fixture
def ros_package_path(monkeypatch):
    paths = [p for p in os.environ.get('ROS_PACKAGE_PATH', '').split(os.pathsep) if p]
    if not any(Path(p).resolve() == REPO for p in paths):
        paths = [str(REPO)] + paths
    # the example robot package's own launch file finds its package (last: it shadows nothing)
    monkeypatch.setenv('ROS_PACKAGE_PATH', os.pathsep.join(paths + [str(EXAMPLE_PACKAGE), str(ROBOT_FIXTURES),
                                                                    str(STANDIN_FIXTURES), str(PLUGIN_FIXTURES)]))
    # roslaunch keeps one RosPack for the process, made from the ROS_PACKAGE_PATH of its first $(find)
    # (an earlier test's, in a whole run): no public call resets it, so start each check with none.
    import roslaunch.substitution_args
    monkeypatch.setattr(roslaunch.substitution_args, '_rospack', None)


def test_there_are_launch_files():
    assert any(p.name == 'empty_world.launch' for p in LAUNCH_FILES)


@pytest.mark.parametrize('path', LAUNCH_FILES, ids=[str(p.relative_to(REPO)) for p in LAUNCH_FILES])
def test_launch_file_check(path, ros_package_path):
    import roslaunch.rlutil
    import rospkg
    needs = FROM_DEPS.get(path)
    error = roslaunch.rlutil.check_roslaunch(str(path))
    if needs and error:
        expected = {'Missing package dependencies: %s/package.xml: %s' % (path.parents[1].name, needs)}
        try:
            rospkg.RosPack().get_path(needs)
        except rospkg.ResourceNotFound:  # not built here (make deps ARGS=gmapping): everything else is checked
            expected |= {line for line in error.splitlines()
                         if line.startswith('ROS path [') or '[%s]' % needs in line or '[%s/' % needs in line}
        error = '\n'.join(line for line in error.splitlines() if line not in expected) or None
    assert error is None, '%s fails roslaunch-check:\n%s' % (path.relative_to(REPO), error)
