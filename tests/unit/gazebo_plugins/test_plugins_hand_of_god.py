"""gazebo_ros_hand_of_god on a real Simulator: a free box (no contact) pulled to the tf frame hog_desired. The
wrench it adds is upstream's law, read back exactly through gazebo_ros_f3d listed after it; the box floats
(gravity off), settles on the frame (critically damped), and world -> hog_actual is its pose."""
import math

import pytest
from geometry_msgs.msg import TransformStamped
from tf2_msgs.msg import TFMessage

from racebot_sim_bridge.gazebo_plugins.gazebo_ros_hand_of_god import hand_of_god_wrench, quaternion_log, rotation_of
from racebot_sim_bridge.gazebo_plugins.link_motion import link_motion
from racebot_sim_bridge.kinematics.rotations import matrix, quaternion_multiply, rotate, rpy_to_quaternion

from model_plugin_sim import PluginWorld

MASS, IXX = 2.0, 0.05
HOG = '<plugin name="hog" filename="libgazebo_ros_hand_of_god.so"><linkName>box</linkName>%s</plugin>'
F3D = '<plugin name="f3d" filename="libgazebo_ros_f3d.so"><bodyName>box</bodyName><topicName>f3d</topicName></plugin>'


def box(*plugins):
    return """<robot name="hog_box">
 <link name="box"><inertial><origin xyz="0.05 0 0"/><mass value="%g"/>
  <inertia ixx="%g" iyy="0.08" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
 <gazebo>%s</gazebo>
</robot>""" % (MASS, IXX, ''.join(plugins))


def spawn(tmp_path, *plugins):
    w = PluginWorld(tmp_path)
    robot = w.spawn('hog_box', box(*plugins), '/', (0.0, 0.0, 3.0))
    return w, robot


def desired(w, position, orientation, frame='hog_desired', static=False):
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id = 'world', frame
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = position
    r = t.transform.rotation
    r.x, r.y, r.z, r.w = orientation
    w.fake.subscribers['/tf_static' if static else '/tf'](TFMessage(transforms=[t]))


def test_the_wrench_added_is_upstreams_law(tmp_path):
    w, robot = spawn(tmp_path, HOG % '<kl>50</kl><ka>20</ka>', F3D)
    try:
        goal = ((0.6, -0.4, 3.5), rpy_to_quaternion(0.3, -0.2, 0.8))
        desired(w, *goal)
        pub = w.fake.publishers['/f3d']
        pub.connections = 1
        w.run(0.2)  # moving and turning: every term counts
        state = link_motion(w.sim.world, robot.body, 'box')
        w.run(0.001)
        f, t = pub.messages[-1].wrench.force, pub.messages[-1].wrench.torque
        cl, ca = 2 * math.sqrt(50 * MASS), 2 * math.sqrt(20 * IXX)
        force, torque = hand_of_god_wrench(*state, *goal, 50.0, 20.0, cl, ca)
        assert (f.x, f.y, f.z) == pytest.approx(force, rel=1e-9, abs=1e-9)
        assert (t.x, t.y, t.z) == pytest.approx(rotate(state[1], torque), rel=1e-9, abs=1e-9)  # in world axes
        assert math.hypot(*state[2]) > 0.1 and math.hypot(*state[3]) > 0.1
        # the law itself, by hand: kl (p* - p) - cl v
        assert force[0] == pytest.approx(50 * (0.6 - state[0][0]) - cl * state[2][0])
    finally:
        w.close()


def test_it_floats_settles_on_the_frame_and_sends_the_actual_pose(tmp_path):
    w, robot = spawn(tmp_path, HOG % '')
    try:
        goal = ((1.0, 0.5, 2.0), rpy_to_quaternion(0.0, 0.0, 2.0))
        desired(w, *goal, static=True)
        w.run(3.0)
        position, orientation, linear, angular = link_motion(w.sim.world, robot.body, 'box')
        assert position == pytest.approx(goal[0], abs=1e-3)
        turn = quaternion_multiply(goal[1], (-orientation[0], -orientation[1], -orientation[2], orientation[3]))
        assert 2 * math.asin(min(1.0, math.sqrt(sum(c * c for c in turn[:3])))) < 1e-3
        assert math.hypot(*linear) < 1e-3 and math.hypot(*angular) < 1e-3  # at rest: no gravity pulls it down
        tf = [t for m in w.fake.publishers['/tf'].messages for t in m.transforms]
        assert len(tf) == 3000  # every world update
        last = tf[-1]
        assert (last.header.frame_id, last.child_frame_id) == ('world', 'hog_actual')
        assert last.header.stamp.to_sec() == pytest.approx(3.0)
        assert last.transform.translation.x == pytest.approx(goal[0][0], abs=1e-3)
    finally:
        w.close()


def test_without_the_frame_it_logs_once_and_the_link_floats(tmp_path):
    w, robot = spawn(tmp_path, HOG % '<frameId>hand</frameId>')
    try:
        desired(w, (0.0, 0.0, 0.0), (0, 0, 0, 1))  # hog_desired: not the frame this plugin looks up
        w.run(0.5)
        assert len(w.errors('hand_desired')) == 1, w.fake.logs
        position, _, linear, _ = link_motion(w.sim.world, robot.body, 'box')
        assert position[2] == pytest.approx(3.0, abs=1e-6) and math.hypot(*linear) < 1e-6  # gravity off
        desired(w, (0.0, 0.0, 3.5), (0, 0, 0, 1), frame='hand_desired')
        w.run(0.2)
        assert link_motion(w.sim.world, robot.body, 'box')[0][2] > 3.1
        assert [t.child_frame_id for m in w.fake.publishers['/tf'].messages for t in m.transforms][-1] == 'hand_actual'
    finally:
        w.close()


def test_quaternion_maths_as_ignition():
    q = rpy_to_quaternion(0.2, -0.4, 1.1)
    assert rotation_of(matrix(q)) == pytest.approx(q)  # w > 0: the same sign
    big = rpy_to_quaternion(0.0, 0.0, 3.0)  # trace < 0: the other branch
    assert rotation_of(matrix(big)) == pytest.approx(big)
    half = quaternion_log(rpy_to_quaternion(0.0, 0.0, 0.5))
    assert half == pytest.approx((0.0, 0.0, 0.25))  # half the rotation vector, as upstream's Log


@pytest.mark.parametrize('plugin, reason', [
    ('<plugin name="p" filename="libgazebo_ros_hand_of_god.so"/>', '<linkName> is missing'),
    ('<plugin name="p" filename="libgazebo_ros_hand_of_god.so"><linkName>nope</linkName></plugin>',
     'is not a link of the model'),
])
def test_refused(tmp_path, plugin, reason):
    w, _ = spawn(tmp_path, plugin)
    try:
        assert w.errors(reason), w.fake.logs
    finally:
        w.close()
