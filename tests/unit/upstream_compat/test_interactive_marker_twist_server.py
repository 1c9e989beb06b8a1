"""upstream_compat/interactive_marker_twist_server: its parameters, controls and Twist as upstream 1.2.2's
marker_server (scaled, clamped per axis; an axis the max maps lack clamps to 0; yaw as tf::getYaw), its config
files read as upstream's launch file loads them. No ROS master."""
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

from interactive_marker_twist_server.twist import controls, settings_from_params, twist, yaw

PACKAGE = Path(__file__).resolve().parents[3] / 'upstream_compat' / 'interactive_marker_twist_server'
IDENTITY = (1.0, 0.0, 0.0, 0.0)


def params(values):
    return lambda name, default: values.get(name, default)


def config(name):
    return settings_from_params(params(yaml.safe_load((PACKAGE / 'config' / ('%s.yaml' % name)).read_text())))


def yaw_quaternion(angle):
    return (math.cos(angle / 2), 0.0, 0.0, math.sin(angle / 2))


def test_defaults_are_upstreams():
    s = settings_from_params(params({}))
    assert (s.link_name, s.robot_name, s.marker_name, s.description) == (
        'base_link', 'robot', 'robot_twist_marker', 'twist controller for robot')
    assert (s.linear_scale, s.max_positive, s.max_negative) == ({'x': 1.0}, {'x': 1.0}, {'x': -1.0})
    assert (s.angular_scale, s.max_angular_velocity, s.marker_size_scale) == (2.2, 2.2, 1.0)
    assert [c[0] for c in controls(s)] == ['move_x', 'rotate_z']


@pytest.mark.parametrize('name, axes', [('linear', ['move_x']), ('planar', ['move_x', 'move_y']),
                                        ('aerial', ['move_x', 'move_y', 'move_z'])])
def test_configs_give_upstreams_controls(name, axes):
    assert [c[0] for c in controls(config(name))] == axes + ['rotate_z']


def test_planar_drags_sideways_and_clamps():
    s = config('planar')  # ridgeback_control's teleop.launch loads it
    assert twist(s, (0.0, 0.4, 0.0), IDENTITY) == ((0.0, 0.4, 0.0), 0.0)
    assert twist(s, (3.0, -5.0, 7.0), IDENTITY) == ((1.0, -1.0, 0.0), 0.0)  # z: no axis, 0


def test_scalar_linear_scale_drives_x_only():
    s = settings_from_params(params({'linear_scale': 2.0, 'max_positive_linear_velocity': 1.5,
                                     'max_negative_linear_velocity': -0.5}))
    assert twist(s, (0.5, 1.0, 1.0), IDENTITY) == ((1.0, 0.0, 0.0), 0.0)
    assert twist(s, (1.0, 0.0, 0.0), IDENTITY)[0][0] == 1.5
    assert twist(s, (-1.0, 0.0, 0.0), IDENTITY)[0][0] == -0.5


def test_axis_missing_from_the_max_maps_clamps_to_zero():
    s = settings_from_params(params({'linear_scale': {'x': 1, 'y': 1}, 'max_positive_linear_velocity': {'x': 1},
                                     'max_negative_linear_velocity': {'x': -1}}))
    assert twist(s, (0.5, 0.5, 0.0), IDENTITY)[0] == (0.5, 0.0, 0.0)


def test_yaw_scaled_and_clamped():
    s = config('linear')
    assert twist(s, (0, 0, 0), yaw_quaternion(0.5))[1] == pytest.approx(1.1)  # 2.2 x 0.5
    assert twist(s, (0, 0, 0), yaw_quaternion(-2.0))[1] == pytest.approx(-2.2)  # clamped
    assert yaw(*yaw_quaternion(3.0)) == pytest.approx(3.0)
    assert yaw(0.0, 0.0, 0.0, 0.0) == 0.0  # an unset Pose's orientation


def test_launch_file_loads_a_config_it_has():
    node = ET.parse(PACKAGE / 'launch' / 'interactive_markers.launch').getroot().find('node')
    assert (node.get('pkg'), node.get('type'), node.get('name')) == (
        'interactive_marker_twist_server', 'marker_server', 'twist_marker_server')
    assert node.find('rosparam').get('file').endswith('/config/$(arg config).yaml')
    assert (PACKAGE / 'scripts' / 'marker_server').stat().st_mode & 0o111
