"""Compiled Gazebo plugins (issue 39): model and world plugins built the way Gazebo's tutorials build them
(tests/fixtures/gazebo_plugin_project: a plain CMake project with find_package(gazebo)) against racebot's Gazebo 11
plugin API, loaded by their <plugin filename> into a real Simulator and driven by Gazebo's events: what they command
moves the physics, what they read is the engine's state, and a plugin that fails is reported and unloaded while the
world goes on."""
import math
import os
import re
import signal
import subprocess
import sys

import pytest

from racebot_sim_bridge.gazebo_plugins.compiled_plugins import find_library, plugin_xml
from racebot_sim_bridge.description import urdf_model
from racebot_sim_bridge.description.sdf_model import WorldPlugin

from model_plugin_sim import PluginWorld

HERE = os.path.dirname(os.path.abspath(__file__))
PROJECT = os.path.join(HERE, '..', '..', 'fixtures', 'gazebo_plugin_project')
ROTOR_IZZ = 0.002
ROTOR_MASS = 0.5

with open(os.path.join(PROJECT, 'spinner.urdf.in')) as _f:
    SPINNER = _f.read()


def spinner(extra):
    """The spinner with its test rotor and limits, and `extra` (its <gazebo> blocks) added."""
    return SPINNER % {'mass': ROTOR_MASS, 'izz': ROTOR_IZZ, 'effort': 3.0, 'velocity': 40.0, 'extra': extra}


def plugin_params(params):
    """A <plugin>'s body of {tag: text}."""
    return ''.join('<%s>%s</%s>' % (k, v, k) for k, v in params.items())


def robot(*plugins):
    return spinner('<gazebo>%s</gazebo>' % ''.join(plugins))


def driver(mode, target, report=0, joint='spin_joint', name='driver'):
    return ('<plugin name="%s" filename="libjoint_driver.so"><joint>%s</joint><mode>%s</mode><target>%s</target>'
            '<report>%d</report></plugin>' % (name, joint, mode, target, report))


def lines(out, prefix):
    return [line for line in out.splitlines() if prefix in line]


def joint_state(robot_):
    return robot_.body.joints['spin_joint'].state()


def test_a_velocity_plugin_drives_its_joint_and_sees_gazebos_times(world, capfd):
    # the base's CoG 0.03 above its origin, on the joint's axis (read back by Link::GetInertial below); its moments
    # 0.05, 0.06, 0.07
    urdf = robot(driver('velocity', 2.5, report=500)).replace(
        '<inertial><mass value="5"/><inertia ixx="0.05" iyy="0.05" izz="0.05"',
        '<inertial><origin xyz="0 0 0.03"/><mass value="5"/><inertia ixx="0.05" iyy="0.06" izz="0.07"', 1)
    assert 'xyz="0 0 0.03"' in urdf
    r = world.spawn('spinner', urdf, '/', (0.0, 0.0, 0.1))
    world.run(1.0)
    assert joint_state(r).velocity == pytest.approx(2.5, abs=1e-3)
    out = capfd.readouterr().out
    loaded = lines(out, 'JointDriver loaded')
    assert len(loaded) == 1, out
    # what Load read of the model: scoped joint name, URDF limits (continuous: none, effort 3), links, the world
    assert ('model spinner joint spinner::spin_joint mode velocity target 2.5 limits 0 -1 effort 3 child rotor '
            'parent base_link links 2 canonical base_link world default') in loaded[0], loaded[0]
    # Link::RelativePose: the rotor in the model's frame, the joint's origin 0.2 above the base (at rest, level)
    relative = [float(v) for v in loaded[0].split('child in model ')[1].split()]
    assert relative == pytest.approx([0.0, 0.0, 0.2, 0.0, 0.0, 0.0], abs=1e-6), loaded[0]
    # Link::GetInertial: the base's <inertial> as spawned above, its CoG in the link frame
    inertial = lines(out, 'JointDriver base inertial')
    assert len(inertial) == 1, out
    words = inertial[0].split('inertial: ')[1].split()
    assert float(words[1]) == pytest.approx(5.0)
    assert [float(v) for v in words[3:6]] == pytest.approx([0.0, 0.0, 0.03], abs=1e-9), inertial[0]
    assert [float(v) for v in words[7:10]] == pytest.approx([0.05, 0.06, 0.07], abs=1e-9), inertial[0]
    assert [float(v) for v in words[11:14]] == [0.0, 0.0, 0.0] and float(words[15]) == pytest.approx(0.07)
    updates = lines(out, 'JointDriver update')
    assert [int(line.split()[3]) for line in updates] == [500, 1000], out
    first = updates[0].split()
    # UpdateInfo::simTime and World::SimTime() inside worldUpdateBegin: the time the update steps to
    assert float(first[5]) == pytest.approx(0.5, abs=1e-9)
    assert float(first[7]) == pytest.approx(0.5, abs=1e-9)
    assert float(first[11]) == pytest.approx(2.5, abs=1e-3)  # its own SetVelocity, read back
    assert int(first[15]) == 499  # worldUpdateEnd came after each update before this one
    # Joint::GetForceTorque(0).body2Force: what the joint holds of the rotor, in its frame: measured from the first
    # call on (update 500), so update 1000 reads the rotor's weight held up
    second = updates[1].split()
    assert [float(v) for v in second[17:20]] == pytest.approx([0.0, 0.0, ROTOR_MASS * 9.8], abs=0.02 * ROTOR_MASS * 9.8)


