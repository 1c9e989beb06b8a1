"""docs/WRITE_A_PLUGIN_OR_CONTROLLER.md, kept true: the page's example model plugin (HeightPublisher) and
ros_control controller (EffortRampController) are defined here exactly as the page shows them (the first test
checks every Python block of the page against this file), and run on a real Simulator (PyBullet DIRECT, no
master): the plugin in a PluginWorld, the controller under gazebo_ros_control's controller manager."""
import re
from pathlib import Path

import pytest

from racebot_sim_bridge.description import sdf_reader
from racebot_sim_bridge.engine.simulator import Simulator
from racebot_sim_bridge.gazebo_plugins.registry import Registry
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin
from racebot_sim_bridge.ros_control.controller_switch import STRICT
from racebot_sim_bridge.ros_controllers import CONTROLLER_TYPES

from fakes import FakeIO, FakeLog
from model_plugin_sim import PluginWorld
from wheel_robot import EMPTY_WORLD, _robot

# the page's imports, as the page shows them: the plugin's, then the controller's
from std_msgs.msg import Float64

from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.gazebo_plugins.model_plugin import ModelPlugin
from racebot_sim_bridge.gazebo_ros_api.plugin_namespace import model_plugin_namespace, name_in
from racebot_sim_bridge.gazebo_plugins.update_timing import FixedPeriod

from racebot_sim_bridge.ros_control.controller_interface import Controller
from racebot_sim_bridge.ros_control.hardware_interface import EFFORT

# -- the page's code, as the page shows it ---------------------------------------------------------------------


class HeightPublisher(ModelPlugin):
    libraries = ('libmy_height_publisher.so',)

    def __init__(self, ctx, robot, spec):
        super().__init__(ctx, robot, spec)  # PluginParams in self.params, the world in self.world
        p = self.params
        self.link_name = self.link_param('bodyName', 'the link whose height is published')
        self.clock = FixedPeriod(p.number('updateRate', 10.0, minimum=0), ctx.sim.time)
        ns = model_plugin_namespace('drive', p.string('robotNamespace', None), robot.spawn_namespace, robot.name,
                                    ctx.sim.node_namespace)
        self.pub = self.publisher(name_in(ns, p.string('topicName', 'height')), Float64)

    def after_step(self, time):
        if self.clock.due(time):
            position = link_motion(self.world, self.robot.body, self.link_name)[0]
            self.pub.publish(Float64(position[2]))


class EffortRampController(Controller):
    """my_controllers/EffortRampController: one joint's effort, from 0 to `effort` in `ramp_time` seconds."""
    type_name = 'my_controllers/EffortRampController'
    interface = EFFORT

    def __init__(self, name, ns, params, hw, io):  # ros_control's init(): ControllerInitError says what is wrong
        super().__init__(name, ns, params, hw, io)
        self.joint = self._joint_param()                       # `joint`, with an EffortJointInterface
        self.effort = self._number('effort', 1.0)
        self.ramp_time = self._number('ramp_time', 1.0, positive=True)
        self.started = 0.0

    def starting(self, time):
        self.started = time

    def update(self, time, period):
        self.joint.command = self.effort * min(1.0, (time - self.started) / self.ramp_time)

    def stopping(self, time):
        self.joint.command = 0.0

    def claimed_resources(self):
        return [(self.interface, [self.joint.name])]


# -- the tests -------------------------------------------------------------------------------------------------

PAGE = Path(__file__).resolve().parents[2] / 'docs' / 'WRITE_A_PLUGIN_OR_CONTROLLER.md'
BOX = ('<robot name="box"><link name="base"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" '
       'iyy="0.01" iyz="0" izz="0.01"/></inertial><collision><geometry><box size="0.2 0.2 0.2"/></geometry>'
       '</collision></link><gazebo><plugin name="height" filename="libmy_height_publisher.so">%s</plugin>'
       '</gazebo></robot>')


def test_the_page_shows_the_code_of_this_file():
    blocks = re.findall(r'```python\n(.*?)```', PAGE.read_text(), re.S)
    assert len(blocks) >= 2
    here = Path(__file__).read_text()
    for block in blocks:
        assert block in here, 'docs/%s shows code this test does not run:\n%s' % (PAGE.name, block)


def test_the_plugin_publishes_its_links_height_at_its_rate(tmp_path):
    w = PluginWorld(tmp_path, registry=Registry([HeightPublisher]))
    try:
        w.spawn('box', BOX % '<bodyName>base</bodyName><updateRate>50</updateRate>', '/box', (0.0, 0.0, 1.0))
        w.run(1.0)
        heights = [m.data for m in w.fake.publishers['/box/height'].messages]
        assert len(heights) == 49                                  # 50 Hz: at 0.021 s, 0.041 s, ... 0.981 s
        assert heights[0] == pytest.approx(1.0, abs=0.01)          # let go at 1 m ...
        assert heights[-1] == pytest.approx(0.1, abs=0.01)         # ... it lies on the ground (half its 0.2 m)
        assert w.warnings() == [] and w.errors() == []
    finally:
        w.close()


def test_the_plugin_refuses_a_link_the_model_does_not_have(tmp_path):
    w = PluginWorld(tmp_path, registry=Registry([HeightPublisher]))
    try:
        w.spawn('box', BOX % '<bodyName>lid</bodyName>', '/box')
        assert '/box/height' not in w.fake.publishers
        (error,) = w.errors("'height'")
        assert '<bodyName>lid</bodyName> is not a link of the model' in error
    finally:
        w.close()


@pytest.fixture
def controlled(monkeypatch):
    """The one-wheel robot (an EffortJointInterface on wheel_joint) under gazebo_ros_control, the example type
    registered as ros_controllers' own are, and its YAML on the parameter server."""
    monkeypatch.setitem(CONTROLLER_TYPES, EffortRampController.type_name, EffortRampController)
    params = {'/ramp': {'type': 'my_controllers/EffortRampController', 'joint': 'wheel_joint', 'effort': 0.02,
                        'ramp_time': 0.5},
              '/bad_ramp': {'type': 'my_controllers/EffortRampController', 'joint': 'wheel_joint', 'ramp_time': -1}}
    world = sdf_reader.parse_world(EMPTY_WORLD.replace('<physics', '<gravity>0 0 0</gravity><physics'))
    sim = Simulator(world, FakeIO(), FakeLog(), params.get)
    GazeboRosControlPlugin.attach(sim)
    robot = sim.spawn_urdf('bot', _robot(''), '/')
    yield sim, robot.control.cm, robot.control.hw.handles['wheel_joint']
    sim.close()


def run(sim, seconds):
    for _ in range(int(round(seconds / sim.step_size))):
        sim.step()


def test_the_controller_ramps_the_effort_and_stops_at_zero(controlled):
    sim, cm, wheel = controlled
    assert cm.load('ramp') and cm.request_switch(['ramp'], [], STRICT)
    run(sim, 0.25)
    assert wheel.command == pytest.approx(0.01, rel=0.05)      # half way up the ramp
    run(sim, 0.5)
    assert wheel.command == pytest.approx(0.02) and wheel.velocity > 0.1
    assert cm.request_switch([], ['ramp'], STRICT)
    sim.step()
    assert wheel.command == 0.0


def test_the_controller_refuses_a_bad_parameter(controlled):
    sim, cm, _ = controlled
    assert not cm.load('bad_ramp')
    assert '/bad_ramp/ramp_time must be a positive number, got -1' in sim.log.errors[-1]
