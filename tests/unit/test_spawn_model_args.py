"""spawn_model.parse_args against gazebo_ros's spawn_model command line (noetic-devel
gazebo_ros/scripts/spawn_model): -urdf|-sdf, one of -file/-param/-database/-stdin, -model (required),
-reference_frame, -gazebo_namespace, -robot_namespace, -unpause, -wait, -x -y -z -R -P -Y,
-J JOINT POSITION (repeatable), -package_to_model, -b. No ROS master.
"""
import pytest

from racebot_sim_bridge.spawn_model import USAGE, UsageError, parse_args

BASE = ['-urdf', '-param', 'robot_description', '-model', 'racebot']


def test_the_tutorials_command_line():
    opts = parse_args(['-urdf', '-model', 'racebot', '-param', 'robot_description'])
    assert opts['kind'] == 'urdf'
    assert (opts['source'], opts['value']) == ('param', 'robot_description')
    assert opts['model'] == 'racebot'


def test_defaults():
    opts = parse_args(BASE)
    assert opts['pose'] == dict(x=0.0, y=0.0, z=0.0, R=0.0, P=0.0, Y=0.0)
    assert opts['gazebo_namespace'] == '/gazebo'
    assert opts['reference_frame'] == ''
    assert opts['joints'] == []
    assert opts['unpause'] is False
    assert opts['wait'] is None


def test_every_option():
    opts = parse_args(['-sdf', '-file', '/tmp/m.sdf', '-model', 'box', '-robot_namespace', '/rb',
                       '-reference_frame', 'world', '-gazebo_namespace', '/sim', '-x', '1', '-y', '-2.5',
                       '-z', '0.1', '-R', '0.1', '-P', '-0.2', '-Y', '3.14', '-J', 'a_joint', '0.5',
                       '-J', 'b_joint', '-1', '-unpause', '-wait', 'other'])
    assert opts['kind'] == 'sdf'
    assert (opts['source'], opts['value']) == ('file', '/tmp/m.sdf')
    assert opts['model'] == 'box'
    assert opts['robot_namespace'] == '/rb'
    assert opts['reference_frame'] == 'world'
    assert opts['gazebo_namespace'] == '/sim'
    assert opts['pose'] == dict(x=1.0, y=-2.5, z=0.1, R=0.1, P=-0.2, Y=3.14)
    assert opts['joints'] == [('a_joint', 0.5), ('b_joint', -1.0)]
    assert opts['unpause'] is True
    assert opts['wait'] == 'other'


def test_options_in_any_order():
    a = parse_args(['-model', 'racebot', '-x', '2', '-param', 'robot_description', '-urdf'])
    assert (a['kind'], a['source'], a['model'], a['pose']['x']) == ('urdf', 'param', 'racebot', 2.0)


def test_stdin_source():
    opts = parse_args(['-urdf', '-stdin', '-model', 'm'])
    assert opts['source'] == 'stdin'


def test_timeout_extension():
    assert parse_args(BASE + ['-timeout', '5'])['timeout'] == 5.0


@pytest.mark.parametrize('flag', ['-package_to_model', '-b'])
def test_gazebo_ros_flags_without_value_are_accepted(flag):
    # gazebo_ros's spawn_model has both (store_true); a launch file written for Gazebo may pass them.
    opts = parse_args(BASE + [flag])
    assert opts['model'] == 'racebot'


# -- errors ---------------------------------------------------------------------------------------

def _error(argv):
    with pytest.raises(UsageError) as err:
        parse_args(argv)
    return str(err.value)


def test_model_is_required():
    assert '-model' in _error(['-urdf', '-param', 'robot_description'])


def test_model_needs_a_value():
    assert '-model' in _error(['-urdf', '-param', 'robot_description', '-model'])


def test_a_source_is_required():
    msg = _error(['-urdf', '-model', 'racebot'])
    assert '-file' in msg and '-param' in msg


def test_a_kind_is_required():
    msg = _error(['-param', 'robot_description', '-model', 'racebot'])
    assert '-urdf' in msg and '-sdf' in msg


def test_database_is_refused_with_a_reason():
    msg = _error(['-sdf', '-database', 'coke_can', '-model', 'can'])
    assert 'database' in msg and ('-file' in msg or '-param' in msg)


@pytest.mark.parametrize('flag', ['-gazebo', '-trimesh'])
def test_old_formats_refused(flag):
    assert flag in _error([flag, '-file', 'x', '-model', 'm'])


@pytest.mark.parametrize('argv, flag', [
    (BASE + ['-x', 'abc'], '-x'),
    (BASE + ['-Y', ''], '-Y'),
    (BASE + ['-z', 'nan'], '-z'),
    (BASE + ['-R', 'inf'], '-R'),
    (BASE + ['-J', 'a_joint', 'up'], '-J'),
    (BASE + ['-timeout', 'soon'], '-timeout'),
])
def test_bad_numbers(argv, flag):
    assert flag in _error(argv)


@pytest.mark.parametrize('argv', [BASE + ['-x'], BASE + ['-J', 'a_joint'], BASE + ['-J'], ['-urdf', '-file']])
def test_missing_values(argv):
    _error(argv)


@pytest.mark.parametrize('option', ['--model', '-foo', '-X', 'stray_word'])
def test_unknown_option(option):
    assert option in _error(BASE + [option])


@pytest.mark.parametrize('argv', [
    ['-urdf', '-sdf', '-param', 'robot_description', '-model', 'm'],
    ['-urdf', '-param', 'robot_description', '-file', '/tmp/m.urdf', '-model', 'm'],
    ['-urdf', '-param', 'robot_description', '-stdin', '-model', 'm'],
])
def test_mutually_exclusive_options(argv):
    # gazebo_ros puts -urdf/-sdf and -file/-param/-database/-stdin in argparse exclusive groups.
    _error(argv)


def test_help_is_a_usage_error_without_message():
    assert _error(['-h']) == ''
    assert '-model NAME' in USAGE
