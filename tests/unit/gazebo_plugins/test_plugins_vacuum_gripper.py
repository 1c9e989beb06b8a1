"""gazebo_ros_vacuum_gripper on a real Simulator: a gripper link fixed 1 m above the ground and a free box
spawned next to it. Off: grasping false, the box falls. On (the `on` service): within 5 cm the box gets the
gripper's velocity and a 20 N force along the gripper's offset in the BOX's axes, applied in world axes (read back
exactly through the box's gazebo_ros_f3d); within 1 cm it is put at the gripper; grasping true; `off` lets go."""
import pytest

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_vacuum_gripper import vacuum_step
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion

from model_plugin_sim import PluginWorld

GRIPPER_AT = (0.0, 0.0, 1.0)
VACUUM = '<plugin name="vacuum" filename="libgazebo_ros_vacuum_gripper.so">%s</plugin>'
PARAMS = '<bodyName>end_effector</bodyName><topicName>grasping</topicName>'


def gripper(plugin):
    return """<robot name="arm">
 <link name="world"/>
 <joint name="fix" type="fixed"><parent link="world"/><child link="wrist"/></joint>
 <link name="wrist"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
 <joint name="end_joint" type="revolute"><parent link="wrist"/><child link="end_effector"/>
  <origin xyz="0 0 1"/><limit effort="30" velocity="1" lower="0" upper="0"/></joint>
 <link name="end_effector"><inertial><mass value="0.0001"/>
  <inertia ixx="1e-08" iyy="1e-08" izz="1e-08" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <gazebo>%s</gazebo>
</robot>""" % plugin


OBJECT = """<robot name="box">
 <link name="box"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/>
  </inertial><collision><geometry><box size="0.02 0.02 0.02"/></geometry></collision></link>
 <gazebo><plugin name="f3d" filename="libgazebo_ros_f3d.so"><bodyName>box</bodyName><topicName>box_force</topicName>
  </plugin></gazebo>
</robot>"""


def spawn(tmp_path, params=PARAMS, box_at=(0.03, 0.0, 1.0), yaw=0.0):
    w = PluginWorld(tmp_path)
    w.spawn('arm', gripper(VACUUM % params), '/', (0.0, 0.0, 0.0))  # first: its update runs before the box's f3d
    box = w.spawn('box', OBJECT, '/', box_at)
    frame = box.body.com_pose_for_frame(box_at, rpy_to_quaternion(0.0, 0.0, yaw))
    box.body.set_pose(frame.position, frame.orientation)
    w.fake.publishers['/box_force'].connections = 1
    return w, box


def test_off_it_publishes_false_every_update_and_the_box_falls(tmp_path):
    w, box = spawn(tmp_path)
    try:
        w.run(0.1)
        grasping = w.fake.publishers['/grasping'].messages
        assert len(grasping) == 100 and not any(m.data for m in grasping)
        assert link_motion(w.sim.world, box.body, 'box')[0][2] == pytest.approx(1.0 - 0.5 * 9.8 * 0.1 ** 2, abs=2e-3)
        assert w.fake.publishers['/box_force'].messages[-1].wrench.force.x == 0.0
    finally:
        w.close()


def test_on_the_force_is_20_n_along_the_offset_in_the_links_axes(tmp_path):
    w, box = spawn(tmp_path, yaw=1.5707963267948966)  # the box turned a quarter left; the gripper 3 cm along -x
    try:
        w.fake.services['/on'](None)
        w.run(0.001)
        f = w.fake.publishers['/box_force'].messages[-1].wrench.force
        # upstream: (gripper - box) in the box's axes is (0, 0.03, 0); 1 / 0.03 > 20 N, so 20 N along world +y, not
        # toward the gripper (-x)
        assert (f.x, f.y, f.z) == pytest.approx((0.0, 20.0, 0.0), abs=1e-6)
        assert w.fake.publishers['/grasping'].messages[-1].data is True
        _, _, linear, _ = link_motion(w.sim.world, box.body, 'box')
        # its velocity was set to the gripper's (0) before the step: one step of 20 N and gravity on 0.1 kg
        assert linear == pytest.approx((0.0, 20.0 / 0.1 * 0.001, -9.8 * 0.001), abs=1e-4)
    finally:
        w.close()


def test_on_an_unturned_box_is_pulled_in_and_held_at_the_gripper(tmp_path):
    w, box = spawn(tmp_path, box_at=(0.0, 0.02, 0.97))
    try:
        w.fake.services['/on'](None)
        w.run(0.001)
        f = w.fake.publishers['/box_force'].messages[-1].wrench.force
        offset = (0.0, -0.02, 0.03)
        norm = sum(c * c for c in offset) ** 0.5
        assert (f.x, f.y, f.z) == pytest.approx(tuple(20.0 * c / norm for c in offset), abs=1e-4)
        w.run(1.0)
        position = link_motion(w.sim.world, box.body, 'box')[0]
        assert position == pytest.approx(GRIPPER_AT, abs=5e-4)  # snapped every step it drifts past 1 cm... held
        assert all(m.data for m in w.fake.publishers['/grasping'].messages[-1000:])
        w.fake.services['/on'](None)
        assert w.warnings("already status is 'on'")
        w.fake.services['/off'](None)
        w.run(0.2)
        assert link_motion(w.sim.world, box.body, 'box')[0][2] < 0.85  # let go: it falls
        assert w.fake.publishers['/grasping'].messages[-1].data is False
    finally:
        w.close()


def test_out_of_reach_nothing_happens(tmp_path):
    w, box = spawn(tmp_path, box_at=(0.06, 0.0, 1.0))
    try:
        w.fake.services['/on'](None)
        w.run(0.05)
        assert not any(m.data for m in w.fake.publishers['/grasping'].messages)
        assert w.fake.publishers['/box_force'].messages[-1].wrench.force.x == 0.0
        assert vacuum_step((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0, 0, 0, 1)) == (True, (0.0, 0.0, 0.0))
    finally:
        w.close()


def test_namespace_and_refusals(tmp_path):
    w, _ = spawn(tmp_path, '<robotNamespace>/robot/left_vacuum_gripper</robotNamespace>' + PARAMS)
    try:
        assert '/robot/left_vacuum_gripper/grasping' in w.fake.publishers
        assert {'/robot/left_vacuum_gripper/on', '/robot/left_vacuum_gripper/off'} <= set(w.fake.services)
    finally:
        w.close()
    for params, reason in (('<topicName>g</topicName>', '<bodyName> is missing'),
                           ('<bodyName>end_effector</bodyName>', '<topicName> is missing'),
                           ('<bodyName>nope</bodyName><topicName>g</topicName>', 'is not a link of the model')):
        w, _ = spawn(tmp_path, params)
        try:
            assert w.errors(reason), w.fake.logs
        finally:
            w.close()
