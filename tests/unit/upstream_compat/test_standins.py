"""upstream_compat's name stand-ins (issue 29, point 4) keep to their one pattern and say what they are.

A name stand-in is a folder whose CMakeLists.txt includes cmake/name_standin.cmake after step_aside.cmake. Each
must be a catkin package of that name whose package.xml says it is racebot's stand-in, be listed in
upstream_compat/README.md, and export only plugin description files it has. The controller classes their plugin
XML files declare are exactly the controller types racebot_sim_bridge simulates, each declared once: a type
added to racebot_sim_bridge/ros_controllers must be declared where upstream declares it, and no file may declare
a controller racebot does not have. Needs the workspace built and sourced (control_msgs) but no master.
"""
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

UPSTREAM_COMPAT = Path(__file__).resolve().parents[3] / 'upstream_compat'
# as the issue and the popular Gazebo robot packages name them
EXPECTED = {'joint_state_controller', 'effort_controllers', 'position_controllers', 'velocity_controllers',
            'forward_command_controller', 'diff_drive_controller', 'ackermann_steering_controller',
            'joint_trajectory_controller', 'gripper_action_controller', 'controller_interface', 'hardware_interface',
            'transmission_interface', 'joint_limits_interface', 'control_toolbox', 'realtime_tools',
            'gazebo_plugins', 'gazebo_ros_control', 'gazebo_dev'}
PATTERN = re.compile(r'cmake_minimum_required\(VERSION 3\.0\.2\)\n'
                     r'project\((\w+)\)\n'
                     r'include\(\$\{CMAKE_CURRENT_SOURCE_DIR\}/\.\./cmake/step_aside\.cmake\)\n'
                     r'if\(NOT RACEBOT_STEP_ASIDE\)\n'
                     # settings, and a stand-in's own build step in its cmake/ folder (control_toolbox's
                     # dynamic_reconfigure config)
                     r'(?:  (?:#.*|set\(RACEBOT_STANDIN_\w+ [\w .-]+\)'
                     r'|include\(\$\{CMAKE_CURRENT_SOURCE_DIR\}/cmake/\w+\.cmake\))\n)*'
                     r'  include\(\$\{CMAKE_CURRENT_SOURCE_DIR\}/\.\./cmake/name_standin\.cmake\)\n')


def standins():
    return sorted(p.parent for p in UPSTREAM_COMPAT.glob('*/CMakeLists.txt')
                  if '/../cmake/name_standin.cmake)' in p.read_text())


def test_every_expected_standin_is_there():
    assert {p.name for p in standins()} == EXPECTED


@pytest.mark.parametrize('folder', standins(), ids=lambda p: p.name)
def test_standin_keeps_to_the_pattern(folder):
    cmake = (folder / 'CMakeLists.txt').read_text()
    match = PATTERN.match(cmake)
    assert match, 'CMakeLists.txt of %s is not the name stand-in pattern (cmake/name_standin.cmake)' % folder.name
    assert match.group(1) == folder.name
    package = ET.parse(folder / 'package.xml').getroot()
    assert package.findtext('name') == folder.name
    description = ' '.join(package.findtext('description').split())
    assert description.startswith("racebot's stand-in for %s " % folder.name), description
    assert 'Steps aside when the real package is installed' in description
    # everything name_standin.cmake installs (the top's *.xml, *.yaml, *.launch) is a file the description names
    for installed in folder.glob('*'):
        if installed.suffix in ('.xml', '.yaml', '.launch') and installed.name != 'package.xml':
            assert installed.name in description, '%s does not say it has %s' % (folder.name, installed.name)
    for export in package.iter('export'):
        for child in export:
            plugin = child.get('plugin')
            if plugin:
                assert plugin.startswith('${prefix}/') and (folder / plugin[len('${prefix}/'):]).is_file(), plugin
                depends = {d.text for d in package if d.tag.endswith('depend')}
                assert child.tag == folder.name or child.tag in depends, \
                    'rospack plugins lists %s only if it depends on %s' % (folder.name, child.tag)


def test_readme_lists_every_standin():
    readme = (UPSTREAM_COMPAT / 'README.md').read_text()
    for folder in standins():
        assert '`%s`' % folder.name in readme


def declared_controllers():
    """{class name: [plugin XML declaring it]} over every stand-in exporting controller_interface plugins."""
    declared = {}
    for folder in standins():
        for export in ET.parse(folder / 'package.xml').getroot().iter('export'):
            for child in export.findall('controller_interface'):
                path = folder / child.get('plugin')[len('${prefix}/'):]
                for cls in ET.parse(path).getroot().iter('class'):
                    declared.setdefault(cls.get('name'), []).append('%s/%s' % (folder.name, path.name))
    return declared


# controllers racebot simulates that a robot package declares in its own plugin XML (not a stand-in's)
ROBOT_PACKAGE_CONTROLLERS = {'mecanum_drive_controller/MecanumDriveController'}  # ridgeback_control


def test_plugin_xml_declares_exactly_the_simulated_controllers():
    from racebot_sim_bridge.ros_controllers import CONTROLLER_TYPES
    declared = declared_controllers()
    assert {name: files for name, files in declared.items() if len(files) > 1} == {}
    assert sorted(declared) == sorted(set(CONTROLLER_TYPES) - ROBOT_PACKAGE_CONTROLLERS)


def test_joint_state_controller_has_upstreams_yaml():
    import yaml
    folder = UPSTREAM_COMPAT / 'joint_state_controller'
    assert yaml.safe_load((folder / 'joint_state_controller.yaml').read_text()) == {
        'joint_state_controller': {'type': 'joint_state_controller/JointStateController', 'publish_rate': 50}}
    launch = ET.parse(folder / 'joint_state_controller.launch').getroot()
    assert launch.find('rosparam').get('file') == '$(find joint_state_controller)/joint_state_controller.yaml'
    node = launch.find('node')
    assert (node.get('pkg'), node.get('type'), node.get('args')) == ('controller_manager', 'spawner',
                                                                     'joint_state_controller')