def test_an_effort_plugin_accelerates_its_joint_by_its_inertia(world, capfd):
    torque = 0.01
    r = world.spawn('spinner', robot(driver('effort', torque, report=250)), '/', (0.0, 0.0, 0.1))
    world.run(0.5)
    expected = torque * 0.5 / ROTOR_IZZ  # 2.5 rad/s
    assert joint_state(r).velocity == pytest.approx(expected, rel=0.05)
    updates = lines(capfd.readouterr().out, 'JointDriver update')
    assert float(updates[0].split()[13]) == pytest.approx(torque)  # Joint::GetForce: what it set this update


def test_an_effort_is_truncated_to_the_joints_limits_as_gazebo_truncates_it(world, capfd):
    """Joint::CheckAndTruncateForce: within the URDF's effort limit (3 N m of the 30 asked), and none in the
    direction of motion once the joint is beyond its velocity limit (40 rad/s): the rotor stops accelerating there."""
    r = world.spawn('spinner', robot(driver('effort', 30.0, report=10)), '/', (0.0, 0.0, 0.1))
    world.run(0.2)
    assert float(lines(capfd.readouterr().out, 'JointDriver update')[0].split()[13]) == pytest.approx(3.0)
    step_gain = 3.0 * world.sim.step_size / ROTOR_IZZ  # what one step of the full effort adds
    assert 40.0 <= joint_state(r).velocity <= 40.0 + step_gain + 1e-6


def test_odes_joint_motor_holds_its_velocity(world):
    r = world.spawn('spinner', robot(driver('motor', -4.0)), '/', (0.0, 0.0, 0.1))
    world.run(0.5)
    assert joint_state(r).velocity == pytest.approx(-4.0, abs=0.05)


def test_the_models_joint_controller_holds_a_velocity_with_gazebos_pid(world, capfd):
    """Gazebo's velodyne tutorial: Model::GetJointController()->SetVelocityPID(joint, common::PID(0.1, 0, 0)) and
    SetVelocityTarget. Gazebo's PID pushes back against error = velocity - target; a P controller alone leaves
    no steady error on a free joint (nothing resists it)."""
    r = world.spawn('spinner', robot(driver('pid', 5.0, report=100)), '/', (0.0, 0.0, 0.1))
    world.run(1.0)
    assert joint_state(r).velocity == pytest.approx(5.0, abs=0.01)
    first = lines(capfd.readouterr().out, 'JointDriver update')[0].split()
    # at update 100 (0.1 s): 0.1 N m per rad/s of error on 0.002 kg m^2: e^(-50 t) of the error is left
    assert float(first[11]) == pytest.approx(5.0 * (1 - math.exp(-50 * 0.1)), rel=0.02)
    # GetForce in worldUpdateBegin: the PID's effort of the update before (the controller runs after the event, and
    # a joint's force is kept until its first SetForce of a later update, as ODE's SaveForce): 0.1 N m per rad/s of
    # that update's error, one step (e^(50 * 0.001)) larger than this one's
    assert float(first[13]) == pytest.approx(0.1 * (5.0 - float(first[11])) * math.exp(50 * 0.001), rel=0.01)


def test_a_force_plugin_holds_a_body_against_gravity(world, capfd):
    pusher = ('<plugin name="lift" filename="libmodel_pusher.so"><link>base_link</link><force>0 0 %g</force></plugin>'
              % ((5 + ROTOR_MASS) * 9.8))
    r = world.spawn('spinner', robot(pusher), '/', (0.0, 0.0, 1.0))
    world.run(1.0)
    assert r.body.frame_pose().position[2] == pytest.approx(1.0, abs=2e-3)
    out = capfd.readouterr().out
    assert 'ModelPusher on spinner::base_link mass 5 force 0 0 53.9' in out
    assert 'ModelPusher world force 0 0 53.9' in out  # Link::WorldForce: what AddForce applied this update
    fall = world.spawn('faller', robot(), '/', (2.0, 0.0, 1.0))
    world.run(0.3)
    assert fall.body.frame_pose().position[2] < 0.7


def test_a_plugin_that_throws_in_load_is_reported_and_the_robot_works(world):
    thrower = '<plugin name="bad" filename="libthrowing_plugin.so"><in_load>true</in_load></plugin>'
    r = world.spawn('spinner', robot(thrower, driver('velocity', 1.0)), '/', (0.0, 0.0, 0.1))
    world.run(0.2)
    errors = world.errors('libthrowing_plugin.so')
    assert len(errors) == 1 and 'ThrowingPlugin: thrown in Load on purpose' in errors[0], world.fake.logs
    assert "plugin 'bad'" in errors[0] and 'The robot works without it' in errors[0]
    assert joint_state(r).velocity == pytest.approx(1.0, abs=1e-3)


