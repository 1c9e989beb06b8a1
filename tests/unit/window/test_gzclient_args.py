"""gzclient's and gazebo's command lines (gzclient.parse_args, gazebo_command.split_args): gzclient's
options accepted, the `gazebo` command's arguments split between the world server and its window."""
import pytest

from racebot_sim_bridge.window.gazebo_command import split_args
from racebot_sim_bridge.window.gzclient import UsageError, address_param, parse_args


def test_gzclient_options():
    opts = parse_args(['--verbose', '-g', '/opt/libgazebo_ros_paths_plugin.so', '--gui-plugin=libx.so', '--foo'])
    assert opts['verbose'] and opts['plugins'] == ['/opt/libgazebo_ros_paths_plugin.so', 'libx.so']
    assert opts['ignored'] == ['--foo'] and not opts['help'] and not opts['version']
    assert parse_args(['-h'])['help'] and parse_args(['--version'])['version']
    assert parse_args(['', ' '])['ignored'] == []  # empty args from empty_world.launch's command_arg3


def test_a_plugin_option_without_its_plugin_is_a_usage_error():
    for argv in (['-g'], ['-g', '--verbose']):
        with pytest.raises(UsageError, match='needs a plugin'):
            parse_args(argv)


def test_the_server_address_parameter_is_in_its_namespace():
    assert address_param('/gazebo') == '/gazebo/gzclient_address'
    assert address_param('/robot1/gazebo/') == '/robot1/gazebo/gzclient_address'


def test_gazebo_gives_the_server_its_command_line_and_the_window_its_own():
    server, client = split_args(['-u', '--verbose', '-e', 'ode', '-g', 'libgui.so', 'worlds/empty.world',
                                 '__ns:=/robot1', '__log:=/tmp/x.log', 'foo:=bar'])
    assert server == ['-u', '--verbose', '-e', 'ode', 'worlds/empty.world', '__ns:=/robot1', '__log:=/tmp/x.log',
                      'foo:=bar']
    assert client == ['__name:=gazebo_gui', '--verbose', '-g', 'libgui.so', '__ns:=/robot1']


def test_gazebo_points_the_window_at_a_renamed_server():
    server, client = split_args(['__name:=sim', 'w.world'])
    assert server == ['__name:=sim', 'w.world']
    assert client == ['__name:=gazebo_gui', '_gazebo_namespace:=sim']
