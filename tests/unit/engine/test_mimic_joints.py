"""URDF <mimic> joints driven by racebot (beyond Gazebo 11, which ignores <mimic>), on a real Simulator: a gripper
whose leader finger a position controller moves (through gazebo_ros_control) and whose other joints follow as
multiplier * leader + offset; loops are refused, a mimic joint's own transmission commands nothing."""
import math

import pytest

from racebot_sim_bridge.description import sdf_reader, urdf_reader
from racebot_sim_bridge.description.urdf_model import UrdfError
from racebot_sim_bridge.engine.simulator import Simulator, SpawnError
from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin

from mimic_gripper import drive, gripper, positions
from fakes import FakeLog


@pytest.fixture
def sim():
    s = Simulator(sdf_reader.parse_world(sdf_reader.EMPTY_WORLD_SDF), io=None, log=FakeLog(), get_params={}.get)
    GazeboRosControlPlugin.attach(s)
    yield s
    s.close()


def test_mimic_joints_follow_multiplier_times_the_leader_plus_offset(sim):
    robot = sim.spawn_urdf('gripper', gripper([('twin', 'revolute', 'joint="leader"'),
                                               ('mirror', 'revolute', 'joint="leader" multiplier="-0.5" offset="0.3"'),
                                               ('slide', 'prismatic', 'joint="leader" multiplier="0.1"')]))
    assert set(robot.body.mimics) == {'twin', 'mirror', 'slide'}
    assert positions(sim, robot, 'twin', 'mirror', 'slide') == pytest.approx([0.0, 0.3, 0.0], abs=1e-9)  # at spawn
    for target in (1.2, -0.7):
        drive(sim, robot, target, 1.0)
        leader, twin, mirror, slide = positions(sim, robot, 'leader', 'twin', 'mirror', 'slide')
        assert leader == pytest.approx(target, abs=1e-3)
        assert twin == pytest.approx(leader, abs=1e-3)
        assert mirror == pytest.approx(-0.5 * leader + 0.3, abs=1e-3)
        assert slide == pytest.approx(0.1 * leader, abs=1e-3)


def test_a_chain_of_mimics_follows_through_and_reset_puts_it_back(sim):
    robot = sim.spawn_urdf('gripper', gripper([('b', 'revolute', 'joint="c" multiplier="2"'),
                                               ('c', 'revolute', 'joint="leader" offset="-0.2"')]))
    drive(sim, robot, 0.5, 1.0)
    leader, b, c = positions(sim, robot, 'leader', 'b', 'c')
    assert c == pytest.approx(leader - 0.2, abs=1e-3) and b == pytest.approx(2 * c, abs=2e-3)
    sim.reset_world()
    assert positions(sim, robot, 'leader', 'b', 'c') == pytest.approx([0.0, -0.4, -0.2], abs=1e-9)
    robot.body.joints['leader'].set_position(0.25)  # set_model_configuration's way
    assert positions(sim, robot, 'b', 'c') == pytest.approx([0.1, 0.05], abs=1e-9)


def test_a_mimic_joints_transmission_reads_it_and_commands_nothing(sim):
    robot = sim.spawn_urdf('gripper', gripper([('twin', 'revolute', 'joint="leader" multiplier="-1"')],
                                              transmissions=('leader', 'twin')))
    assert any("'twin' is a URDF <mimic> of 'leader'" in w for w in sim.log.warnings)
    twin = robot.control.hw.handles['twin']
    for _ in range(1000):
        robot.control.hw.handles['leader'].command = 0.6
        twin.command = 1.5  # ignored: the mimic wins
        sim.step()
    assert twin.position == pytest.approx(-0.6, abs=1e-3)


def test_without_the_gears_the_mimic_joint_would_hang_free(sim):
    """What the test above relies on: the mimic joint's link is loaded by gravity, so only the gear holds it."""
    robot = sim.spawn_urdf('gripper', gripper([('twin', 'revolute', None)]))
    drive(sim, robot, 1.0, 1.0)
    assert abs(positions(sim, robot, 'twin')[0] - 1.0) > 0.3


def test_a_mimic_loop_is_refused_with_the_loop_named():
    for mimics in ([('a', 'revolute', 'joint="b"'), ('b', 'revolute', 'joint="a"')],
                   [('a', 'revolute', 'joint="a" multiplier="2"')]):
        with pytest.raises(UrdfError, match='form a loop') as err:
            urdf_reader.parse_urdf(gripper(mimics))
        assert "'a' mimics" in str(err.value)


def test_a_mimic_loop_is_a_spawn_refusal(sim):
    with pytest.raises(SpawnError, match="the URDF of gripper is not valid: the <mimic> joints form a loop "
                                         "\\('a' mimics 'b' mimics 'a'\\)"):
        sim.spawn_urdf('gripper', gripper([('a', 'revolute', 'joint="b"'), ('b', 'revolute', 'joint="a"')]))
    assert 'gripper' not in sim.world.bodies


def test_mimics_that_cannot_be_driven_are_warned_and_left_free():
    model = urdf_reader.parse_urdf(gripper([('a', 'revolute', 'joint="nothing"')]))
    assert model.mimics() == {}
    assert any("<mimic joint='nothing'>: the URDF has no such joint" in w for w in model.warnings)
    with pytest.raises(UrdfError, match='has no joint attribute'):
        urdf_reader.parse_urdf(gripper([('a', 'revolute', 'multiplier="2"')]))
    with pytest.raises(UrdfError, match='not a number'):
        urdf_reader.parse_urdf(gripper([('a', 'revolute', 'joint="leader" multiplier="x"')]))


def test_a_deleted_robot_takes_its_gears_with_it(sim):
    before = sim.world.client.getNumConstraints()
    sim.spawn_urdf('gripper', gripper([('twin', 'revolute', 'joint="leader"')]))
    assert sim.world.client.getNumConstraints() == before + 1
    sim.delete_model('gripper')
    assert sim.world.client.getNumConstraints() == before
    assert not math.isnan(sim.time)
