"""world_server.load_world_spec: gzserver (gazebo_ros's, fallback_to_empty) loads worlds/empty.world when the
world file it is given cannot be loaded, as Gazebo 11's Server::ParseArgs ("Could not open file[...]", then
"Falling back on worlds/empty.world"); racebot's own world_server keeps that fatal. No ROS master."""
import os

import pytest

from racebot_sim_bridge.description.sdf_reader import WorldError
from racebot_sim_bridge.world_server import load_world_spec

from fakes import FakeLog


def test_missing_world_falls_back_on_the_empty_world(tmp_path):
    # jackal_gazebo's default: $(find gazebo_ros)/worlds/empty_world.world, which gazebo_ros never shipped
    missing = str(tmp_path / 'gazebo_ros' / 'worlds' / 'empty_world.world')
    log = FakeLog()
    path, world = load_world_spec(missing, fallback_to_empty=True, log=log)
    assert path.endswith(os.path.join('worlds', 'empty.world'))
    assert [m.name for m in world.models] == ['ground_plane']
    assert log.lines[0][0] == 'error' and log.lines[0][1].startswith('Could not open file[%s]' % missing)
    assert log.lines[1] == ('warn', 'Falling back on worlds/empty.world')


def test_world_that_is_not_sdf_falls_back_too(tmp_path):
    broken = tmp_path / 'broken.world'
    broken.write_text('<sdf version="1.6"><world name="x"><model name="m"></world>')
    path, world = load_world_spec(str(broken), fallback_to_empty=True, log=FakeLog())
    assert path.endswith(os.path.join('worlds', 'empty.world'))
    assert [m.name for m in world.models] == ['ground_plane']


def test_without_fallback_a_missing_world_is_an_error(tmp_path):
    missing = str(tmp_path / 'missing.world')
    with pytest.raises(WorldError, match='not found'):
        load_world_spec(missing, log=FakeLog())


def test_a_world_that_loads_is_used(tmp_path):
    good = tmp_path / 'good.world'
    good.write_text('<sdf version="1.6"><world name="x"><model name="box"><static>true</static><link name="l">'
                    '<collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>'
                    '</link></model></world></sdf>')
    log = FakeLog()
    path, world = load_world_spec(str(good), fallback_to_empty=True, log=log)
    assert path == str(good) and [m.name for m in world.models] == ['box'] and log.lines == []
