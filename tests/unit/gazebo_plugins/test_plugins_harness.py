"""gazebo_ros_harness on a real Simulator: a 10 kg box hung from the world by the plugin's prismatic joint (Gazebo
11's harness.world settings): the winch holds it against gravity and sideways pushes, lowers it at the commanded
velocity on /<model>/harness/velocity, holds it again at 0, and std_msgs/Bool true on /<model>/harness/detach
drops it to the ground."""
import pytest
from std_msgs.msg import Bool, Float32

from model_plugin_sim import PluginWorld

HARNESS = """<plugin filename="libgazebo_ros_harness.so" name="harness">
 <joint name="joint1" type="prismatic"><pose>0 0 1 0 0 0</pose><parent>world</parent><child>%s</child>
  <axis><xyz>0 0 1</xyz><dynamics><damping>10</damping></dynamics>
   <limit><lower>-1.5</lower><upper>1.5</upper><effort>10000</effort><velocity>-1</velocity></limit></axis></joint>
 <winch><joint>joint1</joint>
  <pos_pid><p>1000000</p><i>0</i><d>0</d><i_max>0</i_max><i_min>0</i_min><cmd_max>10000</cmd_max>
   <cmd_min>-10000</cmd_min></pos_pid>
  <vel_pid><p>10000</p><i>0</i><d>0</d><i_max>0</i_max><i_min>0</i_min><cmd_max>10000</cmd_max>
   <cmd_min>0</cmd_min></vel_pid></winch>
 <detach>joint1</detach>%s
</plugin>"""
BOX = """<robot name="box">
 <link name="link"><inertial><mass value="10"/><inertia ixx="1.7" iyy="1.7" izz="1.7" ixy="0" ixz="0" iyz="0"/>
  </inertial><collision><geometry><box size="1 1 1"/></geometry></collision></link>
 <gazebo>%s</gazebo>
</robot>"""


def spawn(tmp_path, child='link', extra=''):
    w = PluginWorld(tmp_path)
    return w, w.spawn('box', BOX % (HARNESS % (child, extra)), pose=(0.0, 0.0, 1.5))


def z(w, robot):
    return robot.body.frame_pose().position[2]


def test_the_harness_holds_lowers_holds_again_and_detaches(tmp_path):
    w, robot = spawn(tmp_path)
    try:
        w.run(2.0)
        assert z(w, robot) == pytest.approx(1.5, abs=1e-3)  # 98 N of gravity against p = 1e6
        robot.body.links['link'].apply_wrench((500.0, 0.0, 0.0), (0.0, 0.0, 0.0))
        w.run(0.5)
        x, y, _ = robot.body.frame_pose().position
        assert abs(x) < 1e-3 and abs(y) < 1e-3  # a slider: no sideways motion
        w.fake.subscribers['/box/harness/velocity'](Float32(data=-0.5))
        w.run(1.0)
        _, twist = robot.body.links['link'].state()
        assert twist.linear[2] == pytest.approx(-0.5, abs=0.02)  # the winch lets it down at 0.5 m/s
        w.fake.subscribers['/box/harness/velocity'](Float32(data=0.0))
        w.run(0.5)
        held = z(w, robot)
        assert 0.8 < held < 1.1
        w.run(1.0)
        assert z(w, robot) == pytest.approx(held, abs=1e-3)
        w.fake.subscribers['/box/harness/detach'](Bool(data=False))
        w.run(0.5)
        assert z(w, robot) == pytest.approx(held, abs=1e-3)  # false detaches nothing
        w.fake.subscribers['/box/harness/detach'](Bool(data=True))
        w.run(2.0)
        assert z(w, robot) == pytest.approx(0.5, abs=0.01)  # on the ground
        assert w.sim.world.client.getNumConstraints() == 0
    finally:
        w.close()


def test_without_a_winch_gazebo_11_detaches_at_the_first_update(tmp_path):
    w = PluginWorld(tmp_path)
    try:
        urdf = BOX % (HARNESS % ('link', '')).replace('<winch>', '<x>').replace('</winch>', '</x>')
        robot = w.spawn('box', urdf, pose=(0.0, 0.0, 1.5))
        assert w.warnings('A <winch> element is missing from the harness plugin')
        w.run(1.0)
        assert z(w, robot) < 1.0  # falling
    finally:
        w.close()


def test_a_harness_without_joints_is_refused(tmp_path):
    w, robot = spawn(tmp_path, child='nothing')
    try:
        assert w.errors('Unable to load joint[joint1]')
        assert w.errors('No joints specified in the harness plugin')
    finally:
        w.close()
