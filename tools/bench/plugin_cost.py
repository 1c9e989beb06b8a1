"""What a compiled Gazebo model plugin costs per world update, beside the same work in Python (issue 39 point 5).

In-process, no ROS: a Simulator with the spinner robot of tests/fixtures/gazebo_plugin_project (a body and one
continuous joint) under four plugin sets, stepped in interleaved rounds (side by side, so the machine's drift falls
on all alike): none; joint_driver in mode none (an empty worldUpdateBegin callback: what the host's event dispatch
costs); joint_driver in mode velocity (Joint::SetVelocity every update, one call back into the engine); and a Python
model plugin doing the same (racebot's ModelPlugin, before_physics). Each figure is the median over the rounds of
the wall time per update above the bare robot's, in microseconds.
"""
import os
import subprocess
import time

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin
from racebot_sim_bridge.gazebo_plugins.plugin_manager import PluginManager
from racebot_sim_bridge.gazebo_plugins.registry import Registry

from . import common, stats

PROJECT = os.path.join(common.REPO, 'tests', 'fixtures', 'gazebo_plugin_project')
TARGET = 'joint_driver'
VELOCITY = 2.5
with open(os.path.join(PROJECT, 'spinner.urdf.in')) as _f:
    SPINNER = _f.read()  # the compiled plugin tests' robot; its rotor, limits and plugins filled by robot()
CPP = '<plugin name="driver" filename="libjoint_driver.so"><joint>spin_joint</joint><mode>%s</mode>' \
      '<target>%g</target></plugin>'
PYTHON = '<plugin name="driver" filename="libbench_python_driver.so"><joint>spin_joint</joint></plugin>'
VARIANTS = (('none', ''), ('cpp_empty', CPP % ('none', 0.0)), ('cpp_velocity', CPP % ('velocity', VELOCITY)),
            ('python_velocity', PYTHON))


def robot(extra):
    return SPINNER % {'mass': 0.5, 'izz': 0.002, 'effort': 3.0, 'velocity': 40.0, 'extra': extra}


class PythonDriver(ModelPlugin):
    """joint_driver's velocity mode as a racebot Python plugin: the joint's velocity set before every step."""
    libraries = ('libbench_python_driver.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        self.joint_ = self.joint('joint')

    def before_physics(self, time):
        self.joint_.set_position(self.joint_.state().position, VELOCITY)


class _ErrorsKept:
    """The simulator's and the plugins' log (rospy's calls too): errors kept, the rest dropped."""

    def __init__(self):
        self.errors = []

    def error(self, message):
        self.errors.append(message)

    logerr = error

    def warn(self, message):
        pass

    info = logwarn = loginfo = warn


class _NullIO:
    def __getattr__(self, name):
        return lambda *args, **kwargs: None


def build(folder):
    """The fixture project's joint_driver built in `folder` (kept: a second run only checks it is current)."""
    os.makedirs(folder, exist_ok=True)
    for command in (['cmake', PROJECT], ['make', TARGET]):
        done = subprocess.run(command, cwd=folder, capture_output=True, text=True, timeout=600)
        if done.returncode != 0:
            raise common.BenchError('%s failed in %s:\n%s' % (' '.join(command), folder, done.stdout[-2000:]))
    return folder


def _world(tmp, markup):
    path = os.path.join(tmp, 'ground.world')
    with open(path, 'w') as f:
        f.write('<sdf version="1.6"><world name="default"><model name="ground_plane"><static>true</static>'
                '<link name="link"><collision name="c"><geometry><plane><normal>0 0 1</normal></plane></geometry>'
                '</collision></link></model></world></sdf>')
    log = _ErrorsKept()
    sim = Simulator(sdf_reader.load_world(path), _NullIO(), log, lambda name: None)
    manager = PluginManager(log, sim, registry=Registry((PythonDriver,)))
    sim.spawn_urdf('spinner', robot('<gazebo>%s</gazebo>' % markup), '/', (0.0, 0.0, 0.1))
    if log.errors:
        raise common.BenchError('the bench robot did not load its plugin: %s' % log.errors[0])
    return sim, manager


def measure(params, out):
    """{variant: us per update, 'overhead_us': {variant: above 'none'}, ...} (see the module)."""
    folder = build(os.path.join(out, 'gazebo_plugins_build'))
    os.environ['GAZEBO_PLUGIN_PATH'] = folder
    steps, rounds = int(params['steps']), int(params['rounds'])
    worlds = {name: _world(os.path.join(out, 'tmp'), markup) for name, markup in VARIANTS}
    per_update = {name: [] for name, _ in VARIANTS}
    try:
        for sim, _ in worlds.values():  # warm up: first updates allocate
            for _ in range(200):
                sim.step()
        for _ in range(rounds):
            for name, (sim, _) in worlds.items():
                start = time.perf_counter()
                for _ in range(steps):
                    sim.step()
                per_update[name].append(1e6 * (time.perf_counter() - start) / steps)
        for name in ('cpp_velocity', 'python_velocity'):
            sim = worlds[name][0]
            velocity = sim.robots['spinner'].body.joints['spin_joint'].state().velocity
            if abs(velocity - VELOCITY) > 1e-3:
                raise common.BenchError('%s: the joint turns at %.4f rad/s, not %.1f' % (name, velocity, VELOCITY))
    finally:
        for sim, manager in worlds.values():
            manager.close()
            sim.close()
    base = per_update['none']
    overhead = {name: [t - b for t, b in zip(times, base)] for name, times in per_update.items() if name != 'none'}
    return {'steps': steps, 'rounds': rounds,
            'update_us': {name: stats.median(times) for name, times in per_update.items()},
            'overhead_us': {name: stats.median(values) for name, values in overhead.items()},
            'overhead_spread_us': {name: stats.spread(values) for name, values in overhead.items()}}
