"""Model plugins whose <bodyName> and <frameName> name a link Gazebo lumps into its parent, on a real Simulator:
built as Gazebo 11 builds them from sdformat's rewrite (description/sdf_reduction), they report the parent
link's motion with the fixed joint as xyzOffset/rpyOffset, applied as each upstream plugin applies them."""
import pytest

from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.kinematics.rotations import quaternion_multiply, rpy_to_quaternion, yaw_of

from model_plugin_sim import PluginWorld
from diff_drive_world import ServiceRospy

# A robot as community packages write one: base_link with mass and a box, an imu_link without <inertial> on a
# fixed joint 0.1 forward, 0.2 up, turned 0.5 rad about z (J); gazebo_ros_imu naming imu_link as body and
# frame (as TurtleBot3 does), gazebo_ros_p3d naming it as body.
ROBOT = """<robot name="bot">
  <link name="base_link">
    <inertial><mass value="2"/><inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="imu_link"/>
  <joint name="imu_joint" type="fixed">
    <parent link="base_link"/><child link="imu_link"/><origin xyz="0.1 0 0.2" rpy="0 0 0.5"/>
  </joint>
  <gazebo>
    <plugin name="imu_plugin" filename="libgazebo_ros_imu.so">
      <bodyName>imu_link</bodyName><frameName>imu_link</frameName><topicName>imu</topicName>
      <serviceName>imu_service</serviceName><gaussianNoise>0.0</gaussianNoise><updateRate>0</updateRate>
    </plugin>
    <plugin name="ground_truth" filename="libgazebo_ros_p3d.so">
      <bodyName>imu_link</bodyName><topicName>truth</topicName><frameName>world</frameName>
    </plugin>
  </gazebo>
</robot>"""

YAW = 0.3        # the robot's heading
SPIN = 1.0       # rad/s about z, given to the falling robot


@pytest.fixture
def world(tmp_path):
    w = PluginWorld(tmp_path)
    w.fake = ServiceRospy()
    w.manager.rospy = w.fake
    robot = w.sim.spawn_urdf('bot', ROBOT, '/', (0.0, 0.0, 5.0), rpy_to_quaternion(0.0, 0.0, YAW))
    w.sim.world.client.resetBaseVelocity(robot.body.id, (0.0, 0.0, 0.0), (0.0, 0.0, SPIN))
    for topic in ('/imu', '/truth'):
        w.fake.publishers[topic].connections = 1
    yield w, robot
    w.close()


def quaternion(o):
    return (o.x, o.y, o.z, o.w)


def test_both_plugins_are_built_and_say_what_sdformat_rewrote(world):
    w, robot = world
    assert w.errors() == []
    infos = [m for level, m in w.fake.logs if level == 'info' and 'fixed-joint lumping rewrote' in m]
    assert len(infos) == 2 and '<bodyName> imu_link -> base_link' in infos[0]
    assert '<frameName> imu_link -> base_link' in infos[0]


def test_gazebo_ros_imu_reports_the_parent_link_turned_by_the_joint_twice(world):
    # sdformat rewrites bodyName (offsets J), then frameName (offsets J * J): rpyOffset yaw 1.0. The IMU's
    # orientation is Rz(1.0) * the link's (upstream: offset first), its frame_id base_link; its angular
    # velocity the link's, turned by that orientation (about z it stays SPIN)
    w, robot = world
    w.run(0.2)
    msg = w.fake.publishers['/imu'].messages[-1]
    assert msg.header.frame_id == 'base_link'
    _, orientation, _, _ = link_motion(w.sim.world, robot.body, 'base_link')
    expected = quaternion_multiply(rpy_to_quaternion(0.0, 0.0, 1.0), orientation)
    assert yaw_of(quaternion(msg.orientation)) == pytest.approx(yaw_of(expected), abs=1e-3)
    assert yaw_of(orientation) == pytest.approx(YAW + SPIN * 0.2, abs=0.01)  # the link turned as given
    assert msg.angular_velocity.z == pytest.approx(SPIN, abs=1e-3)


def test_gazebo_ros_p3d_reports_the_parent_link_plus_the_joint_as_upstream_applies_offsets(world):
    # bodyName rewritten once: xyzOffset 0.1 0 0.2, rpyOffset 0 0 0.5. p3d adds xyzOffset to the world position
    # as it is (not turned by the link) and puts Rz(0.5) before the link's orientation; child_frame_id is the
    # rewritten bodyName
    w, robot = world
    w.run(0.2)
    msg = w.fake.publishers['/truth'].messages[-1]
    position, orientation, velocity, angular = link_motion(w.sim.world, robot.body, 'base_link')
    assert msg.child_frame_id == 'base_link'
    p = msg.pose.pose.position
    # the message is taken before the last step: positions one step (1 ms of a fall at ~2 m/s) apart
    assert (p.x, p.y, p.z) == pytest.approx((position[0] + 0.1, position[1], position[2] + 0.2), abs=5e-3)
    assert p.z < 5.2 - 0.1  # falling
    assert yaw_of(quaternion(msg.pose.pose.orientation)) == pytest.approx(yaw_of(orientation) + 0.5, abs=2e-3)
    assert msg.twist.twist.angular.z == pytest.approx(SPIN, abs=1e-3)
    assert msg.twist.twist.linear.z == pytest.approx(velocity[2], abs=0.02)


def test_a_link_sdformat_keeps_but_the_physics_merges_is_still_refused_naming_where_it_went(tmp_path):
    # a link fixed to a root named world: sdformat keeps it (no reduction into world), PyBullet's fixed base
    # merges it, so the plugin cannot be given it
    robot = ROBOT.replace('<link name="base_link">', '<link name="world"/><joint name="fix" type="fixed">'
                          '<parent link="world"/><child link="base_link"/></joint><link name="base_link">')
    w = PluginWorld(tmp_path)
    w.fake = ServiceRospy()
    w.manager.rospy = w.fake
    try:
        w.sim.spawn_urdf('bot', robot, '/', (0.0, 0.0, 1.0))
        errors = w.errors('refused')
        assert len(errors) == 2 and all("merges this link into 'world'" in e for e in errors), errors
    finally:
        w.close()
