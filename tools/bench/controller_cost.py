"""What a compiled ros_control controller costs per control update, beside the same work in Python (issue 39 point 5).

A scenario (a child process with its own master: a C++ controller's NodeHandles need one). A Simulator with a
one-joint robot whose gazebo_ros_control plugin drives the joint through a VelocityJointInterface, under three
controller sets, stepped in interleaved rounds (side by side, so the machine's drift falls on all alike): none;
racebot's Python velocity_controllers/JointVelocityController; the C++ VelocityForwardController of
tests/fixtures/gazebo_plugin_workspace/fixture_cpp_controllers, built here from its source with the catkin configs of
racebot's ros_control stand-ins and made through pluginlib as the world server makes it. Both forward a velocity
command to the joint at every update (the control period is the physics step). Each figure is the median over the
rounds of the wall time per update above the robot without a controller, in microseconds.
"""
import os
import subprocess

from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin
from racebot_sim_bridge.ros_control.controller_switch import STRICT

from . import common
from .update_cost import ErrorsKept, check_turning, figures, ground_world, robot, time_updates

FIXTURES = os.path.join(common.REPO, 'tests', 'fixtures', 'gazebo_plugin_workspace')
SOURCE = os.path.join(FIXTURES, 'fixture_cpp_controllers', 'src', 'velocity_forward_controller.cpp')
LIBRARY = 'fixture_cpp_controllers'  # the fixture's plugin XML: lib/libfixture_cpp_controllers
VELOCITY = 2.5
NS = '/bench'
TRANSMISSION = """<transmission name="spin_transmission">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="spin_joint"><hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint>
    <actuator name="spin_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">
    <robotNamespace>%s</robotNamespace></plugin></gazebo>""" % NS
CONTROLLERS = {  # variant -> (controller name, its parameters)
    'python': ('python', {'type': 'velocity_controllers/JointVelocityController', 'joint': 'spin_joint'}),
    'cpp': ('cpp', {'type': 'fixture_cpp_controllers/VelocityForwardController', 'joint': 'spin_joint',
                    'publish_rate': 0.0}),
}
CMAKE = """cmake_minimum_required(VERSION 3.0.2)
project(bench_cpp_controller CXX)
find_package(catkin REQUIRED COMPONENTS controller_interface hardware_interface pluginlib realtime_tools roscpp
  std_msgs)
add_library(%(library)s SHARED %(source)s)
target_include_directories(%(library)s PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(%(library)s ${catkin_LIBRARIES})
target_compile_options(%(library)s PRIVATE -std=c++17 -O2)
set_target_properties(%(library)s PROPERTIES LIBRARY_OUTPUT_DIRECTORY %(prefix)s/lib)
"""


class _Nothing:
    """A publisher, subscriber or service that goes nowhere: the Python controller is driven here without rospy."""

    def __getattr__(self, name):
        return lambda *args, **kwargs: None


class _UnwiredIO:
    """The controllers' I/O (ros_control/controller_io.py's RosIO) without ROS; no command trace."""
    command_trace = None

    def __getattr__(self, name):
        return lambda *args, **kwargs: _Nothing()


def build(folder):
    """The fixture's controller built into `folder`/prefix/lib (kept: a second run only checks it is current);
    the prefix, which pluginlib searches (CMAKE_PREFIX_PATH) for the library the fixture's plugin XML names."""
    prefix, build_dir = os.path.join(folder, 'prefix'), os.path.join(folder, 'build')
    os.makedirs(build_dir, exist_ok=True)
    with open(os.path.join(folder, 'CMakeLists.txt'), 'w') as f:
        f.write(CMAKE % {'library': LIBRARY, 'source': SOURCE, 'prefix': prefix})
    for command in (['cmake', folder], ['make']):
        done = subprocess.run(command, cwd=build_dir, capture_output=True, text=True, timeout=900)
        if done.returncode != 0:
            raise common.BenchError('%s failed in %s:\n%s' % (' '.join(command), build_dir,
                                                            (done.stdout + done.stderr)[-2000:]))
    return prefix


def _world(tmp, variant, params):
    log = ErrorsKept()
    sim = Simulator(ground_world(tmp), _UnwiredIO(), log, lambda key: params.get(key.rstrip('/')))
    from racebot_sim_bridge.gazebo_plugins import gazebo_host
    GazeboRosControlPlugin.attach(sim, ensure_roscpp=lambda: gazebo_host.start_roscpp('bench_controllers_cpp', {}))
    sim.spawn_urdf('spinner', robot(TRANSMISSION), '/', (0.0, 0.0, 0.1))
    control = sim.robots['spinner'].control
    if variant in CONTROLLERS:
        name = CONTROLLERS[variant][0]
        if not control.cm.load(name):
            raise common.BenchError('%s: controller %s did not load: %s' % (variant, name, log.errors))
        request = control.cm.request_switch([name], [], STRICT)
        sim.step()
        if request is None or not request.ok:
            raise common.BenchError('%s: controller %s did not start: %s' % (variant, name, log.errors))
    return sim, control.cm


def measure(p, out):
    """{'update_us': {variant: us per update}, 'overhead_us': {variant: above 'none'}, ...} (see the module)."""
    import rospy
    from std_msgs.msg import Float64
    prefix = build(os.path.join(out, 'controller_cost'))
    os.environ['CMAKE_PREFIX_PATH'] = prefix + ':' + os.environ.get('CMAKE_PREFIX_PATH', '')
    os.environ['ROS_PACKAGE_PATH'] = FIXTURES + ':' + os.environ.get('ROS_PACKAGE_PATH', '')
    port = int(os.environ['ROS_MASTER_URI'].rsplit(':', 1)[1])
    master = common.roscore(port, os.path.join(out, 'logs', 'controller_cost_roscore.log'))
    worlds = {}
    try:
        rospy.init_node('bench_controllers', disable_signals=True)
        params = {'%s/%s' % (NS, name): config for name, config in CONTROLLERS.values()}
        for key, config in params.items():  # what the C++ controller's NodeHandle reads
            rospy.set_param(key, config)
        worlds = {variant: _world(os.path.join(out, 'tmp'), variant, params) for variant in ('none', 'python', 'cpp')}
        worlds['python'][1].loaded['python'].controller.command = VELOCITY  # its topic: no rospy in the Simulator
        command = rospy.Publisher(NS + '/cpp/command', Float64, queue_size=1, latch=True)
        command.publish(Float64(VELOCITY))
        sim = worlds['cpp'][0]
        joint = sim.robots['spinner'].body.joints['spin_joint']
        # to the solver's precision, as check_turning judges it: on ODE's pyramid friction the spinner's base, held on
        # the ground against the rotor's reaction, leaves the motor 2e-4 rad/s off its target
        common.wait_for(lambda: sim.step() or abs(joint.state().velocity - VELOCITY) < 1e-3, 30,
                        'the C++ controller to take its command')
        steps, rounds = int(p['steps']), int(p['rounds'])
        sims = {variant: sim for variant, (sim, _) in worlds.items()}
        per_update = time_updates(sims, steps, rounds)
        check_turning(sims, CONTROLLERS, VELOCITY)
    finally:
        for sim, _ in worlds.values():
            sim.close()
        master.stop()
    return figures(per_update, steps, rounds)
