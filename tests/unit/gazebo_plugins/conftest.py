"""The compiled plugins' fixture project (tests/fixtures/gazebo_plugin_project), built once per test process for the
test files that load its libraries, and a world that finds them."""
import os
import shutil
import subprocess

import pytest

from model_plugin_sim import PluginWorld

HERE = os.path.dirname(os.path.abspath(__file__))
PROJECT = os.path.join(HERE, '..', '..', 'fixtures', 'gazebo_plugin_project')
BUILD_TIMEOUT = 600  # s: the plugin files on sdformat's headers take about a minute on a busy 2-core machine


@pytest.fixture(scope='session')
def plugin_dir(tmp_path_factory):
    """The fixture project configured and built as a user would: cmake, make (racebot's devel space sourced, so
    find_package(gazebo) finds racebot's config)."""
    if not shutil.which('cmake'):
        pytest.fail('cmake is missing: make setup installs it')
    build = tmp_path_factory.mktemp('gazebo_plugins_build')
    for command in (['cmake', os.path.abspath(PROJECT)], ['make', '-j2']):
        done = subprocess.run(command, cwd=build, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=BUILD_TIMEOUT)
        assert done.returncode == 0, '%s failed:\n%s' % (' '.join(command), done.stdout[-4000:])
    return str(build)


@pytest.fixture
def world(tmp_path, plugin_dir, monkeypatch):
    """A PluginWorld whose GAZEBO_PLUGIN_PATH holds the fixture project's libraries."""
    monkeypatch.setenv('GAZEBO_PLUGIN_PATH', plugin_dir)
    w = PluginWorld(tmp_path)
    yield w
    w.close()