def test_a_plugin_that_throws_in_its_update_is_unloaded_and_the_rest_goes_on(world):
    thrower = '<plugin name="bad" filename="libthrowing_plugin.so"><after>10</after></plugin>'
    r = world.spawn('spinner', robot(thrower, driver('velocity', 1.5)), '/', (0.0, 0.0, 0.1))
    world.run(0.5)
    errors = world.errors('unloaded after an exception')
    assert len(errors) == 1, world.fake.logs
    assert "spinner: plugin 'bad' (libthrowing_plugin.so)" in errors[0]
    assert 'ThrowingPlugin: thrown in update 11' in errors[0]
    assert joint_state(r).velocity == pytest.approx(1.5, abs=1e-3)
    assert len(world.manager.compiled.plugins) == 1


@pytest.mark.parametrize('filename, reason', [
    ('libnot_a_plugin.so', 'is not a Gazebo plugin: it has no RegisterPlugin'),
    ('libworld_counter.so', 'is not a model plugin'),
    ('libmissing_symbol.so', 'undefined symbol: fixture_function_nobody_defines'),
])
def test_a_library_that_is_not_a_model_plugin_gets_one_error_saying_why(world, filename, reason):
    world.spawn('spinner', robot('<plugin name="p" filename="%s"/>' % filename), '/', (0.0, 0.0, 0.1))
    world.run(0.05)
    errors = world.errors(filename)
    assert len(errors) == 1 and reason in errors[0], world.fake.logs


def test_a_library_nobody_built_is_named_with_where_it_was_looked_for(world):
    world.spawn('spinner', robot('<plugin name="p" filename="libnobody_built.so"/>'), '/', (0.0, 0.0, 0.1))
    warnings = world.warnings('libnobody_built.so')
    assert len(warnings) == 1, world.fake.logs
    assert 'no library libnobody_built.so was found on GAZEBO_PLUGIN_PATH or LD_LIBRARY_PATH' in warnings[0]


def test_reset_world_calls_reset_and_delete_unloads(world, capfd):
    world.spawn('spinner', robot(driver('velocity', 1.0)), '/', (0.0, 0.0, 0.1))
    world.run(0.1)
    world.sim.reset_world()
    assert 'JointDriver reset after 100 updates' in capfd.readouterr().out
    world.sim.delete_model('spinner')
    assert world.manager.compiled.plugins == {}
    assert world.manager.compiled.host.ids() == []
    world.run(0.1)  # no callback of the deleted plugin is left to call


CRASH_SCRIPT = """
import os, sys
sys.path[:0] = [%(here)r, os.path.dirname(%(here)r)]  # this folder and tests/unit (model_plugin_sim, fakes)
from pathlib import Path
from model_plugin_sim import PluginWorld
from test_compiled_plugins import robot
w = PluginWorld(Path(%(tmp)r))
w.spawn('spinner', robot('<plugin name="crasher" filename="libthrowing_plugin.so"><after>5</after>'
                         '<crash>true</crash></plugin>'), '/', (0.0, 0.0, 0.1))
print('stepping', flush=True)
w.run(0.1)
print('survived', flush=True)
"""


