"""racebot's stand-in for Gazebo's CMake config, and the C++ check of the name stand-ins' catkin configs.

upstream_compat/gazebo_dev writes devel/lib/cmake/gazebo/gazebo-config.cmake (no Gazebo is installed here).
Plain CMake projects, configured with the devel space on CMAKE_PREFIX_PATH as a sourced workspace has it, show
what a package gets: Gazebo 11's variables, handing on racebot's Gazebo plugin API (its headers, libgazebo, Debian's
ignition-math6 and sdformat); for code that includes a Gazebo header the API does not have, an error with REQUIRED
and gazebo_FOUND false without it, the message naming the package, the file and the catkin_make line that leaves it
out; and a compile error with the same advice for an include the scan cannot see. The catkin config
of a name stand-in refuses code including its headers the same way. Needs `make build`, cmake and g++; no
master. The projects declare no language (no compiler check), so each configure takes a fraction of a second; those
of the stand-ins with a C++ API enable C++, as their configs need (about half a second more).
"""
import shutil
import subprocess
import textwrap
from pathlib import Path

import pytest

DEVEL = Path(__file__).resolve().parents[3] / 'devel'
GAZEBO_CONFIG = DEVEL / 'lib' / 'cmake' / 'gazebo' / 'gazebo-config.cmake'
REPORT = textwrap.dedent('''
    foreach(v gazebo_FOUND GAZEBO_VERSION GAZEBO_MAJOR_VERSION GAZEBO_INCLUDE_DIRS GAZEBO_LIBRARIES
              GAZEBO_LIBRARY_DIRS GAZEBO_CXX_FLAGS)
      message(STATUS "probe ${v}=${${v}}")
    endforeach()
''')


