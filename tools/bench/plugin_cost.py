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

from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin
from racebot_sim_bridge.gazebo_plugins.plugin_manager import PluginManager
from racebot_sim_bridge.gazebo_plugins.registry import Registry

from . import common
from .update_cost import PROJECT, ErrorsKept, check_turning, figures, ground_world, robot, time_updates

TARGET = 'joint_driver'
VELOCITY = 2.5
CPP = '<plugin name="driver" filename="libjoint_driver.so"><joint>spin_joint</joint><mode>%s</mode>' \
      '<target>%g</target></plugin>'
PYTHON = '<plugin name="driver" filename="libbench_python_driver.so"><joint>spin_joint</joint></plugin>'
VARIANTS = (('none', ''), ('cpp_empty', CPP % ('none', 0.0)), ('cpp_velocity', CPP % ('velocity', VELOCITY)),
            ('python_velocity', PYTHON))


class PythonDriver(ModelPlugin):
    """joint_driver's velocity mode as a racebot Python plugin: the joint's velocity set before every step."""
    libraries = ('libbench_python_driver.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)
        self.joint_ = self.joint('joint')

    def before_physics(self, time):
        self.joint_.set_position(self.joint_.state().position, VELOCITY)


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
    log = ErrorsKept()
    sim = Simulator(ground_world(tmp), _NullIO(), log, lambda name: None)
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
    try:
        sims = {name: sim for name, (sim, _) in worlds.items()}
        per_update = time_updates(sims, steps, rounds)
        check_turning(sims, ('cpp_velocity', 'python_velocity'), VELOCITY)
    finally:
        for sim, manager in worlds.values():
            manager.close()
            sim.close()
    return figures(per_update, steps, rounds)
