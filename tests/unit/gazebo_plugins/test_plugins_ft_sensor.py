"""gazebo_ros_ft_sensor on a real Simulator: a weight hanging below the sensor joint reads what statics
says (m g along the child frame's up, its moment about the joint), with the topic, frame, rate and noise
upstream gives, and the joints it refuses."""
import statistics

import pytest

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_ft_sensor import cross, wrench_at_link_origin
from racebot_sim_bridge.kinematics.rotations import rotate, rotate_back, rpy_to_quaternion

from model_plugin_sim import PluginWorld

MASS, G = 2.0, 9.8
COM = (0.1, 0.0, -0.05)
JOINT_RPY = (0.6, 0.0, 0.5)  # the child frame tilted: the weight is not along its z
INERTIAL_RPY = (0.0, 0.4, 0.0)  # PyBullet measures in these axes; the message is in the link's


def arm(plugin, ft_type='fixed', preserve=True):
    keep = '<gazebo reference="ft"><preserveFixedJoint>true</preserveFixedJoint></gazebo>' if preserve else ''
    axis = '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/>' if ft_type != 'fixed' else ''
    return """<robot name="arm">
 <link name="world"/>
 <joint name="mount" type="fixed"><parent link="world"/><child link="base"/><origin xyz="0 0 1"/></joint>
 <link name="base"><inertial><mass value="1"/>
  <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <joint name="ft" type="%s"><parent link="base"/><child link="tool"/>
  <origin xyz="0 0 -0.2" rpy="%g %g %g"/>%s</joint>
 <link name="tool"><inertial><origin xyz="%g %g %g" rpy="%g %g %g"/><mass value="%g"/>
  <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
 %s
 <gazebo><plugin name="ft_sensor" filename="libgazebo_ros_ft_sensor.so">%s</plugin></gazebo>
</robot>""" % ((ft_type,) + JOINT_RPY + (axis,) + COM + INERTIAL_RPY + (MASS, keep, plugin))


PLUGIN = '<updateRate>100.0</updateRate><topicName>ft_sensor_topic</topicName><jointName>ft</jointName>'


def expected():
    """Statics: the joint holds the weight, m g up in the world, in the child's axes; about the joint
    (the child's origin) it also holds the weight's moment, r_com x F."""
    q = rpy_to_quaternion(*JOINT_RPY)
    force = rotate_back(q, (0.0, 0.0, MASS * G))
    return force, cross(COM, force)


def test_moving_a_wrench_from_the_centre_of_mass_to_the_link_origin():
    q = rpy_to_quaternion(0.0, 0.0, 0.5)
    f, t = wrench_at_link_origin((1.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), q)
    assert f == pytest.approx(rotate(q, (1.0, 0.0, 0.0)))
    assert t == pytest.approx(cross((0.0, 0.0, 1.0), f))


def spawn(tmp_path, plugin=PLUGIN, namespace='/', **kw):
    w = PluginWorld(tmp_path)
    w.spawn('arm', arm(plugin, **kw), namespace)
    return w


def test_a_hanging_weight_reads_its_statics_in_the_child_frame(tmp_path):
    w = spawn(tmp_path, namespace='/robot')
    try:
        pub = w.fake.publishers['/robot/ft_sensor_topic']  # no robotNamespace element: the spawn request's
        w.run(0.05)
        assert pub.messages == []  # nobody listens: nothing
        pub.connections = 1
        w.run(0.5)
        msg = pub.messages[-1]
        assert msg.header.frame_id == 'tool'
        force, torque = expected()
        f, t = msg.wrench.force, msg.wrench.torque
        assert (f.x, f.y, f.z) == pytest.approx(force, abs=0.02)
        assert (t.x, t.y, t.z) == pytest.approx(torque, abs=0.005)
        assert abs(torque[1]) > 0.1 and abs(force[1]) > 5  # the case tells frames and moment arms apart
    finally:
        w.close()


def test_rate_stamps_namespace_and_noise(tmp_path):
    plugin = ('<robotNamespace>arm_ns</robotNamespace><gaussianNoise>0.5</gaussianNoise>'
              '<topicName>ft</topicName><jointName>ft</jointName><updateRate>50</updateRate>')
    w = spawn(tmp_path, plugin)
    try:
        pub = w.fake.publishers['/arm_ns/ft']
        pub.connections = 1
        w.run(0.3)
        stamps = [m.header.stamp.to_sec() for m in pub.messages]
        assert stamps[:3] == pytest.approx([0.02, 0.04, 0.06])  # the clock starts at 0: first at one period
        w.run(4.0)
        recent = pub.messages[-150:]
        fz = [m.wrench.force.z for m in recent]
        assert statistics.pstdev(fz) == pytest.approx(0.5, rel=0.25)
        assert statistics.mean(fz) == pytest.approx(expected()[0][2], abs=0.15)
    finally:
        w.close()


@pytest.mark.parametrize('plugin, kw, reason', [
    ('<topicName>ft</topicName>', {}, '<jointName> is missing'),
    ('<jointName>ft</jointName>', {}, '<topicName> is missing'),
    ('<topicName>ft</topicName><jointName>nope</jointName>', {}, 'is not a joint of the model'),
    ('<topicName>ft</topicName><jointName>ft</jointName>', {'preserve': False}, 'preserveFixedJoint'),
    ('<topicName>ft</topicName><jointName>mount</jointName>', {}, 'preserveFixedJoint'),
])
def test_refused(tmp_path, plugin, kw, reason):
    w = spawn(tmp_path, plugin, **kw)
    try:
        assert w.errors(reason), w.fake.logs
        assert not w.fake.publishers
    finally:
        w.close()