def project(tmp_path, cmake, sources=None, name='probe_pkg'):
    """(exit code, output, {variable: value} of the probe lines) of configuring a package `name`."""
    if not GAZEBO_CONFIG.is_file():
        pytest.fail('%s is missing: run `make build`' % GAZEBO_CONFIG)
    src = tmp_path / name
    (src / 'src').mkdir(parents=True)
    (src / 'package.xml').write_text('<package format="2"><name>%s</name></package>\n' % name)
    (src / 'CMakeLists.txt').write_text('cmake_minimum_required(VERSION 3.0.2)\nproject(%s NONE)\n%s' % (name, cmake))
    for relative, text in (sources or {}).items():
        (src / relative).write_text(text)
    done = subprocess.run(['cmake', '-S', str(src), '-B', str(tmp_path / 'build'), '-DCMAKE_PREFIX_PATH=%s' % DEVEL],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
    values = dict(line.split('probe ', 1)[1].split('=', 1) for line in done.stdout.splitlines() if 'probe ' in line)
    return done.returncode, done.stdout, values


# a model plugin's includes, all in racebot's Gazebo plugin API
PLUGIN = {'src/plugin.cc': ('#include <ros/ros.h>\n  #  include "gazebo/physics/physics.hh"\n'
                            '#include <gazebo/physics/PhysicsEngine.hh>\n#include <gazebo/gazebo.hh>\n')}
# a ray sensor plugin's, all in it
RAY_PLUGIN = {'src/plugin.cc': ('#include <gazebo/plugins/RayPlugin.hh>\n#include <gazebo/sensors/RaySensor.hh>\n'
                                '#include <gazebo/transport/Node.hh>\n#include <gazebo/msgs/MessageTypes.hh>\n')}
# a depth camera plugin's: gazebo/sensors/DepthCameraSensor.hh is not in it
SENSOR_PLUGIN = {'src/plugin.cc': '#include <gazebo/gazebo.hh>\n  #  include "gazebo/sensors/DepthCameraSensor.hh"\n'}


def flat(text):
    return ' '.join(text.split())  # CMake wraps a message's lines


def test_plain_code_gets_gazebo_11s_variables(tmp_path):
    code, out, values = project(tmp_path, 'find_package(gazebo 9 REQUIRED)\n' + REPORT,
                                {'src/node.cpp': '#include <ros/ros.h>\n#include <geometry_msgs/Twist.h>\n'})
    assert code == 0, out
    assert values['gazebo_FOUND'] in ('1', 'TRUE'), out
    assert values['GAZEBO_VERSION'].startswith('11.') and values['GAZEBO_MAJOR_VERSION'] == '11'
    assert values['GAZEBO_CXX_FLAGS'] == '-std=c++17'
    libraries = values['GAZEBO_LIBRARIES'].split(';')
    assert libraries[0] == str(DEVEL / 'lib' / 'libgazebo.so') and Path(libraries[0]).is_file(), libraries
    assert 'ignition-math6::ignition-math6' in libraries and 'sdformat12::sdformat12' in libraries
    assert values['GAZEBO_LIBRARY_DIRS'] == str(DEVEL / 'lib')
    includes = values['GAZEBO_INCLUDE_DIRS'].split(';')
    assert Path(includes[0], 'gazebo', 'gazebo.hh').is_file() and Path(includes[0], 'gazebo', 'physics').is_dir()
    assert any(Path(folder, 'sdf', 'sdf.hh').is_file() for folder in includes), includes
    assert any(Path(folder, 'ignition', 'math', 'Pose3.hh').is_file() for folder in includes), includes


def test_a_model_plugin_gets_racebots_gazebo_plugin_api(tmp_path):
    code, out, values = project(tmp_path, 'find_package(gazebo REQUIRED)\n' + REPORT, PLUGIN, name='my_plugins')
    assert code == 0, out
    assert values['gazebo_FOUND'] in ('1', 'TRUE'), out


def test_a_ray_sensor_plugin_gets_racebots_gazebo_plugin_api(tmp_path):
    code, out, values = project(tmp_path, 'find_package(gazebo REQUIRED)\n' + REPORT, RAY_PLUGIN, name='my_lidar')
    assert code == 0, out
    assert values['gazebo_FOUND'] in ('1', 'TRUE'), out
    assert (DEVEL / 'lib' / 'libRayPlugin.so').is_file() and (DEVEL / 'lib' / 'libGpuRayPlugin.so').is_file()


def test_a_newer_gazebo_than_11_is_not_found(tmp_path):
    code, out, values = project(tmp_path, 'find_package(gazebo 12 QUIET)\n' + REPORT)
    assert code == 0 and values['gazebo_FOUND'] in ('0', 'FALSE'), out


def test_a_plugin_including_a_header_the_api_lacks_is_refused_naming_the_package(tmp_path):
    code, out, _ = project(tmp_path, 'find_package(gazebo REQUIRED)\n', SENSOR_PLUGIN, name='my_gazebo_plugins')
    assert code != 0, out
    out = flat(out)
    assert ("racebot: package 'my_gazebo_plugins' includes a Gazebo header that racebot's Gazebo plugin API does "
            'not have (src/plugin.cc: # include "gazebo/sensors/DepthCameraSensor.hh")') in out
    assert 'docs/SUPPORTED.md' in out
    assert 'catkin_make -DCATKIN_BLACKLIST_PACKAGES="my_gazebo_plugins"' in out


# hector_gazebo_plugins' sensor_model.h: Gazebo 7's header behind a version test Gazebo 11 does not take
GUARDED = {'src/plugin.cc': ('#include <gazebo/gazebo.hh>\n#if (GAZEBO_MAJOR_VERSION < 8)\n'
                             '#include <gazebo/math/Vector3.hh>\n#else\n#include <ignition/math/Vector3.hh>\n#endif\n'
                             '#if GAZEBO_MAJOR_VERSION >= 9 // new\n#include <gazebo/physics/physics.hh>\n#else\n'
                             '#include <gazebo/physics/PhysicsEngine7.hh>\n#endif\n')}


def test_an_include_in_a_branch_gazebo_11_does_not_take_is_not_refused(tmp_path):
    code, out, values = project(tmp_path, 'find_package(gazebo REQUIRED)\n' + REPORT, GUARDED)
    assert code == 0 and values['gazebo_FOUND'] in ('1', 'TRUE'), out


def test_an_include_under_a_condition_it_cannot_evaluate_is_refused(tmp_path):
    sources = {'src/plugin.cc': '#ifdef WITH_CAMERA\n#include <gazebo/sensors/DepthCameraSensor.hh>\n#endif\n'}
    code, out, _ = project(tmp_path, 'find_package(gazebo REQUIRED)\n', sources)
    assert code != 0 and 'gazebo/sensors/DepthCameraSensor.hh' in flat(out), out


def test_without_required_a_plugin_package_gets_gazebo_not_found(tmp_path):
    """As `find_package(gazebo QUIET) if(gazebo_FOUND) <plugin> endif()` packages expect without Gazebo."""
    code, out, values = project(tmp_path, 'find_package(gazebo)\n' + REPORT, SENSOR_PLUGIN)
    assert code == 0, out
    assert values['gazebo_FOUND'] in ('0', 'FALSE'), out
    assert 'CATKIN_BLACKLIST_PACKAGES' in out  # not QUIET: the reason is shown


@pytest.mark.skipif(shutil.which('g++') is None, reason='no C++ compiler')
def test_an_include_the_scan_misses_fails_the_compile_with_the_advice(tmp_path):
    code, out, values = project(tmp_path, 'find_package(gazebo REQUIRED)\n' + REPORT, name='elsewhere_pkg')
    assert code == 0, out
    outside = tmp_path / 'shared.cpp'  # outside the package's folder, as a source another package lends
    outside.write_text('#include <gazebo/rendering/rendering.hh>\nint main() { return 0; }\n')
    includes = [arg for folder in values['GAZEBO_INCLUDE_DIRS'].split(';') for arg in ('-I', folder)]
    done = subprocess.run(['g++', '-fsyntax-only'] + includes + [str(outside)],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=60)
    assert done.returncode != 0
    assert 'racebot: package elsewhere_pkg includes' in done.stdout, done.stdout
    assert 'catkin_make -DCATKIN_BLACKLIST_PACKAGES=elsewhere_pkg' in done.stdout


@pytest.mark.parametrize('standin, include, refused', [
    ('joint_trajectory_controller', '#include <trajectory_interface/quintic_spline_segment.h>', True),
    ('joint_trajectory_controller', '#include <joint_trajectory_controller/joint_trajectory_controller.h>', True),
    ('joint_trajectory_controller', '#include <control_msgs/FollowJointTrajectoryAction.h>', False),  # generated
    ('controller_manager', '#include <controller_manager/controller_manager.h>', True),  # not a name stand-in
    ('gazebo_plugins', '#include <gazebo_plugins/gazebo_ros_utils.h>', True),
])
def test_a_standins_catkin_config_refuses_code_including_its_headers(tmp_path, standin, include, refused):
    code, out, _ = project(tmp_path, 'find_package(%s REQUIRED)\n' % standin, {'src/arm_hw.cpp': include + '\n'},
                           name='my_arm_control')
    if not refused:
        assert code == 0, out
        return
    assert code != 0, out
    out = flat(out)
    assert "racebot: package 'my_arm_control' compiles C++ against %s" % standin in out
    assert 'src/arm_hw.cpp: %s' % include in out
    assert 'catkin_make -DCATKIN_BLACKLIST_PACKAGES="my_arm_control"' in out


def test_the_advice_keeps_what_is_left_out_already(tmp_path):
    code, out, _ = project(tmp_path, 'set(CATKIN_BLACKLIST_PACKAGES "other_pkg")\nfind_package(controller_manager)\n',
                           {'src/hw.cpp': '#include <controller_manager/controller_manager.h>\n'}, name='my_robot_hw')
    assert code != 0, out
    assert 'catkin_make -DCATKIN_BLACKLIST_PACKAGES="other_pkg;my_robot_hw"' in flat(out)


@pytest.mark.parametrize('standin, include, refused', [
    ('hardware_interface', '#include <hardware_interface/robot_hw.h>', False),
    ('hardware_interface', '#include <hardware_interface/joint_command_interface.h>', False),
    ('controller_interface', '#include <controller_interface/multi_interface_controller.h>', False),
    ('realtime_tools', '#include <realtime_tools/realtime_publisher.h>', False),
    ('realtime_tools', '#include <realtime_tools/realtime_clock.h>', True),
    ('hardware_interface', '#include <hardware_interface/posvelacc_command_interface.h>', True),
    ('hardware_interface', '#include <hardware_interface/imu_sensor_interface.h>', False),
    ('control_toolbox', '#include <control_toolbox/pid.h>', False),
    ('control_toolbox', '#include <control_toolbox/pid_gains_setter.h>', True),
    ('control_toolbox', '#include <control_toolbox/sine_sweep.h>', True),
    ('joint_limits_interface', '#include <joint_limits_interface/joint_limits_interface.h>', False),
    ('joint_limits_interface', '#include <joint_limits_interface/joint_limits_urdf.h>', False),
    ('joint_limits_interface', '#include <joint_limits_interface/joint_limits_rosparam.h>', False),
    ('joint_limits_interface', '#include <joint_limits_interface/joint_limits_interface_exception.h>', False),
    ('joint_limits_interface', '#include <joint_limits_interface/joint_limits_extra.h>', True),  # no such header
    ('gazebo_ros_control', '#include <gazebo_ros_control/robot_hw_sim.h>', False),
    ('gazebo_ros_control', '#include <gazebo_ros_control/default_robot_hw_sim.h>', True),
    ('transmission_interface', '#include <transmission_interface/transmission_info.h>', False),
    ('transmission_interface', '#include <transmission_interface/simple_transmission.h>', True),
])
def test_a_standin_with_cpp_api_refuses_only_headers_it_lacks(tmp_path, standin, include, refused):
    """ros_control's stand-ins carry the C++ API controllers build against (RACEBOT_STANDIN_CPP_API): their
    configs hand on the include folder and refuse a header of theirs that is not in it, naming it."""
    # C++ enabled, as in every catkin package: control_toolbox's config pulls in control_msgs' and so catkin's, which
    # looks for threads, and urdf's and dynamic_reconfigure's configs sit under /usr/lib/<arch>/cmake, which CMake
    # searches only once a compiler has told it the architecture.
    code, out, _ = project(tmp_path, 'enable_language(CXX)\nfind_package(%s REQUIRED)\n' % standin + REPORT,
                           {'src/my_controller.cpp': include + '\n'}, name='my_controllers')
    if not refused:
        assert code == 0, out
        return
    assert code != 0, out
    out = flat(out)
    assert ("racebot: package 'my_controllers' includes a header of %s that racebot's copy of its C++ API does not "
            "have (src/my_controller.cpp: %s)" % (standin, include)) in out
    assert 'catkin_make -DCATKIN_BLACKLIST_PACKAGES="my_controllers"' in out



@pytest.mark.parametrize('components, flags', [
    ('gazebo_ros_control hardware_interface', ''),  # upstream's gazebo_ros_control hands no gazebo_dev on
    ('gazebo_ros roscpp', ''),
    ('gazebo_dev roscpp', ' -std=c++17'),  # upstream's gazebo_dev-extras appends Gazebo's flags
])
def test_only_a_package_naming_gazebo_dev_gets_gazebos_flags_in_cmake_cxx_flags(tmp_path, components, flags):
    # AgileX hunter's steer_drive_controller: list(APPEND CMAKE_CXX_FLAGS "${CMAKE_CXX_FLAGS} ${GAZEBO_CXX_FLAGS}")
    # after naming gazebo_ros_control, which a non-empty CMAKE_CXX_FLAGS turns into "...;..." (a broken command)
    code, out, _ = project(tmp_path, 'enable_language(CXX)\nfind_package(catkin REQUIRED COMPONENTS %s)\n'
                                     'message(STATUS "probe flags=[${CMAKE_CXX_FLAGS}]")\n' % components)
    assert code == 0, out
    assert 'probe flags=[%s]' % flags in out, out
