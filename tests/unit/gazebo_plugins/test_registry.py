"""gazebo_plugins/registry.py: the one registry of plugin libraries. A library's class is in the module named after
it, a filename becomes a library name in one place only, and a library racebot does not simulate is warned about
once, wherever it sits (a model's <plugin>, a <sensor>'s), on a real Simulator with both plugin managers."""
import re
import subprocess
from pathlib import Path

import pytest

from racebot_sim_bridge.description import plugin_library, sdf_reader
from racebot_sim_bridge.description.plugin_library import library_key
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_laser import LaserSensor
from racebot_sim_bridge.gazebo_plugins.plugin_manager import PluginManager
from racebot_sim_bridge.gazebo_plugins.registry import REGISTRY, Registry
from racebot_sim_bridge.gazebo_ros_api.plugin_kind import PluginKind
from racebot_sim_bridge.gazebo_plugins.sensor_manager import SensorManager

from fakes import FakeLog, FakeRospy, NullIO

REPO = Path(__file__).resolve().parents[3]
ROBOT = REPO / 'tests' / 'fixtures' / 'sensor_plugins' / 'robot.urdf'
WORLD = '<sdf version="1.6"><world name="default"></world></sdf>'


@pytest.mark.parametrize('filename', ['libgazebo_ros_diff_drive.so', '/opt/lib/libgazebo_ros_diff_drive.so',
                                      'gazebo_ros_diff_drive', 'libgazebo_ros_diff_drive'])
def test_library_key(filename):
    assert library_key(filename) == 'gazebo_ros_diff_drive'


def registered():
    """(class, its library keys) of every registered class, once each."""
    classes = {}
    for key, cls in REGISTRY.classes.items():
        classes.setdefault(cls, []).append(key)
    return classes.items()


def test_every_library_is_answered_in_the_module_named_after_it():
    for cls, keys in registered():
        module = cls.__module__
        *package, stem = module.split('.')
        assert stem in keys or package[-1] in keys, (
            '%s answers %s but lives in %s: name the module after its library' % (cls.__name__, keys, module))
        assert isinstance(cls.plugin_kind, PluginKind)


def test_lookups_by_filename_and_kind():
    assert REGISTRY.find('libgazebo_ros_laser.so') is LaserSensor
    assert REGISTRY.find('/opt/lib/libgazebo_ros_gpu_laser.so', PluginKind.SENSOR) is LaserSensor
    assert REGISTRY.find('libgazebo_ros_laser.so', PluginKind.MODEL) is None  # a sensor plugin, not a model's
    assert REGISTRY.find('libgazebo_ros_openni_kinect.so') is REGISTRY.find('libgazebo_ros_depth_camera.so')
    assert REGISTRY.find('libgazebo_ros_control.so').plugin_kind is PluginKind.ROBOT_HARDWARE
    assert REGISTRY.find('liblab_lidar_plugin.so') is None
    with pytest.raises(ValueError, match='both answer libgazebo_ros_laser.so'):
        Registry([LaserSensor, type('Other', (LaserSensor,), {})])


# Taking `lib` and `.so` off a filename: only library_key may.
STRIPPING = re.compile(r"""endswith\(\s*['"]\.so|startswith\(\s*['"]lib|remove(prefix|suffix)\(\s*['"](lib|\.so)|"""
                       r"""len\(\s*['"](lib|\.so)|\[\s*:\s*-3\s*\]""")


def python_sources():
    """The Python files under version control, tests aside: modules, scripts and tools."""
    files = subprocess.run(['git', 'ls-files'], cwd=str(REPO), capture_output=True, text=True, check=True).stdout
    for name in files.split():
        path = REPO / name
        if name.startswith('tests/') or not path.is_file():
            continue
        if name.endswith('.py'):
            yield path
            continue
        head = path.read_bytes()[:64]
        if head.startswith(b'#!') and b'python' in head:
            yield path


def test_one_function_turns_a_filename_into_a_library_name():
    own = Path(plugin_library.__file__).resolve()
    sources = list(python_sources())
    assert own in sources and len(sources) > 50
    assert STRIPPING.search(own.read_text())  # the pattern finds library_key's own stripping
    elsewhere = ['%s:%d: %s' % (path.relative_to(REPO), number, line.strip())
                 for path in sources if path != own
                 for number, line in enumerate(path.read_text(errors='replace').splitlines(), 1)
                 if STRIPPING.search(line)]
    assert not elsewhere, ('a filename made a library name outside description/plugin_library.library_key:\n'
                           + '\n'.join(elsewhere))


def spawn(tmp_path, urdf):
    path = tmp_path / 'empty.world'
    path.write_text(WORLD)
    sim = Simulator(sdf_reader.load_world(str(path)), NullIO(), FakeLog(), lambda path: None)
    fake = FakeRospy({'~sensors/report_period': 0, '~sensors/render_worker': False})
    PluginManager(fake, sim)
    SensorManager(fake, sim)
    sim.spawn_urdf('sensor_robot', urdf, '/', (0.0, 0.0, 0.0))
    return sim, [message for level, message in fake.logs if level == 'warn']


def test_a_library_not_simulated_is_warned_about_once_wherever_it_sits(tmp_path):
    model_level = ('<gazebo><plugin name="gripper" filename="libacme_vacuum_gripper.so"/>'
                   '<plugin name="laser_here" filename="libgazebo_ros_laser.so"/>'
                   '<plugin name="control" filename="libgazebo_ros_control.so"/></gazebo>')
    in_a_sensor = '<plugin name="odometry" filename="libgazebo_ros_p3d.so"/></sensor>'
    urdf = ROBOT.read_text().replace('</robot>', model_level + '</robot>')
    urdf = urdf.replace('</plugin>\n    </sensor>', '</plugin>\n    ' + in_a_sensor, 1)  # the sonar's
    sim, warnings = spawn(tmp_path, urdf)
    try:
        for library, where in (('libacme_vacuum_gripper.so', "plugin 'gripper'"),
                               ('libgazebo_ros_laser.so', "plugin 'laser_here'"),  # a sensor plugin, in no sensor
                               ('libgazebo_ros_p3d.so', "sensor 'sonar' (type ray): plugin 'odometry'"),
                               ('liblab_lidar_plugin.so', "sensor 'lab_lidar' (type ray)")):
            said = [w for w in warnings if library in w]
            assert len(said) == 1, (library, warnings)
            assert where in said[0] and 'is not simulated by racebot' in said[0]
            assert "see the table 'Supported plugins, sensors and controllers'" in said[0]
        assert not [w for w in warnings if 'gazebo_ros_control' in w]  # the simulator's
    finally:
        sim.close()
