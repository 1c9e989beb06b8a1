"""world_server.parse_args / resolve_world: gzserver's command line as empty_world.launch builds it
(`[-u] [-r] [--verbose] -e PHYSICS EXTRA_ARGS WORLD`) and gzserver's world look-up; set_own_ros_time. No ROS master.
"""
import os
import time
from pathlib import Path

import genpy
import pytest

from racebot_sim_bridge.world_server import parse_args, resolve_world

REPO = Path(__file__).resolve().parents[3]
PACKAGE_EMPTY_WORLD = REPO / 'racebot_sim_bridge' / 'worlds' / 'empty.world'


def test_nothing():
    assert parse_args([]) == (None, False, False, [])


def test_the_launch_files_default_line():
    # args="$(arg command_arg1) $(arg command_arg2) $(arg command_arg3) -e ode  worlds/empty.world"
    world, paused, verbose, ignored = parse_args(['-e', 'ode', 'worlds/empty.world'])
    assert (world, paused, verbose, ignored) == ('worlds/empty.world', False, False, [])


@pytest.mark.parametrize('flag', ['-u', '--pause'])
def test_paused(flag):
    world, paused, verbose, _ = parse_args([flag, '-e', 'ode', 'w.world'])
    assert (world, paused, verbose) == ('w.world', True, False)


def test_verbose():
    world, paused, verbose, ignored = parse_args(['--verbose', 'w.world'])
    assert (world, paused, verbose, ignored) == ('w.world', False, True, [])


@pytest.mark.parametrize('flag', ['-e', '--physics'])
def test_other_physics_engine_is_noted_and_ignored(flag):
    world, _, _, ignored = parse_args([flag, 'bullet', 'w.world'])
    assert world == 'w.world'
    assert len(ignored) == 1 and 'bullet' in ignored[0]


def test_physics_value_is_not_taken_for_the_world():
    assert parse_args(['-e', 'dart'])[0] is None


def test_unknown_flags_are_ignored_and_reported():
    world, paused, _, ignored = parse_args(['-u', '-r', '--minimal_comms', '--lockstep', 'w.world'])
    assert (world, paused) == ('w.world', True)
    assert ignored[1:] == ['--minimal_comms', '--lockstep']
    assert ignored[0].startswith('-r (recording:=true')  # said once, with what it would have done


@pytest.mark.parametrize('flag', ['-r', '--record'])
def test_recording_is_named_as_such(flag):
    assert parse_args([flag, 'w.world'])[3] == ['%s (recording:=true: there are no Gazebo state logs here)' % flag]


def test_empty_arguments_from_unset_launch_args_are_skipped():
    assert parse_args(['', ' ', '-e', 'ode', '', 'w.world', ''])[0] == 'w.world'


@pytest.mark.parametrize('argv, expected', [
    (['w.world', '--seed', '42'], 'w.world'),
    (['-s', 'libgazebo_ros_api_plugin.so', '--iters', '1000'], None),
])
def test_gzserver_options_with_a_value_do_not_become_the_world(argv, expected):
    # gzserver's -s/--server-plugin, --seed, --iters, -o/--profile, --record_path, ... take a value.
    world, _, _, ignored = parse_args(argv)
    assert world == expected
    assert ignored


# -- resolve_world ------------------------------------------------------------------------------

@pytest.fixture
def elsewhere(tmp_path, monkeypatch):
    """Run from a directory without worlds/, with no GAZEBO_RESOURCE_PATH."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv('GAZEBO_RESOURCE_PATH', raising=False)
    return tmp_path


@pytest.mark.parametrize('name', ['worlds/empty.world', None, ''])
def test_empty_world_is_the_packages(elsewhere, name):
    path = resolve_world(name)
    assert os.path.isabs(path)
    assert Path(path).resolve() == PACKAGE_EMPTY_WORLD.resolve()


def test_absolute_path_is_kept(elsewhere):
    assert resolve_world('/somewhere/else/my.world') == '/somewhere/else/my.world'
    assert resolve_world(str(PACKAGE_EMPTY_WORLD)) == str(PACKAGE_EMPTY_WORLD)


def test_gazebo_resource_path_is_searched(elsewhere, tmp_path, monkeypatch):
    root = tmp_path / 'resources'
    (root / 'worlds').mkdir(parents=True)
    (root / 'worlds' / 'track.world').write_text('<sdf version="1.6"><world name="default"/></sdf>')
    monkeypatch.setenv('GAZEBO_RESOURCE_PATH', '/nonexistent:' + str(root))
    assert resolve_world('worlds/track.world') == str(root / 'worlds' / 'track.world')


def test_relative_to_the_working_directory(elsewhere):
    (elsewhere / 'mine.world').write_text('<sdf/>')
    assert resolve_world('mine.world') == str(elsewhere / 'mine.world')


def test_missing_world_is_returned_unchanged_for_the_loader_to_report(elsewhere):
    assert resolve_world('worlds/no_such.world') == 'worlds/no_such.world'


def test_the_world_servers_own_ros_time_is_set_and_wakes_who_waits_for_it():
    # the world server drives its own ROS time where it publishes /clock (it does not subscribe to itself); a
    # thread waiting for time to pass (rospy.sleep, rospy.Timer wait on rospy's time condition) must be woken
    import threading

    import rospy.rostime
    from racebot_sim_bridge.world_server import set_own_ros_time
    cond = rospy.rostime.get_rostime_cond()
    saved = rospy.rostime._rostime_current
    woke = threading.Event()

    def waiter():
        with cond:
            cond.wait()  # no timeout: only a notify ends it
        woke.set()
    thread = threading.Thread(target=waiter, daemon=True)
    try:
        thread.start()
        deadline = time.monotonic() + 10.0
        while not cond._waiters and time.monotonic() < deadline:
            time.sleep(0.001)
        set_own_ros_time(rospy.Time(12, 345))
        assert woke.wait(10.0)
        assert rospy.rostime._rostime_current == rospy.Time(12, 345)
        set_own_ros_time(genpy.Time(13, 0))  # a genpy Time (a message's field) is kept as a rospy.Time
        assert type(rospy.rostime._rostime_current) is rospy.Time
        assert rospy.rostime._rostime_current == rospy.Time(13, 0)
    finally:
        rospy.rostime._rostime_current = saved
        with cond:
            cond.notify_all()
        thread.join(5.0)