def test_a_crash_inside_a_plugin_names_the_plugin_in_the_log(tmp_path, plugin_dir):
    """A bad pointer in a plugin's update ends the process, as in Gazebo, and the log says which plugin ran."""
    env = dict(os.environ, GAZEBO_PLUGIN_PATH=plugin_dir)
    done = subprocess.run([sys.executable, '-c', CRASH_SCRIPT % {'here': HERE, 'tmp': str(tmp_path)}], env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == -signal.SIGSEGV, (done.returncode, done.stdout, done.stderr[-3000:])
    assert 'stepping' in done.stdout and 'survived' not in done.stdout
    assert ("racebot: the world server crashed (SIGSEGV) inside compiled model 'spinner': plugin 'crasher' "
            "(libthrowing_plugin.so), in its own code") in done.stderr, done.stderr[-3000:]


def test_a_world_plugin_loads_after_the_models_and_sees_the_world(world, capfd):
    world.spawn('spinner', robot(), '/', (0.0, 0.0, 0.1))
    world.sim.spec.plugins = [WorldPlugin('counter', 'libworld_counter.so',
                                          '<plugin name="counter" filename="libworld_counter.so">'
                                          '<report>100</report></plugin>'),
                              WorldPlugin('ghost', 'libnobody_built.so', '<plugin name="ghost" filename="x"/>')]
    world.manager.load_world_plugins()
    world.spawn('second', robot(), '/', (2.0, 0.0, 0.1))  # spawned after: the world plugin sees it too
    world.run(0.2)
    counts = lines(capfd.readouterr().out, 'WorldCounter')
    assert counts == ['[Msg] WorldCounter %d models 2 iterations %d' % (n, n) for n in (100, 200)]
    warnings = world.warnings("world plugin 'ghost' (libnobody_built.so) is not simulated")
    assert len(warnings) == 1 and 'GAZEBO_PLUGIN_PATH' in warnings[0], world.fake.logs
    assert world.warnings('libworld_counter.so') == [] and world.errors() == []


def test_gazebo_looks_on_the_plugin_path_then_the_linkers(tmp_path):
    first, second = tmp_path / 'a', tmp_path / 'b'
    for folder in (first, second):
        folder.mkdir()
        (folder / 'libx.so').write_text('')
    env = {'GAZEBO_PLUGIN_PATH': '%s:%s' % (second, first), 'LD_LIBRARY_PATH': str(first)}
    assert find_library('libx.so', env) == str(second / 'libx.so')
    assert find_library('libx.so', {'LD_LIBRARY_PATH': ':%s' % first}) == str(first / 'libx.so')
    assert find_library('liby.so', env) is None
    assert find_library(str(first / 'libx.so'), {}) == str(first / 'libx.so')


def test_the_element_a_plugin_reads_has_sdformats_rewrites():
    import xml.etree.ElementTree as ET
    element = ET.fromstring('<plugin name="p" filename="libp.so"><bodyName>imu_link</bodyName>'
                            '<nested><a>1</a></nested></plugin>')
    spec = urdf_model.GazeboPlugin('p', 'libp.so', {'bodyName': 'base_link', 'nested': ''}, element=element)
    text = plugin_xml(spec)
    assert re.search(r'<bodyName>base_link</bodyName>', text)
    assert '<nested><a>1</a></nested>' in text
    assert 'robotNamespace' not in text


def test_the_spawn_requests_namespace_goes_into_a_compiled_plugin_without_one_as_gazebo_ros_walks_it():
    import xml.etree.ElementTree as ET
    bare = urdf_model.GazeboPlugin('p', 'libp.so', {}, element=ET.fromstring('<plugin name="p" filename="libp.so"/>'))
    own = urdf_model.GazeboPlugin('q', 'libq.so', {'robotNamespace': 'mine'}, element=ET.fromstring(
        '<plugin name="q" filename="libq.so"><robotNamespace>mine</robotNamespace></plugin>'))
    assert ET.fromstring(plugin_xml(bare, '/')).findtext('robotNamespace') == '/'  # spawn_model's default
    assert ET.fromstring(plugin_xml(bare, '')).find('robotNamespace') is None  # an empty request adds nothing
    assert [e.text for e in ET.fromstring(plugin_xml(own, '/uav1')).iter('robotNamespace')] == ['mine']


def test_every_engine_call_gazebo_host_makes_is_a_method_of_the_adapter():
    """gazebo_host's PyEngine looks up the EngineAdapter's methods by name once, when the host is made: a name the
    adapter lacks would fail every plugin at its first load, and an adapter method nobody calls is dead code."""
    source = open(os.path.join(HERE, '..', '..', '..', 'racebot_sim_bridge', 'src', 'cpp', 'gazebo_host.cpp')).read()
    listed = re.search(r'for \(const char \*name : \{([^}]*)\}\)', source)
    assert listed, 'the method list of PyEngine is not where this test reads it'
    called = set(re.findall(r'"(\w+)"', listed.group(1)))
    from racebot_sim_bridge.gazebo_plugins.compiled_plugins import EngineAdapter
    offered = {name for name in vars(EngineAdapter) if not name.startswith('_') and name != 'add_model'}
    assert called == offered, 'PyEngine calls %s the adapter lacks; the adapter has %s PyEngine never calls' % (
        sorted(called - offered), sorted(offered - called))


# -- compiled sensor plugins (scan_probe.cc: a RayPlugin) -------------------------------------------------------
SENSOR_HEIGHT = 0.6  # the spinner's base_link at z 0.1, the laser 0.5 above it, looking straight down


def probe(sensor_type='ray', always_on=False, update_rate=20, samples=11, resolution=1, **params):
    """The spinner with a downward ray sensor 1 m ahead of its base (at `update_rate`), carrying scan_probe (its
    <plugin> params: `params`)."""
    body = plugin_params(params)
    return spinner(
        '<gazebo reference="base_link"><sensor type="%s" name="probe_laser"><pose>1 0 0.5 0 1.5707963 0</pose>'
        '<always_on>%s</always_on><update_rate>%g</update_rate><ray><scan><horizontal><samples>%d</samples>'
        '<resolution>%g</resolution><min_angle>-0.2</min_angle><max_angle>0.2</max_angle></horizontal></scan>'
        '<range><min>0.05</min><max>5</max><resolution>0.01</resolution></range></ray>'
        '<plugin name="probe" filename="libscan_probe.so">%s</plugin></sensor></gazebo>'
        % (sensor_type, 'true' if always_on else 'false', update_rate, samples, resolution, body))


@pytest.fixture
def sensor_world(tmp_path, plugin_dir, monkeypatch):
    """A PluginWorld whose sensors are managed too, the compiled ones on the model plugins' host (as the world
    server shares one)."""
    from racebot_sim_bridge.gazebo_plugins.compiled_plugins import CompiledPlugins
    from racebot_sim_bridge.gazebo_plugins.sensor_manager import SensorManager
    monkeypatch.setenv('GAZEBO_PLUGIN_PATH', plugin_dir)
    w = PluginWorld(tmp_path, params={'~sensors/report_period': 0, '~sensors/render_worker': False})
    compiled = CompiledPlugins(w.fake, w.sim)
    w.manager.compiled = compiled
    w.sensors = SensorManager(w.fake, w.sim, compiled=compiled)
    yield w
    w.sensors.close()
    w.close()


def test_a_sensor_plugin_reads_gazebos_names_and_counts_of_its_ray_sensor(sensor_world, capfd):
    sensor_world.spawn('spinner', probe(samples=11, resolution=2), '/', (0.0, 0.0, 0.1))
    loaded = lines(capfd.readouterr().out, 'ScanProbe loaded')
    assert loaded == ['ScanProbe loaded probe_laser type ray parent spinner::base_link scoped '
                      'default::spinner::base_link::probe_laser topic ~/spinner/base_link/probe_laser/scan rays 11 '
                      'ranges 22 layers 1 rate 20 active 0 world default'], loaded
    assert any("sensor 'probe_laser' on base_link at 20 Hz with compiled plugins" in m
               for _, m in sensor_world.fake.logs), sensor_world.fake.logs


def test_an_inactive_sensor_is_not_measured_and_an_active_one_is_at_its_rate(sensor_world, capfd):
    sensor_world.spawn('spinner', probe(), '/', (0.0, 0.0, 0.1))
    sensor_world.run(0.5)
    assert lines(capfd.readouterr().out, 'ScanProbe rays') == []  # <always_on> false, nobody subscribes
    sensor_world.sim.delete_model('spinner')
    sensor_world.spawn('spinner', probe(always_on=True), '/', (0.0, 0.0, 0.1))
    sensor_world.run(1.0)
    out = capfd.readouterr().out
    rays, updated = lines(out, 'ScanProbe rays'), lines(out, 'ScanProbe updated')
    assert 19 <= len(rays) <= 21 and len(updated) == len(rays), out  # 20 Hz
    # the raw rays (one per sample, from range min, no noise) and the scan, straight down to the ground
    assert float(rays[-1].split()[6]) == pytest.approx(SENSOR_HEIGHT, abs=0.01)
    assert float(rays[-1].split()[4]) == pytest.approx(SENSOR_HEIGHT / math.cos(0.2), abs=0.01)
    times = [float(line.split()[3]) for line in updated]
    assert times[1] - times[0] == pytest.approx(0.05, abs=sensor_world.sim.step_size + 1e-9)
    assert float(updated[-1].split()[5]) == pytest.approx(SENSOR_HEIGHT, abs=0.01)


def test_a_transport_subscriber_gets_each_scan_and_makes_the_sensor_active(sensor_world, capfd):
    sensor_world.spawn('spinner', probe(subscribe='true', rate=10), '/', (0.0, 0.0, 0.1))
    sensor_world.run(1.0)
    out = capfd.readouterr().out
    assert 'ScanProbe subscribed to /gazebo/default/spinner/base_link/probe_laser/scan active 1' in out, out
    scans = lines(out, 'ScanProbe scan ')
    assert 9 <= len(scans) <= 11, out  # the plugin's <rate> 10 over the sensor's 20
    fields = scans[-1].split()
    # ScanProbe scan N time T count C of R mid M step S pose_z Z frame F
    assert int(fields[6]) == 11 and int(fields[8]) == 11
    assert float(fields[10]) == pytest.approx(SENSOR_HEIGHT, abs=0.01)
    assert float(fields[12]) == pytest.approx(0.04, abs=1e-9)  # (0.2 - -0.2) / (11 - 1)
    assert float(fields[14]) == pytest.approx(SENSOR_HEIGHT, abs=0.01)  # the sensor's world pose
    assert fields[16] == 'spinner::base_link'
    assert float(fields[4]) == pytest.approx(float(lines(out, 'ScanProbe updated')[-1].split()[3]))


def test_a_ray_plugin_on_a_gpu_ray_sensor_is_refused_as_gazebo_refuses_it(sensor_world, capfd):
    sensor_world.spawn('spinner', probe(sensor_type='gpu_ray'), '/', (0.0, 0.0, 0.1))
    errors = sensor_world.errors('libscan_probe.so')
    assert len(errors) == 1 and 'RayPlugin requires a Ray Sensor as its parent' in errors[0], sensor_world.fake.logs


def test_a_sensor_plugin_that_throws_in_its_subscriber_is_unloaded_and_the_world_goes_on(sensor_world, capfd):
    r = sensor_world.spawn('spinner', probe(subscribe='true', throw_at=3), '/', (0.0, 0.0, 0.1))
    sensor_world.run(0.5)
    errors = sensor_world.errors('unloaded after an exception')
    assert len(errors) == 1, sensor_world.fake.logs
    assert "spinner: sensor 'probe_laser': plugin 'probe' (libscan_probe.so)" in errors[0]
    assert 'in its subscriber of /gazebo/default/spinner/base_link/probe_laser/scan: ScanProbe: thrown in scan 3' \
        in errors[0]
    assert len(lines(capfd.readouterr().out, 'ScanProbe scan ')) == 2
    assert sensor_world.manager.compiled.plugins == {}
    sensor_world.run(0.2)  # nothing of the unloaded plugin is called
    assert r.name in sensor_world.sim.robots


def test_a_model_plugin_in_a_sensor_is_refused_and_a_depth_cameras_plugin_is_not_hosted(sensor_world):
    urdf = probe().replace('libscan_probe.so', 'libjoint_driver.so')
    sensor_world.spawn('spinner', urdf, '/', (0.0, 0.0, 0.1))
    errors = sensor_world.errors('libjoint_driver.so')
    assert len(errors) == 1 and 'is not a sensor plugin' in errors[0], sensor_world.fake.logs
    sensor_world.sim.delete_model('spinner')
    depth = probe().replace('type="ray"', 'type="depth"')
    sensor_world.spawn('spinner', depth, '/', (0.0, 0.0, 0.1))
    warnings = sensor_world.warnings('libscan_probe.so')
    assert len(warnings) == 1
    assert 'racebot hosts the compiled plugins of ray, gpu_ray, imu, contact, camera sensors only' in warnings[0]


# -- compiled IMU sensor plugins (imu_probe.cc: a SensorPlugin on an ImuSensor) ----------------------------------
def imu_probe(link='base_link', yaw=0.0, always_on=True, update_rate=50, noise='', extra='', **params):
    """The spinner with an imu sensor on `link` (yawed by `yaw` there, at `update_rate`) carrying imu_probe (its
    <plugin> params: `params`); `noise`: the <imu> element's body; `extra`: more <gazebo> (a joint driver)."""
    body = plugin_params(params)
    return spinner(
        '<gazebo reference="%s"><sensor type="imu" name="probe_imu"><pose>0 0 0 0 0 %r</pose>'
        '<always_on>%s</always_on><update_rate>%g</update_rate><imu>%s</imu>'
        '<plugin name="imu_probe" filename="libimu_probe.so">%s</plugin></sensor></gazebo>%s'
        % (link, yaw, 'true' if always_on else 'false', update_rate, noise, body, extra))


def imu_updates(out):
    """ImuProbe's updated lines as (time, orientation xyzw, angular, angular noise-free, linear, linear noise-free)."""
    rows = []
    for line in lines(out, 'ImuProbe updated at'):
        f = line.split()
        values = [float(v) for v in f[3:4] + f[5:9] + f[10:13] + f[14:17] + f[18:21] + f[22:25]]
        rows.append((values[0], values[1:5], values[5:8], values[8:11], values[11:14], values[14:17]))
    return rows


def test_an_imu_plugin_reads_gazebos_measurement_of_a_resting_sensor(sensor_world, capfd):
    sensor_world.spawn('spinner', imu_probe(yaw=0.5), '/', (0.0, 0.0, 0.1))
    sensor_world.run(1.0)
    out = capfd.readouterr().out
    assert 'ImuProbe loaded probe_imu type imu parent spinner::base_link category 2 rate 50 active 1' in out, out
    updates = imu_updates(out)
    assert 49 <= len(updates) <= 51, out  # 50 Hz
    assert updates[1][0] - updates[0][0] == pytest.approx(0.02, abs=sensor_world.sim.step_size + 1e-9)
    _, q, w, w0, a, a0 = updates[-1]
    # Gazebo's default reference: the sensor's own orientation when it was made, so a resting sensor reads identity
    assert q == pytest.approx([0.0, 0.0, 0.0, 1.0], abs=1e-3)
    assert w0 == pytest.approx([0.0, 0.0, 0.0], abs=1e-3) and w == w0  # no <noise>: the same values
    # at rest an accelerometer reads minus gravity, whatever its yaw: +9.8 up
    assert a0 == pytest.approx([0.0, 0.0, 9.8], abs=0.02) and a == a0
    assert any("imu sensor 'probe_imu' on base_link at 50 Hz with compiled plugins, Gazebo topic "
               '/gazebo/default/spinner/base_link/probe_imu/imu' in m for _, m in sensor_world.fake.logs), \
        sensor_world.fake.logs


def test_an_imu_with_the_world_as_reference_reads_its_yaw_and_set_reference_pose_rezeroes_it(sensor_world, capfd):
    sensor_world.spawn('spinner', imu_probe(yaw=0.5, world_reference='true'), '/', (0.0, 0.0, 0.1))
    sensor_world.run(0.5)
    q = imu_updates(capfd.readouterr().out)[-1][1]
    assert q == pytest.approx([0.0, 0.0, math.sin(0.25), math.cos(0.25)], abs=1e-3)
    sensor_world.sim.delete_model('spinner')
    sensor_world.spawn('spinner', imu_probe(yaw=0.5, world_reference='true', reference_at=3), '/', (0.0, 0.0, 0.1))
    sensor_world.run(0.5)
    updates = imu_updates(capfd.readouterr().out)
    # the 3rd update's callback set the reference after that measurement: from the 4th on, identity
    assert updates[2][1] == pytest.approx([0.0, 0.0, math.sin(0.25), math.cos(0.25)], abs=1e-3)
    assert updates[3][1] == pytest.approx([0.0, 0.0, 0.0, 1.0], abs=1e-3)


def test_an_imu_on_a_spinning_rotor_reads_its_rate_and_in_free_fall_reads_no_acceleration(sensor_world, capfd):
    sensor_world.spawn('spinner', imu_probe(link='rotor', extra='<gazebo>%s</gazebo>' % driver('velocity', 3.0)),
                       '/', (0.0, 0.0, 5.0))
    sensor_world.run(0.4)  # falling from 5 m: on the ground after about 1 s
    _, q, w, w0, a, a0 = imu_updates(capfd.readouterr().out)[-1]
    assert w0[2] == pytest.approx(3.0, abs=0.05)
    assert a0 == pytest.approx([0.0, 0.0, 0.0], abs=0.05)  # gravity and the fall cancel, as Gazebo differences
    # its yaw has turned with the rotor since it was made: the reference is where it started
    yaw = 2.0 * math.atan2(q[2], q[3])
    assert abs(yaw) > 0.3


def test_an_imus_noise_is_on_what_a_plugin_reads_and_the_noise_free_values_are_kept(sensor_world, capfd):
    noise = ('<angular_velocity><z><noise type="gaussian"><mean>0.5</mean><stddev>0</stddev></noise></z>'
             '</angular_velocity><linear_acceleration><x><noise type="gaussian"><mean>-0.25</mean><stddev>0'
             '</stddev></noise></x></linear_acceleration>')
    sensor_world.spawn('spinner', imu_probe(noise=noise), '/', (0.0, 0.0, 0.1))
    sensor_world.run(0.5)
    _, _, w, w0, a, a0 = imu_updates(capfd.readouterr().out)[-1]
    assert w[2] == pytest.approx(w0[2] + 0.5, abs=1e-5) and w0[2] == pytest.approx(0.0, abs=1e-3)
    assert a[0] == pytest.approx(a0[0] - 0.25, abs=1e-5) and a[2] == a0[2]


def test_an_inactive_imu_is_not_measured_until_a_transport_subscriber_comes(sensor_world, capfd):
    sensor_world.spawn('spinner', imu_probe(always_on=False), '/', (0.0, 0.0, 0.1))
    sensor_world.run(0.3)
    out = capfd.readouterr().out
    assert 'active 0' in lines(out, 'ImuProbe loaded')[0] and imu_updates(out) == [], out
    sensor_world.sim.delete_model('spinner')
    sensor_world.spawn('spinner', imu_probe(always_on=False, update_rate=10, subscribe='true'), '/', (0.0, 0.0, 0.1))
    sensor_world.run(1.0)
    out = capfd.readouterr().out
    assert 'ImuProbe subscribed to /gazebo/default/spinner/base_link/probe_imu/imu active 1' in out, out
    messages = lines(out, 'ImuProbe msg ')
    assert 9 <= len(messages) <= 11, out
    f = messages[-1].split()  # ImuProbe msg N entity E stamp T linear_z Z orientation_w W
    assert f[4] == 'spinner::base_link' and float(f[8]) == pytest.approx(9.8, abs=0.02)
    assert float(f[6]) == pytest.approx(imu_updates(out)[-1][0])


# -- compiled contact sensor plugins (contact_probe.cc: a SensorPlugin on a ContactSensor) ------------------------
def contact_probe(update_rate=10, collision='base_link_collision', **params):
    """The spinner with a contact sensor on its base (at `update_rate`) watching `collision`, carrying
    contact_probe."""
    body = plugin_params(params)
    return spinner(
        '<gazebo reference="base_link"><sensor type="contact" name="bumper"><update_rate>%g</update_rate>'
        '<contact><collision>%s</collision></contact>'
        '<plugin name="contact_probe" filename="libcontact_probe.so">%s</plugin></sensor></gazebo>'
        % (update_rate, collision, body))


def contact_updates(out):
    return [line.split() for line in lines(out, 'ContactProbe updated at')]


def test_a_contact_plugin_reads_every_steps_contacts_since_the_last_update_as_gazebo_keeps_them(sensor_world, capfd):
    sensor_world.spawn('spinner', contact_probe(), '/', (0.0, 0.0, 0.1))
    sensor_world.run(1.0)
    out = capfd.readouterr().out
    assert ('ContactProbe loaded bumper type contact collisions 1 first spinner::base_link::base_link_collision '
            'beyond []') in out, out
    updates = contact_updates(out)
    # 10 Hz; the first update it is active at subscribes and has no steps yet, as Gazebo's
    assert 8 <= len(updates) <= 10, out
    f = updates[-1]
    # ContactProbe updated at T time T contacts N first C1 with C2 points P depth D force_z F step_time S
    #   points_of_own Q others O other_count K other_name X
    assert f[3] == f[5]  # the Contacts message's time is the update's
    assert int(f[7]) == 100  # one contact (the base on the ground) of each of the 100 steps since the last update
    assert f[9] == 'spinner::base_link::base_link_collision' and f[11] == 'ground_plane::link::collision'
    points = int(f[13])
    assert points >= 1
    # the ground holds the whole robot: (5 + 0.5) kg * 9.8 up, on the base's link in its frame
    assert float(f[17]) == pytest.approx(5.5 * 9.8, rel=0.02)
    assert float(f[19]) < float(f[3])  # the first contact is the oldest step's
    assert int(f[21]) == 100 * points  # GetCollisionContactCount: every point of every contact
    # Contacts(collision): one physics::Contact per other collision (the last step's), its points counted
    assert f[23] == '1' and int(f[25]) == points and f[27] == 'ground_plane::link::collision'


def test_a_contact_sensor_in_the_air_reads_no_contacts_and_a_transport_subscriber_gets_each_update(sensor_world,
                                                                                                   capfd):
    sensor_world.spawn('spinner', contact_probe(update_rate=20, subscribe='true'), '/', (0.0, 0.0, 3.0))
    sensor_world.run(0.3)  # falling: 0.44 m in 0.3 s
    out = capfd.readouterr().out
    assert 'ContactProbe subscribed to /gazebo/default/spinner/base_link/bumper' in out, out
    updates = contact_updates(out)
    assert updates and all(int(f[7]) == 0 for f in updates), out
    messages = lines(out, 'ContactProbe msg ')
    assert len(messages) == len(updates) and messages[-1].endswith('contacts 0')


# -- compiled camera sensor plugins (camera_probe.cc: a CameraPlugin) --------------------------------------------
WALL = """<robot name="wall"><link name="wall"><inertial><mass value="50"/><inertia ixx="1" iyy="1" izz="1" ixy="0"
ixz="0" iyz="0"/></inertial><visual><geometry><box size="0.5 4 0.9"/></geometry><material name="red"><color
rgba="0.9 0.1 0.1 1"/></material></visual><collision><geometry><box size="0.5 4 0.9"/></geometry></collision></link>
</robot>"""


def camera_probe(image_format='R8G8B8', update_rate=10, distortion='', **params):
    """The spinner with a camera 0.5 m above its base looking ahead, carrying camera_probe (a red wall 0.8 m ahead,
    whose top edge crosses its image, fills the image's bottom row: camera_world)."""
    body = plugin_params(params)
    return spinner(
        '<gazebo reference="base_link"><sensor type="camera" name="probe_camera"><pose>0 0 0.5 0 0 0</pose>'
        '<update_rate>%g</update_rate><camera><horizontal_fov>1.2</horizontal_fov><image><width>64</width>'
        '<height>48</height><format>%s</format></image><clip><near>0.05</near><far>50</far></clip>%s</camera>'
        '<plugin name="camera_probe" filename="libcamera_probe.so">%s</plugin></sensor></gazebo>'
        % (update_rate, image_format, distortion, body))


def camera_frames(out):
    return [line.split() for line in lines(out, 'CameraProbe frame ')]


def test_a_camera_plugin_reads_its_cameras_image_and_gets_each_frame(sensor_world, capfd):
    sensor_world.spawn('wall', WALL, '/', (1.05, 0.0, 0.45))
    sensor_world.spawn('spinner', camera_probe(), '/', (0.0, 0.0, 0.1))
    sensor_world.run(1.0)
    out = capfd.readouterr().out
    loaded = lines(out, 'CameraProbe loaded')
    assert len(loaded) == 1, out
    f = loaded[0].split()
    # CameraProbe loaded NAME type T size WxH depth D format F hfov H vfov V clip N F bytes B active A topic X k1 K
    assert f[2:12] == ['probe_camera', 'type', 'camera', 'size', '64x48', 'depth', '3', 'format', 'R8G8B8', 'hfov']
    assert float(f[12]) == pytest.approx(1.2)
    assert float(f[14]) == pytest.approx(2 * math.atan(math.tan(0.6) * 48 / 64), abs=1e-6)
    assert f[16:18] == ['0.05', '50'] and f[19] == str(64 * 48 * 3) and f[21] == '1'  # CameraPlugin switches it on
    assert f[23] == '~/spinner/base_link/probe_camera/image' and f[25] == '-1'  # no <distortion>
    frames = camera_frames(out)
    assert 9 <= len(frames) <= 11, out  # 10 Hz
    g = frames[-1]
    # CameraProbe frame N at T size WxH depth D format F top MEAN bottom MEAN same_data S
    assert g[6:12] == ['64x48', 'depth', '3', 'format', 'R8G8B8', 'top'] and g[15:] == ['same_data', '1']
    assert float(frames[1][4]) - float(frames[0][4]) == pytest.approx(0.1, abs=sensor_world.sim.step_size + 1e-9)
    # rendered from the world: the red wall fills the bottom row, the background the top one; without the wall
    # the bottom row sees the ground plane, the top one the same background
    sensor_world.sim.delete_model('wall')
    sensor_world.run(0.3)
    h = camera_frames(capfd.readouterr().out)[-1]
    assert abs(float(g[14]) - float(h[14])) > 10.0 and float(g[12]) == pytest.approx(float(h[12]), abs=1.0), (g, h)


def test_a_mono_camera_gets_one_byte_a_pixel_and_a_plugins_set_hfov_is_rendered(sensor_world, capfd):
    sensor_world.spawn('spinner', camera_probe('L8', hfov=0.6), '/', (0.0, 0.0, 0.1))
    sensor_world.run(0.5)
    out = capfd.readouterr().out
    f = lines(out, 'CameraProbe loaded')[0].split()
    assert f[7:9] == ['depth', '1'] and f[19] == str(64 * 48) and float(f[12]) == pytest.approx(0.6)
    assert camera_frames(out)[-1][6:11] == ['64x48', 'depth', '1', 'format', 'L8']


def test_a_cameras_distortion_is_read_and_a_camera_plugin_on_a_ray_sensor_is_refused(sensor_world, capfd):
    distortion = '<distortion><k1>-0.25</k1><k2>0.12</k2><k3>0</k3><p1>0</p1><p2>0</p2></distortion>'
    sensor_world.spawn('spinner', camera_probe(distortion=distortion), '/', (0.0, 0.0, 0.1))
    assert lines(capfd.readouterr().out, 'CameraProbe loaded')[0].split()[25] == '-0.25'
    sensor_world.sim.delete_model('spinner')
    sensor_world.spawn('spinner', probe().replace('libscan_probe.so', 'libcamera_probe.so'), '/', (0.0, 0.0, 0.1))
    errors = sensor_world.errors('libcamera_probe.so')
    assert len(errors) == 1 and 'CameraPlugin requires a CameraSensor as its parent' in errors[0], errors
