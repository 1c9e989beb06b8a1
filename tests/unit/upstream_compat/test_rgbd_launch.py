"""upstream_compat/rgbd_launch (reduced): includes/manager.launch.xml, as fetch_gazebo's head_camera.launch.xml
includes it, gives the nodelet manager upstream's file gives, read by roslaunch's own loader. No ROS master."""
from pathlib import Path

import pytest
import roslaunch.config
import roslaunch.xmlloader

MANAGER = Path(__file__).resolve().parents[3] / 'upstream_compat' / 'rgbd_launch' / 'launch' / 'includes' / \
    'manager.launch.xml'


def load(*args):
    config = roslaunch.config.ROSLaunchConfig()
    loader = roslaunch.xmlloader.XmlLoader()
    loader.ignore_unset_args = False  # what roslaunch itself sets: an arg without value is an error
    loader.load(str(MANAGER), config, argv=list(args), verbose=False)
    return config


def test_fetch_gazebos_include():
    config = load('name:=head_camera_nodelet_manager', 'debug:=false', 'num_worker_threads:=2')
    [node] = config.nodes
    assert (node.package, node.type, node.name, node.args) == ('nodelet', 'nodelet', 'head_camera_nodelet_manager',
                                                              'manager')
    assert (node.launch_prefix or '', node.respawn, node.output) == ('', False, 'screen')
    assert config.params['/head_camera_nodelet_manager/num_worker_threads'].value == 2
    assert '/bond_disable_heartbeat_timeout' not in config.params


def test_debug_and_respawn():
    config = load('name:=m', 'num_worker_threads:=4', 'debug:=true', 'respawn:=true')
    [node] = config.nodes
    assert node.launch_prefix == 'xterm -e gdb --args' and node.respawn
    assert config.params['/bond_disable_heartbeat_timeout'].value is True


def test_worker_threads_are_required_as_upstream():
    with pytest.raises(roslaunch.xmlloader.XmlParseException):
        load('name:=m')
