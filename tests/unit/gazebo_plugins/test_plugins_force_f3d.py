"""gazebo_ros_force and gazebo_ros_f3d on a real Simulator: a wrench from the topic accelerates a free body
at F/m and spins it at tau/I (world axes, every update, held until the next message); f3d reads what was
applied to the link in the update before it (world axes, frame_id frameName), nothing when the force plugin
comes after it, as Gazebo's accumulators; and the template plugin is registered and silent."""
import pytest
from geometry_msgs.msg import Wrench

from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion

from model_plugin_sim import PluginWorld

MASS, IZZ = 2.0, 0.5
FORCE = '<plugin name="push" filename="libgazebo_ros_force.so"><bodyName>%s</bodyName>' \
        '<topicName>force</topicName></plugin>'
F3D = '<plugin name="f3d" filename="libgazebo_ros_f3d.so"><bodyName>box</bodyName><topicName>f3d</topicName>' \
      '<frameName>map</frameName></plugin>'


def box(*plugins):
    return """<robot name="box">
 <link name="box"><inertial><mass value="%g"/>
  <inertia ixx="0.5" iyy="0.5" izz="%g" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
 <joint name="marker_joint" type="fixed"><parent link="box"/><child link="marker"/><origin xyz="0 0 0.1"/></joint>
 <link name="marker"/>
 <gazebo>%s</gazebo>
</robot>""" % (MASS, IZZ, ''.join(plugins))


def spawn(tmp_path, *plugins, namespace='/'):
    w = PluginWorld(tmp_path)
    robot = w.spawn('box', box(*plugins), namespace, (0.0, 0.0, 5.0))  # in the air: no contact for a second
    frame = robot.body.com_pose_for_frame((0.0, 0.0, 5.0), rpy_to_quaternion(0.3, 0.0, 0.0))
    robot.body.set_pose(frame.position, frame.orientation)  # tilted: world axes are not the box's
    return w, robot


def push(w, topic, force, torque=(0.0, 0.0, 0.0)):
    msg = Wrench()
    msg.force.x, msg.force.y, msg.force.z = force
    msg.torque.x, msg.torque.y, msg.torque.z = torque
    w.fake.subscribers[topic](msg)


def test_a_force_accelerates_a_free_body_at_f_over_m_in_world_axes(tmp_path):
    w, robot = spawn(tmp_path, FORCE % 'box', namespace='/ns')
    try:
        w.run(0.1)
        _, _, v0, _ = link_motion(w.sim.world, robot.body, 'box')
        assert v0[0] == pytest.approx(0.0, abs=1e-9) and v0[1] == pytest.approx(0.0, abs=1e-9)  # zero before
        push(w, '/ns/force', (3.0, -1.0, 0.0), (0.0, 0.0, 0.25))
        w.run(0.5)
        _, _, v, omega = link_motion(w.sim.world, robot.body, 'box')
        assert v[0] == pytest.approx(3.0 / MASS * 0.5, rel=0.01)  # every update until the next message
        assert v[1] == pytest.approx(-1.0 / MASS * 0.5, rel=0.01)
        assert v[2] == pytest.approx(-9.8 * 0.6, rel=0.01)  # gravity as ever
        # tau about world z on a box tilted about x: solve I_world * alpha = tau for the spin it gives
        assert omega[2] > 0.05 and omega[0] == pytest.approx(0.0, abs=1e-6)
        push(w, '/ns/force', (0.0, 0.0, 0.0))
        w.run(0.2)
        _, _, v2, _ = link_motion(w.sim.world, robot.body, 'box')
        assert v2[0] == pytest.approx(v[0], rel=0.002)  # a zero wrench stops the push
    finally:
        w.close()


def test_an_untilted_spin_is_tau_over_i(tmp_path):
    w, robot = spawn(tmp_path, FORCE % 'marker')  # a lumped link: sdformat's rewrite makes it the box
    try:
        robot.body.set_pose(robot.body.com_pose_for_frame((0, 0, 5), (0, 0, 0, 1)).position,
                             (0, 0, 0, 1))
        push(w, '/force', (0.0, 0.0, 0.0), (0.0, 0.0, 0.25))
        w.run(0.4)
        _, _, _, omega = link_motion(w.sim.world, robot.body, 'box')
        assert omega[2] == pytest.approx(0.25 / IZZ * 0.4, rel=0.01)
    finally:
        w.close()


def test_f3d_reads_what_was_applied_before_it_in_world_axes(tmp_path):
    w, robot = spawn(tmp_path, FORCE % 'box', F3D)
    try:
        pub = w.fake.publishers['/f3d']
        w.run(0.01)
        assert pub.messages == []  # nobody listens
        pub.connections = 1
        push(w, '/force', (3.0, -1.0, 0.5), (0.1, 0.2, 0.3))
        w.run(0.01)
        msg = pub.messages[-1]
        assert msg.header.frame_id == 'map'  # frameName is the frame_id, the values stay in world axes
        assert msg.header.stamp.to_sec() == pytest.approx(0.02)
        f, t = msg.wrench.force, msg.wrench.torque
        assert (f.x, f.y, f.z, t.x, t.y, t.z) == pytest.approx((3.0, -1.0, 0.5, 0.1, 0.2, 0.3))
        assert len(pub.messages) == 10  # every update
    finally:
        w.close()


def test_f3d_before_the_force_plugin_reads_nothing_as_gazebos_cleared_accumulators(tmp_path):
    w, robot = spawn(tmp_path, F3D, FORCE % 'box')
    try:
        pub = w.fake.publishers['/f3d']
        pub.connections = 1
        push(w, '/force', (3.0, 0.0, 0.0))
        w.run(0.01)
        f = pub.messages[-1].wrench.force
        assert (f.x, f.y, f.z) == (0.0, 0.0, 0.0)  # no gravity, no contact: only what is added to the body
        assert pub.messages[-1].header.frame_id == 'map'
    finally:
        w.close()


@pytest.mark.parametrize('plugin, reason', [
    ('<plugin name="p" filename="libgazebo_ros_force.so"><topicName>f</topicName></plugin>', '<bodyName> is missing'),
    ('<plugin name="p" filename="libgazebo_ros_force.so"><bodyName>box</bodyName></plugin>', '<topicName> is missing'),
    ('<plugin name="p" filename="libgazebo_ros_f3d.so"><bodyName>nope</bodyName><topicName>f</topicName></plugin>',
     'is not a link of the model'),
    ('<plugin name="p" filename="libgazebo_ros_f3d.so"><bodyName>box</bodyName></plugin>', '<topicName> is missing'),
])
def test_refused(tmp_path, plugin, reason):
    w, _ = spawn(tmp_path, plugin)
    try:
        assert w.errors(reason), w.fake.logs
    finally:
        w.close()


def test_the_template_is_simulated_and_does_nothing(tmp_path):
    w, _ = spawn(tmp_path, '<plugin name="t" filename="libgazebo_ros_template.so"/>')
    try:
        w.run(0.01)
        assert not w.warnings() and not w.errors()
        assert len(w.manager.plugins['box']) == 1
    finally:
        w.close()
