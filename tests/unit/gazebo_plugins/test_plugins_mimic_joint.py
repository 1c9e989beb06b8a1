"""roboticsgroup's mimic joint plugin (libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so and its older name) on a
real Simulator: the mimic joint follows joint * multiplier + offset, set in place every update (upstream's
SetPosition) or pushed there by a PID effort (hasPID, gains from the parameter server); it takes a joint over from
racebot's URDF <mimic> gear; a missing joint refuses it."""
import pytest

from model_plugin_sim import PluginWorld
from mimic_gripper import drive, gripper, positions  # the gripper of the URDF <mimic> tests

PLUGIN = ('<gazebo><plugin name="mimic" filename="%s"><joint>leader</joint><mimicJoint>twin</mimicJoint>%s'
          '</plugin></gazebo></robot>')


def spawn(tmp_path, params='', library='libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so', mimic=None,
          pid_params=None):
    from racebot_sim_bridge.gazebo_ros_control.gazebo_ros_control_plugin import GazeboRosControlPlugin
    w = PluginWorld(tmp_path)
    w.sim.get_params = (pid_params or {}).get
    GazeboRosControlPlugin.attach(w.sim)
    urdf = gripper([('twin', 'revolute', mimic)]).replace('</robot>', PLUGIN % (library, params))
    return w, w.spawn('gripper', urdf)


@pytest.mark.parametrize('library', ['libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so',
                                     'libroboticsgroup_gazebo_mimic_joint_plugin.so'])
def test_the_mimic_joint_is_set_to_multiplier_times_the_joint_plus_offset(tmp_path, library):
    w, robot = spawn(tmp_path, '<multiplier>-0.5</multiplier><offset>0.3</offset>', library)
    try:
        for target in (1.2, -0.7):
            drive(w.sim, robot, target, 1.0)
            leader, twin = positions(w.sim, robot, 'leader', 'twin')
            assert leader == pytest.approx(target, abs=1e-3)
            assert twin == pytest.approx(-0.5 * leader + 0.3, abs=1e-3)
    finally:
        w.close()


def test_with_has_pid_an_effort_pushes_it_there(tmp_path):
    gains = {'/gazebo_ros_control/pid_gains/twin': {'p': 50.0, 'd': 0.5}}
    w, robot = spawn(tmp_path, '<multiplier>2</multiplier><hasPID/><maxEffort>30</maxEffort>', pid_params=gains)
    try:
        drive(w.sim, robot, 0.4, 2.0)
        leader, twin = positions(w.sim, robot, 'leader', 'twin')
        assert twin == pytest.approx(2 * leader, abs=0.02)  # a PID against gravity: a small steady error
        assert abs(twin - 2 * leader) > 1e-5  # not set in place: pushed
    finally:
        w.close()


def test_has_pid_without_gains_gives_no_effort_as_upstream(tmp_path):
    w, robot = spawn(tmp_path, '<hasPID>my_gains</hasPID>')
    try:
        assert w.errors("/my_gains: no PID gains given")
        drive(w.sim, robot, 1.0, 1.0)
        assert abs(positions(w.sim, robot, 'twin')[0] - 1.0) > 0.3  # hangs free
    finally:
        w.close()


def test_sensitiveness_leaves_small_differences_alone(tmp_path):
    w, robot = spawn(tmp_path, '<sensitiveness>0.5</sensitiveness>')
    try:
        drive(w.sim, robot, 0.3, 1.0)
        assert positions(w.sim, robot, 'twin')[0] == pytest.approx(0.0, abs=0.05)  # braked by fmax, not moved
        drive(w.sim, robot, 1.5, 1.0)
        leader, twin = positions(w.sim, robot, 'leader', 'twin')
        assert abs(twin - leader) <= 0.5 + 1e-3 and abs(twin) > 0.9
    finally:
        w.close()


def test_it_takes_a_urdf_mimic_joint_over_from_the_gear(tmp_path):
    w, robot = spawn(tmp_path, '<multiplier>-1</multiplier>', mimic='joint="leader" multiplier="1"')
    try:
        assert 'twin' not in robot.body.mimics and w.sim.world.client.getNumConstraints() == 0
        drive(w.sim, robot, 0.8, 1.0)
        leader, twin = positions(w.sim, robot, 'leader', 'twin')
        assert twin == pytest.approx(-leader, abs=1e-3)  # the plugin's multiplier, not the URDF's
    finally:
        w.close()


def test_a_missing_or_unknown_joint_refuses_the_plugin(tmp_path):
    for plugin, error in (('<joint>leader</joint>', 'No mimicJoint element present. MimicJointPlugin could not be'),
                          ('<joint>leader</joint><mimicJoint>nothing</mimicJoint>', '<mimicJoint>nothing</mimicJoint> '
                                                                                    'is not a movable joint')):
        urdf = gripper([('twin', 'revolute', None)]).replace(
            '</robot>', '<gazebo><plugin name="m" filename="libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so">'
            '%s</plugin></gazebo></robot>' % plugin)
        w = PluginWorld(tmp_path)
        try:
            w.spawn('gripper', urdf)
            assert w.errors(error)
        finally:
            w.close()
